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

use super::assemble::{read3, write3};
use super::body_terms::project_bodies;
use super::constraint::{DotRow, Nodes};
pub(crate) use super::increment::{resolve, solve, update};
pub(crate) use super::kernels::{body_nodes, expm1_so3, rotation_increment};
use super::kernels::{
    linvec_jac, node_block, outer, project, push_torque, row_q, torque_jac, Sink,
};
use super::model::{DofRt, Model};
use super::sparse_row::{Side, SparseRow};
use super::turn::{row_increment, theta_jac, turn_step};
pub(crate) use super::work::{Held, Norms, Work};
use crate::math::Vec3;

/// What one call of [`evaluate`] computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Mode {
    /// Residual (all rows, norms, work, right-hand side `−r`) and the analytic Jacobian: clears
    /// and fills the tree blocks (`d`, `u`, `l`, `r`) and the border, or the dense system
    /// (`dense`, `drhs`).
    Full,
    /// Everything [`Mode::Full`] computes for the right-hand side, bit for bit, but no
    /// Jacobian: zeroes and fills only the right-hand sides (`Block::r` of every block and the
    /// border's `rc`, or `drhs`); the matrices `d`, `u`, `l`, the border's and `dense` are left
    /// untouched (they may hold the
    /// factors of an earlier `Full` iteration, for chord iterations).
    Residual,
    /// Final pass at the converged iterate: no constraint rows; computes `a`, `θ`, the
    /// unwrapped angles and the work only.
    Final,
}

