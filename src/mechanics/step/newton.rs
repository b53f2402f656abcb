//! Residual and analytic Jacobian of one energy–momentum step, and the Newton iteration.
//!
//! Unknowns per iteration: per body `x_b = (δφ, δθ)` with `φ ← φ + δφ`, `dᵢ ← exp(δθ̂) dᵢ`
//! (orthonormality holds identically), per active joint row the scaled multiplier
//! `μ = h² λ / 2`. Residuals (theory.md §4.4–4.5, scaled by `h²/2`):
//!
//! ```text
//! R̃ = M (q − qₙ − h vₙ) − (h²/2) F(q̄) + Σ_k μ_k ∇g_k(q̄)      (12 per body, node form)
//! r_b = [R̃_φ ; Σᵢ d̄ᵢ × R̃_{dᵢ}] − (h²/2) [0 ; m_b]            (6 per body, P_int(q̄)ᵀ R̃)
//! g_k(q) = 0                                                   (per active row)
//! ```
//!
//! with consistent torques `m_b` entering the projected moment row directly (for any basis
//! `Σᵢ d̄ᵢ × ½ m × d̄ⁱ = m`). Jacobian: `P(q̄)ᵀ K̃ Q + ½ Σᵢ hat(R̃_{dᵢ}) hat(dᵢ)` with
//! `K̃ = M + ½ Σ μ_k H_k − (h²/2) ∂F/∂q`, multiplier columns `P(q̄)ᵀ ∇g(q̄)`, joint rows
//! `∇g(q) Q`, `Q = [I 0; 0 −d̂₁; 0 −d̂₂; 0 −d̂₃]`. Exact for inertia, constraints, gravity,
//! body loads, slide forces/springs/dampers, joint torques through `n̄(q̄)` and angle
//! springs/dampers (the `atan2` discrete gradient of `turn`; checked against finite differences
//! in the unit tests, also for a joint nearly at rest) and the spherical joint's damper (through
//! the exact `∂θ/∂ε` of `turn::theta_jac`).
//!
//! Round-off: the velocity recursion `v_{n+1} = vₙ + 2a/h` (`a = Δq − h vₙ`, one fused
//! rounding) is carried in double-double (`Work::vlo`), so that the energy does not drift by a
//! few ulps per step; conservation over 10⁴ steps stays at 1e-14–1e-13.
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use super::body_terms::project_bodies;
use super::contact::contact_forces;
pub(crate) use super::increment::{resolve, solve, update};
pub(crate) use super::joint_loads::apply_joint;
use super::joint_loads::{joint_loads, loaded, Acc, Pair};
use super::work::ContactJacobian;
pub(crate) use super::work::{Held, Mode, Norms, Work};
use crate::math::Vec3;
use crate::mechanics::model::constraint::body_nodes;
use crate::mechanics::model::constraint::{read3, write3};
use crate::mechanics::model::runtime::Model;
use crate::mechanics::model::sink::Sink;
use crate::mechanics::model::sparse_row::Side;

