//! Per-body terms of the Newton residual and Jacobian: the projection `P̄ᵀ R̃` of the node
//! residual onto the body's six rows, applied body torques, the scaled residual norm and the
//! diagonal Jacobian block `P̄ᵀ (C ⊗ I) Q + ½ Σᵢ hat(R̃_{dᵢ}) hat(dᵢ)`.
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use super::work::{Held, Mode, Work};
use crate::math::{Mat3, Vec3};
use crate::mechanics::model::constraint::body_nodes;
use crate::mechanics::model::constraint::read3;
use crate::mechanics::model::kernels::{node_block, project};
use crate::mechanics::model::runtime::Model;
use crate::mechanics::model::sink::Sink;

/// Projects the node residual `ws.rn` of every body onto its six rows (right-hand side `−r`
/// into the tree blocks or the dense system), adds the body torques
/// and, in [`Mode::Full`], the diagonal Jacobian blocks. Returns the largest scaled body
/// residual.
#[allow(clippy::too_many_arguments)]
pub(crate) fn project_bodies(
    model: &Model,
    ws: &mut Work,
    held: &Held,
    hh: f64,
    mode: Mode,
    nd: usize,
) -> f64 {
    let jac = mode == Mode::Full;
    let mut res = 0.0_f64;
    for b in 0..model.bodies.len() {
        let r = body_rows(model, ws, held, hh, b, jac);
        let (fs, ms) = (model.bodies[b].fs, model.bodies[b].ms);
        for k in 0..3 {
            res = res.max((r[k] * fs).abs()).max((r[3 + k] * ms).abs());
        }
        if model.dense {
            for k in 0..6 {
                ws.drhs[6 * b + k] = -r[k];
            }
        } else {
            for k in 0..6 {
                ws.blocks[b].r[k] = -r[k];
            }
        }
        if jac {
            let blk = ws.xbody[b];
            let mut sink = Sink {
                model,
                blocks: &mut ws.blocks,
                border: &mut ws.border,
                dense: &mut ws.dense,
                drhs: &mut ws.drhs,
                nd,
            };
            sink.body_body(b, b, &blk);
        }
    }
    res
}

/// The six rows `r_b = P̄ᵀ R̃_b` of body `b` (projected node residual `ws.rn`, joint torques
/// `ws.mom`, body torques) and, if `jac`, its diagonal Jacobian block completed in place in
/// `ws.xbody[b]` (row-major 6 × 6).
pub(crate) fn body_rows(
    model: &Model,
    ws: &mut Work,
    held: &Held,
    hh: f64,
    b: usize,
    jac: bool,
) -> [f64; 6] {
    let qbar = body_nodes(&ws.qbar, b);
    let dbar = [qbar[1], qbar[2], qbar[3]];
    let rnode: [Vec3; 4] = std::array::from_fn(|k| read3(&ws.rn, 12 * b + 3 * k));
    let mut r = project(&rnode, &dbar);
    for k in 0..3 {
        r[3 + k] += ws.mom[3 * b + k];
    }
    for &(tb, at) in &model.body_torques {
        if tb != b {
            continue;
        }
        let m = Vec3::new(held.inputs[at], held.inputs[at + 1], held.inputs[at + 2]);
        let applied = if model.naive_torque {
            let mut c = Mat3::zeros();
            for d in &dbar {
                c += d * d.transpose();
            }
            (Mat3::identity() * c.trace() - c) * m * 0.5
        } else {
            m
        };
        for k in 0..3 {
            r[3 + k] -= hh * applied[k];
        }
    }
    if jac {
        let q = body_nodes(&ws.q, b);
        let d = [q[1], q[2], q[3]];
        // the extra terms complete to the diagonal block in place (zeroed every Full pass)
        let blk = &mut ws.xbody[b];
        node_block(&ws.cbody[b], &dbar, &d, blk);
        // derivative of the projection: ½ Σ hat(R̃_{dᵢ}) hat(dᵢ)
        // (hat(r) hat(d) = d rᵀ − (r·d) I)
        let mut pm = Mat3::zeros();
        let mut tr = 0.0;
        for i in 0..3 {
            pm += d[i] * rnode[i + 1].transpose();
            tr += rnode[i + 1].dot(&d[i]);
        }
        for rr in 0..3 {
            pm[(rr, rr)] -= tr;
            for s in 0..3 {
                blk[(rr + 3) * 6 + 3 + s] += 0.5 * pm[(rr, s)];
            }
        }
    }
    r
}
