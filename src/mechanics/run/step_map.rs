//! The discrete-time linear model of a run's communication step: the step's tangent map
//! (`step::tangent`) started from the embedding's tangent of the operating point and read off
//! in minimal coordinates at the end (`model::minimal`).
//!
//! ```text
//! columns at the start:  ∂(ξ, δv)/∂x  (2n, the embedding),  δu = eⱼ  (one per input)
//! carried through every stage of every (sub-)step taken, then
//! [Ad Bd] = ∂x(t+h)/∂(x(t), u) = read-off tangent at the end × the columns
//! closed loops: x = (q_I, ν_I); the embedding's columns × ∂(q, ν)/∂x (2k), the read-off's
//!   rows of I (`model::minimal`, `model::loop_linear`), the same I at both ends
//! ```

use super::operating::Operating;
use super::state::State;
use crate::mechanics::model::loop_closure::Independent;
use crate::mechanics::model::minimal::NodalColumns;
use crate::mechanics::model::runtime::Model;
use crate::mechanics::step::tangent::Tangent;
use nalgebra::DMatrix;

/// The discrete-time linear model of one communication step `δx(t+h) = Ad δx(t) + Bd δu`.
#[derive(Clone, Debug)]
pub struct StepMap {
    /// `∂x(t+h)/∂x(t)`, 2n × 2n (closed loops: 2k × 2k).
    pub ad: DMatrix<f64>,
    /// `∂x(t+h)/∂u`, 2n × (every input of the model, in `Model::inputs` order).
    pub bd: DMatrix<f64>,
    /// `x(t+h)` (the rotation-vector coordinates 0: about the end's own orientations).
    pub x1: Vec<f64>,
}

/// Starts carrying the step's tangent map in `state` from its operating point (module docs),
/// closed loops in the independent coordinates `pick`; returns the coordinates to read off at
/// the end ([`Independent::Coords`] of those picked).
///
/// # Errors
/// Why the model has no minimal coordinates (contact, friction), or a pick that
/// is not independent here.
pub fn begin_step_map(
    model: &Model,
    state: &mut State,
    pick: &Independent,
) -> Result<Independent, String> {
    if !model.contact.is_empty() || model.nfric > 0 {
        return Err(
            "the step's tangent map does not cover contact and joint friction yet (A, B, C, D do)"
                .into(),
        );
    }
    let op = Operating::picked(model, state, pick).map_err(|e| e.to_string())?;
    let (n, m) = (op.x().len() / 2, model.inputs.len());
    let nb = model.bodies.len();
    // the inputs' columns follow the embedding's in the same buffers (trees)
    let spare = if op.loops.is_none() { m } else { 0 };
    let mut emb = op.dynamics.embed_tangent_spare(&op.q, &op.nu, spare);
    // the rotors' rates are their joints' rates: per tree column, the rotor of coordinate k
    // moves with the rate column of k
    let nt = op.dynamics.n();
    let na = model.narm;
    let mut dw_tree = DMatrix::zeros(na, 2 * nt);
    for (j, jt) in model.joints.iter().enumerate() {
        if jt.armature > 0.0 && jt.sph_axes.is_none() {
            if let Some(k0) = op.dynamics.joint_at(j) {
                for dk in 0..jt.dofs.len() {
                    dw_tree[(jt.arm0 + dk, nt + k0 + dk)] = 1.0;
                }
            }
        }
    }
    let (end, dw_x) = match &op.loops {
        Some(cl) => {
            let map = cl.embed_map(&op.dynamics, &op.q, &op.nu)?;
            emb = emb.times(&map);
            (Independent::Coords(cl.indep.clone()), dw_tree * map)
        }
        None => (Independent::Auto, dw_tree),
    };
    let cols = 2 * n + m;
    let mut xi = emb.xi;
    xi.resize(6 * nb * cols, 0.0);
    let mut dv = emb.dv;
    dv.resize(12 * nb * cols, 0.0);
    let mut du = vec![0.0; m * cols];
    for i in 0..m {
        du[(2 * n + i) * m + i] = 1.0;
    }
    let mut dw = vec![0.0; na * cols];
    for c in 0..2 * n {
        for r in 0..na {
            dw[c * na + r] = dw_x[(r, c)];
        }
    }
    state.ws.tangent = Some(Box::new(Tangent::new(model, cols, (xi, dv), du, dw)));
    Ok(end)
}

/// Stops carrying the tangent map and reads it off at `state` (the end of the step), closed
/// loops in the coordinates `pick` (those [`begin_step_map`] returned).
///
/// # Errors
/// No tangent was carried, no minimal coordinates, or a singular mass matrix.
pub fn finish_step_map(
    model: &Model,
    state: &mut State,
    pick: &Independent,
) -> Result<StepMap, String> {
    let tangent = state
        .ws
        .tangent
        .take()
        .ok_or("no step tangent was carried")?;
    let end = Operating::picked(model, state, pick).map_err(|e| e.to_string())?;
    let x1 = end.x();
    let n = x1.len() / 2;
    // the columns are stored as the read-off takes them (column-major)
    let Tangent { cols, xi, dv, .. } = *tangent;
    let nodal = NodalColumns { cols, xi, dv };
    let dx =
        end.dynamics
            .readoff_tangent(&end.q, &state.q, &state.v, &nodal, end.loops.as_ref())?;
    let dx = match &end.loops {
        Some(cl) => {
            let nt = end.q.len();
            let rows: Vec<usize> = cl
                .indep
                .iter()
                .copied()
                .chain(cl.indep.iter().map(|i| nt + i))
                .collect();
            dx.select_rows(&rows)
        }
        None => dx,
    };
    Ok(StepMap {
        ad: dx.columns(0, 2 * n).into_owned(),
        bd: dx.columns(2 * n, cols - 2 * n).into_owned(),
        x1,
    })
}
