//! Joint couplings `q_b = r q_a + o` in the Newton residual and Jacobian: one multiplier row
//! each, whose reaction acts on the two joint coordinates through their discrete gradients.
//!
//! With `Δ_j` the increment of joint `j`'s coordinate over the stage (a turn: the `atan2`
//! increment `Δt = β X` of `turn`; a slide: `Δs = s(q) − s(qₙ)`, `s` quadratic) and `D_j` its
//! discrete gradient (`D = β (c̄ ∇s(q̄) − s̄ ∇c(q̄))`, resp. `∇s(q̄)`), for which `D_j·Δq = Δ_j`
//! exactly, the coupling adds (scaled by `h²/2` like every row, `μ = h²λ/2`)
//!
//! ```text
//! R̃ += μ (D_b − r D_a)                          (reaction on the two joints' bodies)
//! g = e₀ + Δ_b − r Δ_a = 0,   e₀ = q_b,ₙ − r q_a,ₙ − o   (the defect at the stage start)
//! ```
//!
//! Work of the reaction over the stage: `μ (Δ_b − r Δ_a) = −μ e₀`, zero to round-off (`e₀` is
//! the defect left by the previous stage's Newton tolerance, and `g = 0` removes it), so
//! `energy − work` holds with couplings as without; `D` is a combination of midpoint
//! gradients of rigid-motion invariants, so the reaction preserves linear and angular
//! momentum. Jacobian (body unknowns `x`): the multiplier column `P̄ᵀ(D_b − r D_a)`, the row
//! `∂Δ_b/∂x − r ∂Δ_a/∂x` (`∂Δt/∂(s₁, c₁) = (Y c₀ − X s₀, −Y s₀ − X c₀)/(X² + Y²)`, times
//! `∇s(q)Q`, `∇c(q)Q`), and `μ ∂D/∂x` (the Hessians of `s`, `c` and the derivatives of
//! `β c̄`, `−β s̄` as for a turn load of constant size, `turn::turn_load`).

use super::joint_loads::{
    add_dot_row, add_sparse_row, apply_joint, turn_jac, turn_start, Acc, Pair,
};
use super::turn::{row_increment, turn_load};
use super::work::Work;
use crate::math::Vec3;
use crate::mechanics::model::constraint::{body_nodes, Nodes};
use crate::mechanics::model::kernels::{project, row_q};
use crate::mechanics::model::runtime::{DofRt, Model};
use crate::mechanics::model::sink::Sink;

/// What a coupling's reaction on one of its joints adds: its part `w Δ_j` of the row value
/// (the stage-start part `w qⱼ,ₙ` included) and, in a Jacobian pass, the multiplier column
/// `w P̄ᵀ D_j` and the row `w ∂Δ_j/∂x` on the joint's bodies (child, then parent; body twists).
pub(crate) struct Reaction {
    /// `w (qⱼ,ₙ + Δ_j)`, rad or m.
    pub g: f64,
    /// Multiplier column on the child and the parent.
    pub col: [[f64; 6]; 2],
    /// Row on the child and the parent.
    pub row: [[f64; 6]; 2],
}

