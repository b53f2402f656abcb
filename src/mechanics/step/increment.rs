//! Solution of the assembled Newton system (tree elimination, bordered for loop-closing joints;
//! the dense LU only as the test oracle) and the update of the iterate: `φ ← φ + δφ`,
//! `dᵢ ← exp(δθ̂) dᵢ` (accumulated as increments), `μ ← μ + δμ`.

use super::work::Work;
use crate::math::Vec3;
use crate::mechanics::linalg::tree::{lu_factor, lu_solve, solve_factored, solve_tree};
use crate::mechanics::model::constraint::{read3, write3};
use crate::mechanics::model::kernels::expm1_so3;
use crate::mechanics::model::runtime::Model;

/// Factors the assembled iteration matrix and solves for the assembled right-hand side; the
/// solution replaces the right-hand side (every `ws.blocks[b].r` and the loop rows'
/// `ws.border.rc`, or `ws.drhs` for the dense oracle) and the factors are kept (the tree blocks'
/// `d` and `u` and the border's, or `ws.dense`/`ws.dpiv`) for [`resolve`]. False if the matrix
/// is singular (the factors are then unusable).
pub(crate) fn solve(model: &Model, ws: &mut Work) -> bool {
    if model.dense {
        let n = ws.drhs.len();
        if !lu_factor(&mut ws.dense, n, n, &mut ws.dpiv, 1e-14) {
            return false;
        }
        lu_solve(&ws.dense, n, n, &ws.dpiv, &mut ws.drhs);
        true
    } else if ws.border.is_active() {
        ws.border
            .factor_solve(&mut ws.blocks, &model.order, &model.parent)
    } else {
        solve_tree(&mut ws.blocks, &model.order, &model.parent)
    }
}

/// Solves for a new right-hand side with the factors kept by the last successful [`solve`]
/// (chord Newton iterations): the right-hand side is read from, and the solution written to,
/// every `ws.blocks[b].r` and `ws.border.rc` (or `ws.drhs`, dense oracle); only the right-hand
/// side may have been re-assembled since. Always succeeds (the factors were checked by [`solve`]);
/// returns true for symmetry with it.
pub(crate) fn resolve(model: &Model, ws: &mut Work) -> bool {
    if model.dense {
        let n = ws.drhs.len();
        lu_solve(&ws.dense, n, n, &ws.dpiv, &mut ws.drhs);
    } else if ws.border.is_active() {
        ws.border
            .resolve(&mut ws.blocks, &model.order, &model.parent);
    } else {
        solve_factored(&mut ws.blocks, &model.order, &model.parent);
    }
    true
}

/// Applies the Newton update; returns the scaled update norm of the body unknowns and that of
/// the multipliers (`|δμ|` times the largest residual scale of the child body, force or moment
/// row with a lever of `max(1, lc)`, i.e. the size of its effect on the scaled residual).
pub(crate) fn update(model: &Model, ws: &mut Work) -> (f64, f64) {
    let nb = model.bodies.len();
    let mut upd = 0.0_f64;
    for b in 0..nb {
        let x: [f64; 6] = if model.dense {
            std::array::from_fn(|k| ws.drhs[6 * b + k])
        } else {
            std::array::from_fn(|k| ws.blocks[b].r[k])
        };
        let dphi = Vec3::new(x[0], x[1], x[2]);
        let dth = Vec3::new(x[3], x[4], x[5]);
        upd = upd.max(dphi.norm() / model.lc).max(dth.norm());
        let inc = read3(&ws.dq, 12 * b) + dphi;
        write3(&mut ws.dq, 12 * b, &inc);
        write3(&mut ws.q, 12 * b, &(read3(&ws.qn, 12 * b) + inc));
        let em1 = expm1_so3(&dth);
        for i in 0..3 {
            let o = 12 * b + 3 + 3 * i;
            let inc = read3(&ws.dq, o) + em1 * read3(&ws.q, o);
            write3(&mut ws.dq, o, &inc);
            write3(&mut ws.q, o, &(read3(&ws.qn, o) + inc));
        }
    }
    let mut dmu = 0.0_f64;
    for (j, jt) in model.joints.iter().enumerate() {
        let br = &model.bodies[jt.child];
        let scale = br.fs.max(model.lc.max(1.0) * br.ms);
        for k in 0..jt.rows.len() {
            let dm = if model.dense {
                ws.drhs[6 * nb + jt.row0 + k]
            } else if let Some(l) = ws.border.lrow[j] {
                ws.border.rc[l + k]
            } else {
                ws.blocks[jt.child].r[6 + k]
            };
            ws.mu[jt.row0 + k] += dm;
            dmu = dmu.max(dm.abs() * scale);
        }
    }
    // coupling rows, always in the border (after the joints' row groups)
    for (c, cp) in model.couplings.iter().enumerate() {
        let br = &model.bodies[model.joints[cp.b].child];
        let scale = br.fs.max(model.lc.max(1.0) * br.ms);
        let dm = coupling_entry(model, ws, c);
        ws.mu[cp.row] += dm;
        dmu = dmu.max(dm.abs() * scale);
    }
    (upd, dmu)
}

/// The solution entry of coupling `c`'s multiplier after a solve (always in the border; the
/// dense oracle's after the joints' rows).
pub(crate) fn coupling_entry(model: &Model, ws: &Work, c: usize) -> f64 {
    if model.dense {
        ws.drhs[6 * model.bodies.len() + model.couplings[c].row]
    } else {
        ws.border.lrow[model.joints.len() + c].map_or(0.0, |l| ws.border.rc[l])
    }
}