/// Evaluates the residual at the iterate `ws.q` (and, in [`Mode::Full`], the Jacobian) into
/// the sink; the right-hand side stored is `−r`. Also returns the step's discrete work in
/// `work_out`.
#[allow(clippy::too_many_lines)]
pub(crate) fn evaluate(
    model: &Model,
    ws: &mut Work,
    held: &Held,
    h: f64,
    mode: Mode,
    work_out: &mut f64,
) -> Norms {
    let jac = mode == Mode::Full;
    // the final pass (no Jacobian) only needs a, θ, the unwrapped angles and the work
    let final_pass = mode == Mode::Final;
    let nb = model.bodies.len();
    let hh = 0.5 * h * h;
    let g = model.def().gravity;
    let mut work = 0.0;
    for k in 0..ws.q.len() {
        ws.qbar[k] = ws.qn[k] + 0.5 * ws.dq[k];
    }
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
        Mode::Final => {}
    }
    // body inertia and applied forces, node form
    for b in 0..nb {
        let br = &model.bodies[b];
        let qn = body_nodes(&ws.qn, b);
        let q = body_nodes(&ws.q, b);
        // a = Δq − h vₙ with one rounding (fused multiply-add) plus the low part of vₙ
        for k in 12 * b..12 * b + 12 {
            ws.acc[k] = (-h).mul_add(ws.vn[k], ws.dq[k]) - h * ws.vlo[k];
        }
        let dq = body_nodes(&ws.acc, b);
        let mut r = [Vec3::zeros(); 4];
        r[0] = dq[0] * br.mass - g * (hh * br.mass);
        for i in 0..3 {
            r[i + 1] = dq[1] * br.e[(i, 0)] + dq[2] * br.e[(i, 1)] + dq[3] * br.e[(i, 2)];
        }
        for k in 0..4 {
            write3(&mut ws.rn, 12 * b + 3 * k, &r[k]);
        }
        let th = rotation_increment(&qn, &q);
        write3(&mut ws.theta, 3 * b, &th);
        if jac {
            let c = &mut ws.cbody[b];
            c.fill(0.0);
            c[0] = br.mass;
            for i in 0..3 {
                for j in 0..3 {
                    c[4 * (i + 1) + j + 1] = br.e[(i, j)];
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
        work += f.dot(&read3(&ws.dq, 12 * b));
    }
    // joint rows: μ ∇g(q̄) into R̃, g(q) residual, Jacobian columns/rows and node couplings
    let mut res = 0.0_f64;
    let gscale = 1.0 / model.lc.min(1.0);
    let zero: Nodes = [Vec3::zeros(); 4];
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
        // off-diagonal node coupling C_AB and extra blocks of one joint (Jacobian only, zeroed
        // per joint in Full mode)
        let mut cab = [0.0; 16];
        let mut x_ab = [0.0; 36];
        let mut x_ba = [0.0; 36];
        let mut x_aa = [0.0; 36];
        let mut x_bb = [0.0; 36];
        // scratch of the compact gradients at q̄ and q (entries beyond a row's nodes unused)
        let (mut buf, mut buf1) = ([Vec3::zeros(); 8], [Vec3::zeros(); 8]);
        for (j, jt) in model.joints.iter().enumerate() {
            let a = jt.parent;
            let bb = jt.child;
            let qa_bar = a.map_or(zero, |a| body_nodes(&ws.qbar, a));
            let qb_bar = body_nodes(&ws.qbar, bb);
            let qa = a.map_or(zero, |a| body_nodes(&ws.q, a));
            let qb = body_nodes(&ws.q, bb);
            let dbar_a = [qa_bar[1], qa_bar[2], qa_bar[3]];
            let dbar_b = [qb_bar[1], qb_bar[2], qb_bar[3]];
            let d_a = [qa[1], qa[2], qa[3]];
            let d_b = [qb[1], qb[2], qb[3]];
            if jac {
                cab.fill(0.0);
                for x in [&mut x_ab, &mut x_ba, &mut x_aa, &mut x_bb] {
                    x.fill(0.0);
                }
            }
            // coef ∇g(q̄) into the node forces and (Full) ½ coef S into the node couplings;
            // returns ∇g(q̄) over the eight nodes (also used by the slide dofs)
            let add_row = |row: &DotRow,
                           coef: f64,
                           fa: &mut [Vec3; 4],
                           fb: &mut [Vec3; 4],
                           cb: &mut [[f64; 16]],
                           cab: &mut [f64; 16]| {
                let sr = SparseRow::new(row, a.is_some());
                let mut buf = [Vec3::zeros(); 8];
                let grad = sr.grad_at(&qa_bar, &qb_bar, &mut buf);
                sr.add_forces(grad, coef, fa, fb);
                if jac {
                    sr.add_hessian(0.5 * coef, cb, a, bb, cab);
                }
                sr.expand(grad)
            };
            let mut fa = [Vec3::zeros(); 4];
            let mut fb = [Vec3::zeros(); 4];
            for (k, sr) in jt.sparse.iter().enumerate().filter(|_| !final_pass) {
                let mu = ws.mu[jt.row0 + k];
                // compact ∇g(q̄) over the row's non-zero nodes (see `SparseRow`)
                let grad = sr.grad_at(&qa_bar, &qb_bar, &mut buf);
                sr.add_forces(grad, mu, &mut fa, &mut fb);
                if jac {
                    sr.add_hessian(0.5 * mu, &mut ws.cbody, a, bb, &mut cab);
                }
                // u, w at the iterate once: the value and the gradient ∇g(q)
                let (u1, w1) = sr.uw(&qa, &qb);
                let gv = sr.value(&u1, &w1);
                res = res.max(gv.abs() * gscale);
                sink.rhs_row(j, k, -gv);
                if jac {
                    // multiplier columns P̄ᵀ∇g(q̄) (skipped where the row is zero)
                    if let Some(col) = sr.project(grad, Side::B, &dbar_b) {
                        sink.body_mu(bb, j, k, &col);
                    }
                    if let (Some(a), Some(col)) = (a, sr.project(grad, Side::A, &dbar_a)) {
                        sink.body_mu(a, j, k, &col);
                    }
                    // joint rows ∇g(q) Q
                    let g1 = sr.grad(&u1, &w1, &mut buf1);
                    if let Some(row) = sr.project(g1, Side::B, &d_b) {
                        sink.mu_body(j, k, bb, &row);
                    }
                    if let (Some(a), Some(row)) = (a, sr.project(g1, Side::A, &d_a)) {
                        sink.mu_body(j, k, a, &row);
                    }
                }
            }
            // joint loads on the coordinates
            let c_d = held.damping[j];
            let k_s = held.stiffness[j];
            let mut turn = jt.turn0;
            let mut sph_t = Vec3::zeros();
            for (dk, dof) in jt.dofs.iter().enumerate() {
                let act = jt
                    .input
                    .map_or(0.0, |i| actuator_input(model, j, dk, held.inputs, i));
                match dof {
                    DofRt::Slide(row) => {
                        let qa_n = a.map_or(zero, |a| body_nodes(&ws.qn, a));
                        let qb_n = body_nodes(&ws.qn, bb);
                        let s0 = row.eval(&qa_n, &qb_n);
                        let s1 = row.eval(&qa, &qb);
                        let ds = s1 - s0;
                        let coef = act - 0.5 * k_s * (s0 + s1) - c_d * ds / h;
                        work += act * ds - c_d * ds * ds / h;
                        let grad =
                            add_row(row, -hh * coef, &mut fa, &mut fb, &mut ws.cbody, &mut cab);
                        if jac && (k_s != 0.0 || c_d != 0.0) {
                            // rank-one term d(−hh·coef)/dx = hh (k/2 + c/h) ∇s(q) Q
                            let kap = hh * (0.5 * k_s + c_d / h);
                            let mut g1 = [Vec3::zeros(); 8];
                            row.gradient(&qa, &qb, &mut g1);
                            let cb_ = project(&grad[4..], &dbar_b);
                            let rb_ = row_q(&g1[4..], &d_b);
                            outer(&mut x_bb, kap, &cb_, &rb_);
                            if a.is_some() {
                                let ca_ = project(&grad[..4], &dbar_a);
                                let ra_ = row_q(&g1[..4], &d_a);
                                outer(&mut x_aa, kap, &ca_, &ra_);
                                outer(&mut x_ab, kap, &ca_, &rb_);
                                outer(&mut x_ba, kap, &cb_, &ra_);
                            }
                        }
                    }
                    DofRt::Turn(tr) => {
                        // actuator: the consistent torque ±act n̄, its work act·δ (nothing to
                        // do for an unactuated or idle joint, the common case in a chain)
                        if act != 0.0 {
                            let nbar = tr.axis.eval(&qa_bar, &qb_bar);
                            let th_b = read3(&ws.theta, 3 * bb);
                            let th_a = a.map_or(Vec3::zeros(), |a| read3(&ws.theta, 3 * a));
                            work += act * nbar.dot(&(th_b - th_a));
                            push_torque(&mut ws.mom, bb, a, &(nbar * (hh * act)));
                            if jac {
                                let jb = linvec_jac(&tr.axis.b, &d_b);
                                let ja = linvec_jac(&tr.axis.a, &d_a);
                                torque_jac(
                                    &mut x_bb,
                                    &mut x_ba,
                                    &mut x_ab,
                                    &mut x_aa,
                                    hh * act,
                                    &jb,
                                    &ja,
                                    a.is_some(),
                                );
                            }
                        }
                        // the angle step, and the spring and damper as the discrete gradient
                        // F = f β (c̄ ∇s(q̄) − s̄ ∇c(q̄)) of `turn`
                        let t0 = ws.ang[turn];
                        let loaded = k_s != 0.0 || c_d != 0.0;
                        if loaded || final_pass {
                            let dqa = a.map_or(zero, |a| body_nodes(&ws.dq, a));
                            let dqb = body_nodes(&ws.dq, bb);
                            let qa_n = a.map_or(zero, |a| body_nodes(&ws.qn, a));
                            let qb_n = body_nodes(&ws.qn, bb);
                            let (s0, c0) = (tr.sin.eval(&qa_n, &qb_n), tr.cos.eval(&qa_n, &qb_n));
                            let ds = row_increment(&tr.sin, &qa_bar, &qb_bar, &dqa, &dqb);
                            let dc = row_increment(&tr.cos, &qa_bar, &qb_bar, &dqa, &dqb);
                            let st = turn_step([s0, c0], [ds, dc], t0, k_s, c_d, h);
                            ws.ang1[turn] = t0 + st.dt;
                            if loaded {
                                work -= c_d * st.dt * st.dt / h;
                                let gs = add_row(
                                    &tr.sin,
                                    -hh * st.fs,
                                    &mut fa,
                                    &mut fb,
                                    &mut ws.cbody,
                                    &mut cab,
                                );
                                let gc = add_row(
                                    &tr.cos,
                                    -hh * st.fc,
                                    &mut fa,
                                    &mut fb,
                                    &mut ws.cbody,
                                    &mut cab,
                                );
                                if jac {
                                    // d(−hh f)/dx through (s₁, c₁): Σᵢⱼ −hh ∂fᵢ/∂j₁ P̄ᵀ∇i(q̄) ⊗ ∇j(q)Q
                                    let mut g1 = [Vec3::zeros(); 8];
                                    tr.sin.gradient(&qa, &qb, &mut g1);
                                    let (rs_b, rs_a) =
                                        (row_q(&g1[4..], &d_b), row_q(&g1[..4], &d_a));
                                    tr.cos.gradient(&qa, &qb, &mut g1);
                                    let (rc_b, rc_a) =
                                        (row_q(&g1[4..], &d_b), row_q(&g1[..4], &d_a));
                                    let mix = |ws_: f64, wc: f64, rs: &[f64; 6], rc: &[f64; 6]| {
                                        std::array::from_fn::<f64, 6, _>(|i| {
                                            -hh * (ws_ * rs[i] + wc * rc[i])
                                        })
                                    };
                                    let j = st.jac;
                                    let (ms_b, mc_b) = (
                                        mix(j[0], j[1], &rs_b, &rc_b),
                                        mix(j[2], j[3], &rs_b, &rc_b),
                                    );
                                    let (cs_b, cc_b) =
                                        (project(&gs[4..], &dbar_b), project(&gc[4..], &dbar_b));
                                    outer(&mut x_bb, 1.0, &cs_b, &ms_b);
                                    outer(&mut x_bb, 1.0, &cc_b, &mc_b);
                                    if a.is_some() {
                                        let (ms_a, mc_a) = (
                                            mix(j[0], j[1], &rs_a, &rc_a),
                                            mix(j[2], j[3], &rs_a, &rc_a),
                                        );
                                        let (cs_a, cc_a) = (
                                            project(&gs[..4], &dbar_a),
                                            project(&gc[..4], &dbar_a),
                                        );
                                        outer(&mut x_ba, 1.0, &cs_b, &ms_a);
                                        outer(&mut x_ba, 1.0, &cc_b, &mc_a);
                                        outer(&mut x_ab, 1.0, &cs_a, &ms_b);
                                        outer(&mut x_ab, 1.0, &cc_a, &mc_b);
                                        outer(&mut x_aa, 1.0, &cs_a, &ms_a);
                                        outer(&mut x_aa, 1.0, &cc_a, &mc_a);
                                    }
                                }
                            }
                        } else {
                            ws.ang1[turn] = t0;
                        }
                        turn += 1;
                    }
                }
            }
            if let Some(axes) = &jt.sph_axes {
                let th_b = read3(&ws.theta, 3 * bb);
                let th_a = a.map_or(Vec3::zeros(), |a| read3(&ws.theta, 3 * a));
                let rel = th_b - th_a;
                let mut tv = -rel * (c_d / h);
                work -= c_d * rel.norm_squared() / h;
                for (k, ax) in axes.iter().enumerate() {
                    let act = jt.input.map_or(0.0, |i| held.inputs[i + k]);
                    if act != 0.0 {
                        let abar = ax.eval(&qa_bar, &qb_bar);
                        tv += abar * act;
                        work += act * abar.dot(&rel);
                        if jac {
                            let jb = linvec_jac(&ax.b, &d_b);
                            let ja = linvec_jac(&ax.a, &d_a);
                            torque_jac(
                                &mut x_bb,
                                &mut x_ba,
                                &mut x_ab,
                                &mut x_aa,
                                hh * act,
                                &jb,
                                &ja,
                                a.is_some(),
                            );
                        }
                    }
                }
                sph_t += tv;
                push_torque(&mut ws.mom, bb, a, &(sph_t * hh));
                if jac && c_d != 0.0 {
                    // d(hh (c/h)(θᴮ − θᴬ))/dε through the exact ∂θ/∂ε of each body
                    let kap = hh * c_d / h;
                    let qa_n = a.map_or(zero, |a| body_nodes(&ws.qn, a));
                    let qb_n = body_nodes(&ws.qn, bb);
                    let jb = theta_jac(&qb_n, &qb);
                    let ja = a.map(|_| theta_jac(&qa_n, &qa));
                    for r in 0..3 {
                        for c in 0..3 {
                            let o = (r + 3) * 6 + 3 + c;
                            x_bb[o] += kap * jb[(r, c)];
                            if let Some(ja) = &ja {
                                x_aa[o] += kap * ja[(r, c)];
                                x_ab[o] -= kap * jb[(r, c)];
                                x_ba[o] -= kap * ja[(r, c)];
                            }
                        }
                    }
                }
            }
            // node forces of this joint into R̃ (the final pass does not use R̃)
            if !final_pass {
                if let Some(a) = a {
                    for k in 0..4 {
                        let v = read3(&ws.rn, 12 * a + 3 * k) + fa[k];
                        write3(&mut ws.rn, 12 * a + 3 * k, &v);
                    }
                }
                for k in 0..4 {
                    let v = read3(&ws.rn, 12 * bb + 3 * k) + fb[k];
                    write3(&mut ws.rn, 12 * bb + 3 * k, &v);
                }
            }
            if jac {
                for (x, y) in ws.xbody[bb].iter_mut().zip(&x_bb) {
                    *x += y;
                }
                if let Some(a) = a {
                    for (x, y) in ws.xbody[a].iter_mut().zip(&x_aa) {
                        *x += y;
                    }
                    // the extra blocks complete in place (zeroed again for the next joint)
                    node_block(&cab, &dbar_a, &d_b, &mut x_ab);
                    sink.body_body(a, bb, &x_ab);
                    let mut cba = [0.0; 16];
                    for n in 0..4 {
                        for m in 0..4 {
                            cba[4 * n + m] = cab[4 * m + n];
                        }
                    }
                    node_block(&cba, &dbar_b, &d_a, &mut x_ba);
                    sink.body_body(bb, a, &x_ba);
                }
            }
        }
    }
    ws.dense = sink_dense;
    ws.blocks = sink_blocks;
    ws.drhs = sink_drhs;
    ws.border = sink_border;
    res = res.max(project_bodies(model, ws, held, hh, mode, nd, &mut work));
    *work_out = work;
    Norms { res }
}

/// Value of the actuator input driving dof `dk` of joint `j` (inputs start at `first`).
fn actuator_input(model: &Model, j: usize, dk: usize, inputs: &[f64], first: usize) -> f64 {
    let _ = (model, j);
    inputs.get(first + dk).copied().unwrap_or(0.0)
}

#[cfg(test)]
#[path = "newton_tests.rs"]
mod tests;