/// Adds the reaction `μ w D_j` of a coupling with multiplier `mu` on joint `j` (weight `w`:
/// 1 for the following joint, `−r` for the leading one) to `acc` (node forces and, if `jac`,
/// the `μ ∂D/∂x` blocks and node couplings, with the Hessians of the rows in `ws.cbody`).
pub(crate) fn reaction(
    model: &Model,
    ws: &mut Work,
    (j, w, mu): (usize, f64, f64),
    p: &Pair,
    jac: bool,
    acc: &mut Acc,
) -> Reaction {
    let jt = &model.joints[j];
    let zero: Nodes = [Vec3::zeros(); 4];
    let dqa = jt.parent.map_or(zero, |a| body_nodes(&ws.dq, a));
    let dqb = body_nodes(&ws.dq, jt.child);
    let f = mu * w;
    let Acc {
        fa,
        fb,
        cab,
        x_ab,
        x_ba,
        x_aa,
        x_bb,
    } = acc;
    let none = [[0.0; 6]; 2];
    match &jt.dofs[0] {
        DofRt::Turn(tr) => {
            let [s0, c0] = turn_start(ws, tr, jt.turn0, jt.parent, jt.child);
            let ds = row_increment(&tr.sin, &p.qa_bar, &p.qb_bar, &dqa, &dqb);
            let dc = row_increment(&tr.cos, &p.qa_bar, &p.qb_bar, &dqa, &dqb);
            let tl = turn_load([s0, c0], [ds, dc], f);
            let g = w * (ws.ang[jt.turn0] + tl.step.dt);
            let [ss, sc] = &tr.sparse;
            let nodes = (&mut *fa, &mut *fb, &mut ws.cbody[..], &mut *cab);
            let gs = add_sparse_row(ss, tl.step.fs, p, jac, nodes);
            let nodes = (&mut *fa, &mut *fb, &mut ws.cbody[..], &mut *cab);
            let gc = add_sparse_row(sc, tl.step.fc, p, jac, nodes);
            if !jac {
                return Reaction {
                    g,
                    col: none,
                    row: none,
                };
            }
            let xs = (&mut *x_ab, &mut *x_ba, &mut *x_aa, &mut *x_bb);
            let t = turn_jac(tr, p, (&gs, &gc), &tl.step.jac, 1.0, xs);
            let (us, uc) = (w * tl.unit[0], w * tl.unit[1]);
            let (ts, tc) = (w * tl.ddt[0], w * tl.ddt[1]);
            let lin = |x: f64, u: &[f64; 6], y: f64, v: &[f64; 6]| {
                std::array::from_fn::<f64, 6, _>(|i| x * u[i] + y * v[i])
            };
            let side = |k: usize| {
                (
                    lin(us, &t.cs[k], uc, &t.cc[k]),
                    lin(ts, &t.rs[k], tc, &t.rc[k]),
                )
            };
            let ((col_b, row_b), (col_a, row_a)) = (side(0), side(1));
            Reaction {
                g,
                col: [col_b, col_a],
                row: [row_b, row_a],
            }
        }
        DofRt::Slide(sr) => {
            let qa_n = jt.parent.map_or(zero, |a| body_nodes(&ws.qn, a));
            let qb_n = body_nodes(&ws.qn, jt.child);
            let ds = row_increment(sr, &p.qa_bar, &p.qb_bar, &dqa, &dqb);
            let g = w * (sr.eval(&qa_n, &qb_n) + ds);
            let nodes = (&mut *fa, &mut *fb, &mut ws.cbody[..], &mut *cab);
            let gs = add_dot_row(sr, f, p, jac, nodes);
            if !jac {
                return Reaction {
                    g,
                    col: none,
                    row: none,
                };
            }
            let mut g1 = [Vec3::zeros(); 8];
            sr.gradient(&p.qa, &p.qb, &mut g1);
            let sc = |v: [f64; 6]| v.map(|x| w * x);
            Reaction {
                g,
                col: [
                    sc(project(&gs[4..], &p.dbar_b)),
                    sc(project(&gs[..4], &p.dbar_a)),
                ],
                row: [sc(row_q(&g1[4..], &p.d_b)), sc(row_q(&g1[..4], &p.d_a))],
            }
        }
    }
}

/// Adds every coupling's reaction to the node residual, its row's value `−g` to the
/// right-hand side and (`jac`) its column, row and `μ ∂D/∂x` blocks to the sink; returns the
/// largest scaled `|g|`.
pub(crate) fn couplings(model: &Model, ws: &mut Work, jac: bool, sink: &mut Sink) -> f64 {
    let nj = model.joints.len();
    let gscale = 1.0 / model.lc.min(1.0);
    let mut acc = Acc::new();
    let mut res = 0.0_f64;
    for (c, cp) in model.couplings.iter().enumerate() {
        let group = nj + c;
        let mu = ws.mu[cp.row];
        let mut g = -cp.offset;
        for (j, w) in cp.weighted() {
            let jt = &model.joints[j];
            let p = Pair::new(ws, jt.parent, jt.child);
            acc.clear(jac);
            let r = reaction(model, ws, (j, w, mu), &p, jac, &mut acc);
            g += r.g;
            if apply_joint(ws, &p, &mut acc, jac) {
                if let Some(a) = p.a {
                    sink.body_body(a, p.b, &acc.x_ab);
                    sink.body_body(p.b, a, &acc.x_ba);
                }
            }
            if jac {
                sink.body_mu(p.b, group, 0, &r.col[0]);
                sink.mu_body(group, 0, p.b, &r.row[0]);
                if let Some(a) = p.a {
                    sink.body_mu(a, group, 0, &r.col[1]);
                    sink.mu_body(group, 0, a, &r.row[1]);
                }
            }
        }
        res = res.max(g.abs() * gscale);
        sink.rhs_row(group, 0, -g);
    }
    res
}