/// Evaluates the residual at the iterate `ws.q` (and, in [`Mode::Full`], the Jacobian) into
/// the sink; the right-hand side stored is `−r`. The work account, the angles and the rotation
/// increments of the accepted iterate are `finish`'s.
#[allow(clippy::too_many_lines)]
pub(crate) fn evaluate(model: &Model, ws: &mut Work, held: &Held, h: f64, mode: Mode) -> Norms {
    let jac = mode == Mode::Full;
    let hh = 0.5 * h * h;
    ws.set_midpoint();
    match mode {
        Mode::Full if model.dense => {
            ws.dense.fill(0.0);
            ws.drhs.fill(0.0);
        }
        Mode::Full => {
            ws.blocks.iter_mut().for_each(|b| b.clear());
            ws.border.clear();
        }
        // the matrices may hold factors: only the right-hand sides are rebuilt
        Mode::Residual if model.dense => ws.drhs.fill(0.0),
        Mode::Residual => {
            ws.blocks.iter_mut().for_each(|b| b.r.fill(0.0));
            ws.border.rc.fill(0.0);
        }
    }
    inertia_and_forces(model, ws, held, h, jac);
    if !model.contact.is_empty() && ws.contact_jacobian != ContactJacobian::Off {
        contact_forces(model, ws, h, jac);
    }
    // joint rows: μ ∇g(q̄) into R̃, g(q) residual, Jacobian columns/rows and node couplings
    let mut res = 0.0_f64;
    let gscale = 1.0 / model.lc.min(1.0);
    let mut sink_dense = std::mem::take(&mut ws.dense);
    let mut sink_blocks = std::mem::take(&mut ws.blocks);
    let mut sink_drhs = std::mem::take(&mut ws.drhs);
    let mut sink_border = std::mem::take(&mut ws.border);
    let nd = sink_drhs.len();
    {
        let mut sink = Sink {
            model,
            blocks: &mut sink_blocks,
            border: &mut sink_border,
            dense: &mut sink_dense,
            drhs: &mut sink_drhs,
            nd,
        };
        // what one joint adds (node forces, node coupling C_AB and extra blocks; cleared per
        // joint)
        let mut acc = Acc::new();
        // scratch of the compact gradients at q̄ and q (entries beyond a row's nodes unused)
        let (mut buf, mut buf1) = ([Vec3::zeros(); 8], [Vec3::zeros(); 8]);
        for (j, jt) in model.joints.iter().enumerate() {
            let p = Pair::new(ws, jt.parent, jt.child);
            let (a, bb) = (p.a, p.b);
            let (qa_bar, qb_bar, qa, qb) = (&p.qa_bar, &p.qb_bar, &p.qa, &p.qb);
            let (dbar_a, dbar_b, d_a, d_b) = (&p.dbar_a, &p.dbar_b, &p.d_a, &p.d_b);
            acc.clear(jac);
            for (k, sr) in jt.sparse.iter().enumerate() {
                let mu = ws.mu[jt.row0 + k];
                // compact ∇g(q̄) over the row's non-zero nodes (see `SparseRow`)
                let grad = sr.grad_at(qa_bar, qb_bar, &mut buf);
                sr.add_forces(grad, mu, &mut acc.fa, &mut acc.fb);
                if jac {
                    sr.add_hessian(0.5 * mu, &mut ws.cbody, a, bb, &mut acc.cab);
                }
                // u, w at the iterate once: the value and the gradient ∇g(q)
                let (u1, w1) = sr.uw(qa, qb);
                let gv = sr.value(&u1, &w1);
                res = res.max(gv.abs() * gscale);
                sink.rhs_row(j, k, -gv);
                if jac {
                    // multiplier columns P̄ᵀ∇g(q̄) (skipped where the row is zero)
                    if let Some(col) = sr.project(grad, Side::B, dbar_b) {
                        sink.body_mu(bb, j, k, &col);
                    }
                    if let (Some(a), Some(col)) = (a, sr.project(grad, Side::A, dbar_a)) {
                        sink.body_mu(a, j, k, &col);
                    }
                    // joint rows ∇g(q) Q
                    let g1 = sr.grad(&u1, &w1, &mut buf1);
                    if let Some(row) = sr.project(g1, Side::B, d_b) {
                        sink.mu_body(j, k, bb, &row);
                    }
                    if let (Some(a), Some(row)) = (a, sr.project(g1, Side::A, d_a)) {
                        sink.mu_body(j, k, a, &row);
                    }
                }
            }
            // joint loads on the coordinates (actuators, springs, dampers); nothing to do for
            // a joint without any, the common case in a chain
            if loaded(model, held, j) {
                joint_loads(model, ws, held, j, h, jac, &p, &mut acc);
            }
            if apply_joint(ws, &p, &mut acc, jac) {
                if let Some(a) = a {
                    sink.body_body(a, bb, &acc.x_ab);
                    sink.body_body(bb, a, &acc.x_ba);
                }
            }
        }
        if !model.couplings.is_empty() {
            res = res.max(super::coupling::couplings(model, ws, jac, &mut sink));
        }
    }
    ws.dense = sink_dense;
    ws.blocks = sink_blocks;
    ws.drhs = sink_drhs;
    ws.border = sink_border;
    res = res.max(project_bodies(model, ws, held, hh, mode, nd));
    Norms { res }
}

