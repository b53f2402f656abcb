//! Joint couplings at set-up: `q_b = r q_a + o` between two one-coordinate tree joints of the
//! same kind (revolute–revolute, rad; prismatic–prismatic, m), as one row of the multiplier
//! system each (`step::coupling` evaluates it).
//!
//! ```text
//! g = (q_b − r q_a − o)   held at the end of every stage:   g(q₁) = 0
//! ġ = q̇_b − r q̇_a = 0     the velocity row of the projection (∇t = (c ∇s − s ∇c)/(s² + c²))
//! ```
//!
//! A chain of couplings (`a → b → c`) is allowed; a joint follows at most one other, no joint
//! follows itself through a cycle (the rows would be dependent), and a loop-closing joint is
//! never coupled (its coordinate is not a tree coordinate). The initial state must satisfy the
//! coupling (the spec derives the follower's `q0`, `qd0`); rates that violate it are projected
//! with the loops' rates.

use super::def::{JointType, ModelDef};
use super::error::ModelError;
use super::runtime::{CouplingRt, DofRt, Model};

/// Largest initial defect `|q_b − r q_a − o|` accepted (rad or m, relative to `1 + |q_b|`).
const INITIAL_TOL: f64 = 1e-9;

/// The couplings of `def` as rows `row0, row0 + 1, …`, checked (kinds, cycles, the initial
/// coordinates; `model`'s joints must be assembled).
pub(crate) fn build(
    model: &Model,
    def: &ModelDef,
    row0: usize,
) -> Result<Vec<CouplingRt>, ModelError> {
    let nj = def.joints.len();
    let mut follows = vec![None; nj];
    let mut out = Vec::with_capacity(def.couplings.len());
    for (c, cd) in def.couplings.iter().enumerate() {
        let bad = |why: String| ModelError::Invalid(format!("coupling {c}: {why}"));
        if cd.a >= nj || cd.b >= nj || cd.a == cd.b {
            return Err(bad("needs two different joints of the model".into()));
        }
        let (ja, jb) = (&def.joints[cd.a], &def.joints[cd.b]);
        let one = |k: JointType| matches!(k, JointType::Revolute | JointType::Prismatic);
        if ja.kind != jb.kind || !one(ja.kind) {
            return Err(bad(format!(
                "joints '{}' ({}) and '{}' ({}) must both be revolute or both prismatic",
                ja.name,
                ja.kind.name(),
                jb.name,
                jb.kind.name()
            )));
        }
        if ja.loop_closing || jb.loop_closing {
            return Err(bad(format!(
                "joint '{}' closes a loop: only tree joints can be coupled",
                if ja.loop_closing { &ja.name } else { &jb.name }
            )));
        }
        if !(cd.ratio.is_finite() && cd.ratio != 0.0 && cd.offset.is_finite()) {
            return Err(bad(format!(
                "ratio must be finite and non-zero and offset finite (got {}, {})",
                cd.ratio, cd.offset
            )));
        }
        if follows[cd.b].is_some() {
            return Err(bad(format!(
                "joint '{}' already follows another joint",
                jb.name
            )));
        }
        follows[cd.b] = Some(cd.a);
        out.push(CouplingRt {
            a: cd.a,
            b: cd.b,
            ratio: cd.ratio,
            offset: cd.offset,
            row: row0 + c,
        });
    }
    // no cycle: following the leaders from any joint ends
    for start in 0..nj {
        let (mut j, mut n) = (start, 0);
        while let Some(a) = follows[j] {
            j = a;
            n += 1;
            if n > nj {
                return Err(ModelError::Invalid(format!(
                    "couplings: joint '{}' follows itself through a cycle of couplings",
                    def.joints[start].name
                )));
            }
        }
    }
    for c in &out {
        let (qa, qb) = (initial_coord(model, c.a), initial_coord(model, c.b));
        let defect = qb - c.ratio * qa - c.offset;
        if defect.abs() > INITIAL_TOL * (1.0 + qb.abs()) {
            return Err(ModelError::Invalid(format!(
                "coupling of '{}' to '{}': the initial q = {qb} differs from ratio · q_a + offset = {}",
                def.joints[c.b].name,
                def.joints[c.a].name,
                c.ratio * qa + c.offset
            )));
        }
    }
    Ok(out)
}

/// The initial coordinate of one-coordinate joint `j` (rad, unwrapped; m).
fn initial_coord(model: &Model, j: usize) -> f64 {
    let jt = &model.joints[j];
    match &jt.dofs[0] {
        DofRt::Turn(_) => model.angles0[jt.turn0],
        DofRt::Slide(row) => {
            let qa = super::joint::body_nodes(&model.q0, jt.parent);
            let qb = super::joint::body_nodes(&model.q0, Some(jt.child));
            row.eval(&qa, &qb)
        }
    }
}

/// Whether the initial rates violate a coupling (`|q̇_b − r q̇_a| > 1e-12 (1 + |q̇_b|)`).
pub(crate) fn rates_violated(model: &Model) -> bool {
    model.couplings.iter().any(|c| {
        let rate = |j: usize| {
            let jt = &model.joints[j];
            let qa = super::joint::body_nodes(&model.q0, jt.parent);
            let qb = super::joint::body_nodes(&model.q0, Some(jt.child));
            let va = super::joint::body_nodes(&model.v0, jt.parent);
            let vb = super::joint::body_nodes(&model.v0, Some(jt.child));
            let mut out = [0.0];
            jt.geom.rates(&qa, &qb, &va, &vb, &mut out);
            out[0]
        };
        let (wa, wb) = (rate(c.a), rate(c.b));
        (wb - c.ratio * wa).abs() > 1e-12 * (1.0 + wb.abs())
    })
}
