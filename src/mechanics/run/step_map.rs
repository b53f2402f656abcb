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
//! ground contact, joint friction: x = (q, ν, σ) as for A, B (`model::sticking`): a contact
//!   bristle state σ's column moves its point's bristle along its axis t (δs = t), its row
//!   reads t·δs at the end; a joint's moves its bristle; the same points must touch at both
//!   ends (else refused by name)
//! ```

use super::operating::Operating;
use super::state::State;
use crate::mechanics::model::loop_closure::Independent;
use crate::mechanics::model::minimal::NodalColumns;
use crate::mechanics::model::runtime::Model;
use crate::mechanics::step::tangent::Tangent;
use crate::mechanics::step::tangent_state::ground_points;
use nalgebra::DMatrix;

/// The discrete-time linear model of one communication step `δx(t+h) = Ad δx(t) + Bd δu`.
#[derive(Clone, Debug)]
pub struct StepMap {
    /// `∂x(t+h)/∂x(t)`, 2n + s × 2n + s (`s` contact bristle states; closed loops: 2k × 2k).
    pub ad: DMatrix<f64>,
    /// `∂x(t+h)/∂u`, 2n + s × (every input of the model, in `Model::inputs` order).
    pub bd: DMatrix<f64>,
    /// `x(t+h)` (the rotation-vector coordinates 0: about the end's own orientations).
    pub x1: Vec<f64>,
}

/// Starts carrying the step's tangent map in `state` from its operating point (module docs),
/// closed loops in the independent coordinates `pick`; returns the coordinates to read off at
/// the end ([`Independent::Coords`] of those picked).
///
/// # Errors
/// Why the model has no minimal coordinates here (a sliding bristle, contact or friction with
/// closed loops, friction on a spherical joint), or a pick that is not independent here.
pub fn begin_step_map(
    model: &Model,
    state: &mut State,
    pick: &Independent,
) -> Result<Independent, String> {
    if let Some(j) = model
        .joints
        .iter()
        .position(|j| j.friction.is_some() && j.sph_axes.is_some())
    {
        return Err(format!(
            "joint '{}' is spherical with friction: its bristles are no states of the linear \
             model",
            model.def().joints[j].name
        ));
    }
    let op = Operating::picked(model, state, pick).map_err(|e| e.to_string())?;
    let axes = op.dynamics.sticking().contact_axes();
    let fric = op.dynamics.sticking().joint_bristles();
    let nc = axes.len();
    let ns = nc + fric.len();
    let (n, m) = ((op.x().len() - ns) / 2, model.inputs.len());
    let nb = model.bodies.len();
    // the bristles' and the inputs' columns follow the embedding's in the same buffers (trees)
    let spare = if op.loops.is_none() { ns + m } else { 0 };
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
    let cols = 2 * n + ns + m;
    let mut xi = emb.xi;
    xi.resize(6 * nb * cols, 0.0);
    let mut dv = emb.dv;
    dv.resize(12 * nb * cols, 0.0);
    let mut du = vec![0.0; m * cols];
    for i in 0..m {
        du[(2 * n + ns + i) * m + i] = 1.0;
    }
    // a bristle state σ moves its point's bristle along its axis
    let ng = ground_points(model);
    let mut ds = vec![0.0; 3 * ng * cols];
    for (j, (k, axis)) in axes.iter().enumerate() {
        let at = (2 * n + j) * 3 * ng + 3 * k;
        ds[at..at + 3].copy_from_slice(axis.as_slice());
    }
    let mut dw = vec![0.0; na * cols];
    for c in 0..2 * n {
        for r in 0..na {
            dw[c * na + r] = dw_x[(r, c)];
        }
    }
    // a joint bristle state moves its bristle
    let nf = model.nfric;
    let mut df = vec![0.0; nf * cols];
    for (j, &i) in fric.iter().enumerate() {
        df[(2 * n + nc + j) * nf + i] = 1.0;
    }
    let mut tangent = Tangent::new(model, cols, (xi, dv), du, (dw, ds, df));
    tangent.touching = op.dynamics.sticking().touching();
    state.ws.tangent = Some(Box::new(tangent));
    Ok(end)
}

/// Stops carrying the tangent map and reads it off at `state` (the end of the step), closed
/// loops in the coordinates `pick` (those [`begin_step_map`] returned).
///
/// # Errors
/// No tangent was carried, no minimal coordinates, a singular mass matrix, two bodies' shapes
/// touched during the step, or the touching ground points changed.
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
    if let Some(why) = &tangent.inexact {
        return Err(format!(
            "{why} during the step: the step's tangent map covers ground contact only"
        ));
    }
    let end = Operating::picked(model, state, pick).map_err(|e| e.to_string())?;
    let axes = end.dynamics.sticking().contact_axes();
    let touching = end.dynamics.sticking().touching();
    if touching != tangent.touching {
        let shapes = &model.def().contact.shapes;
        let names = |s: &[usize]| {
            let mut v: Vec<&str> = model.contact.ground.as_ref().map_or(Vec::new(), |g| {
                s.iter()
                    .map(|k| shapes[g.points[*k].shape].name.as_str())
                    .collect()
            });
            v.dedup();
            if v.is_empty() {
                "none".to_string()
            } else {
                v.join(", ")
            }
        };
        return Err(format!(
            "the ground points that touch change over the step (shapes touching at its start: \
             {}; at its end: {}): Ad, Bd would have different bristle states at its two ends; \
             take a shorter --step or a point where the contacts stay",
            names(&tangent.touching),
            names(&touching)
        ));
    }
    let fric = end.dynamics.sticking().joint_bristles();
    let x1 = end.x();
    let (nc, nf) = (axes.len(), model.nfric);
    let ns = nc + fric.len();
    let n = (x1.len() - ns) / 2;
    // the columns are stored as the read-off takes them (column-major)
    let Tangent {
        cols,
        xi,
        dv,
        ds,
        df,
        ..
    } = *tangent;
    let ng = ground_points(model);
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
    // the bristle states' rows: each state's axis on its point's bristle column
    let mut full = DMatrix::zeros(2 * n + ns, cols);
    full.rows_mut(0, 2 * n).copy_from(&dx);
    for (j, (k, axis)) in axes.iter().enumerate() {
        for c in 0..cols {
            let at = c * 3 * ng + 3 * k;
            full[(2 * n + j, c)] = axis.dot(&crate::math::Vec3::from_column_slice(&ds[at..at + 3]));
        }
    }
    for (j, &i) in fric.iter().enumerate() {
        for c in 0..cols {
            full[(2 * n + nc + j, c)] = df[c * nf + i];
        }
    }
    let nx = 2 * n + ns;
    Ok(StepMap {
        ad: full.columns(0, nx).into_owned(),
        bd: full.columns(nx, cols - nx).into_owned(),
        x1,
    })
}