/// Sets `ws.hv`, `ws.hv_lo` for a stage of size `h` from its start velocities: `h vₙ` rounded,
/// and the rest of `h (vₙ + v_lo)` (the product's rounding error, exact by [`product_error`],
/// plus `h v_lo`). An evaluation's `a = Δq − h vₙ` is then `(Δq − hv) − hv_lo`: `Δq − hv` is
/// exact while `Δq` is within a factor 2 of `h vₙ` (Sterbenz), so `a` carries about one
/// rounding of its own size, as one fused multiply-add per evaluation would.
pub(crate) fn stage_rates(ws: &mut Work, h: f64) {
    let hs = split(h);
    let rates = ws.vn.iter().zip(&ws.vlo);
    for ((hv, hv_lo), (&v, &vlo)) in ws.hv.iter_mut().zip(ws.hv_lo.iter_mut()).zip(rates) {
        let p = h * v;
        *hv = p;
        *hv_lo = product_error(hs, split(v), p) + h * vlo;
    }
}

/// Veltkamp's split `a = hi + lo` into halves of 26 significant bits (exact).
#[inline]
fn split(a: f64) -> (f64, f64) {
    let t = 134_217_729.0 * a; // 2²⁷ + 1
    let hi = t - (t - a);
    (hi, a - hi)
}

/// Dekker's exact rounding error `a b − p` of the product `p = fl(a b)` from the splits of `a`
/// and `b` (the value a fused multiply-add `a·b − p` gives, without the library call the
/// baseline x86-64 target makes of it).
#[inline]
fn product_error(a: (f64, f64), b: (f64, f64), p: f64) -> f64 {
    ((a.0 * b.0 - p) + a.0 * b.1 + a.1 * b.0) + a.1 * b.1
}

/// The inertia and gravity terms of every body's node residual `ws.rn` (and `ws.acc`; in a
/// Jacobian pass its node coupling `ws.cbody`, cleared `ws.xbody`), joint torques `ws.mom`
/// cleared, and the body forces.
pub(crate) fn inertia_and_forces(model: &Model, ws: &mut Work, held: &Held, h: f64, jac: bool) {
    let nb = model.bodies.len();
    let hh = 0.5 * h * h;
    let g = model.def().gravity;
    // body inertia and applied forces, node form
    for b in 0..nb {
        let br = &model.bodies[b];
        ws.set_acc(b);
        let dq = body_nodes(&ws.acc, b);
        let mut r = [Vec3::zeros(); 4];
        r[0] = dq[0] * br.mass - g * (hh * br.mass);
        for i in 0..3 {
            r[i + 1] = dq[1] * br.e[(i, 0)] + dq[2] * br.e[(i, 1)] + dq[3] * br.e[(i, 2)];
        }
        for k in 0..4 {
            write3(&mut ws.rn, 12 * b + 3 * k, &r[k]);
        }
        if jac {
            let c = &mut ws.cbody[b];
            c.fill(0.0);
            if ws.inertia_in_jacobian {
                c[0] = br.mass;
                for i in 0..3 {
                    for j in 0..3 {
                        c[4 * (i + 1) + j + 1] = br.e[(i, j)];
                    }
                }
            }
            ws.xbody[b].fill(0.0);
        }
        write3(&mut ws.mom, 3 * b, &Vec3::zeros());
    }
    for &(b, at) in &model.body_forces {
        let f = Vec3::new(held.inputs[at], held.inputs[at + 1], held.inputs[at + 2]);
        let r = read3(&ws.rn, 12 * b) - f * hh;
        write3(&mut ws.rn, 12 * b, &r);
    }
}

#[cfg(test)]
#[path = "newton_tests.rs"]
pub(crate) mod tests;
