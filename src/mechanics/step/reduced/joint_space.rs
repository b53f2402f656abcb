//! A revolute joint's loads taken in joint space by the reduced iteration: its input torque,
//! springs, dampers, stops, rotor, friction and actuator laws (`turn::turn_step`) and the
//! reactions of its couplings (`turn::turn_load`, `couple`), as scalars on the joint's own
//! rate instead of node forces on its two bodies.
//!
//! The joint's turn rows are `s = p_s·k_s`, `c = p_c·k_c` with `p` fixed in the parent (a
//! combination of its directors; a constant for the world) and `k` in the child, and its axis
//! `n` is fixed in the parent. A load `F = −(h²/2)(f_s ∇s(q̄) + f_c ∇c(q̄))` is a midpoint
//! gradient of invariants of the pair, so `P̄ᵀF` vanishes on every rate but the joint's own
//! (a rigid motion of both bodies leaves `s`, `c` unchanged; the rates below the joint move
//! neither body), where it is `n̄` times the moment of `F` on the child (`kernels::project`:
//! `Σ d̄ᵢ × F_dᵢ = −(h²/2) Σ f_i k̄_i × p̄_i`). The input torque `τ` acts as `∓(h²/2)τ n̄` on
//! the child and the parent (`kernels::push_torque`). So, with bars at the midpoint `q̄`:
//!
//! ```text
//! R_j = −(h²/2) (f_s κ_s + f_c κ_c + τ n̄·n̄),   κ_i = n̄·(k̄_i × p̄_i)
//! ```
//!
//! the same number the node path forms (to round-off). Its Newton row on the child's and the
//! parent's twists (rotational parts; a twist turns the iterate's vectors by `δθ ×` and the
//! midpoint's by half of it):
//!
//! ```text
//! ∂s₁/∂θ_B = k × p,   ∂s₁/∂θ_A = p × k                    (s₁ = p·k at the iterate)
//! ∂κ/∂θ_B = ½ k × (p̄ × n̄)
//! ∂κ/∂θ_A = ½ [(k̄·p) n̄ − (p·n̄) k̄ + (p̄·n) k̄ − (k̄·n) p̄]
//! ∂(n̄·n̄)/∂θ_A = n × n̄
//! ∂R_j = −(h²/2) Σ_i [(∂f_i/∂s₁ ∂s₁ + ∂f_i/∂c₁ ∂c₁) κ_i + f_i ∂κ_i] − (h²/2) τ ∂(n̄·n̄)
//! ```
//!
//! exact, so the reduced matrix stays the Jacobian. A coupling's reaction `μ w D_j` is the
//! load of constant size `f = μ w` (scale 1 instead of `−h²/2`, `step::coupling`); its column
//! is `w (β c̄ κ_s − β s̄ κ_c)` and its row `w (∂Δt/∂s₁ ∂s₁ + ∂Δt/∂c₁ ∂c₁)`.
//!
//! Cost per joint and evaluation: a few dozen vector operations, against the node path's
//! node forces, Hessians and 6 × 6 blocks on both bodies (`joint_loads`, `apply_joint`).

use super::super::joint_loads::{actuator_input, turn_start};
use super::super::turn::{turn_load, turn_step};
use super::super::work::{Held, Work};
use super::bordered::Slot;
use super::maps::V6;
use super::split::{row_increment, Factor, JointRow, Split};
use crate::math::Vec3;
use crate::mechanics::model::constraint::{body_nodes, Nodes};
use crate::mechanics::model::runtime::{DofRt, Model};

/// The vectors of one row at the midpoint and at the iterate.
struct Row {
    pb: Vec3,
    kb: Vec3,
    p: Vec3,
    k: Vec3,
    /// `κ = n̄·(k̄ × p̄)`.
    kappa: f64,
}

/// The joint's vectors at `q̄` and `q`.
struct Frame {
    rows: [Row; 2],
    nb: Vec3,
    n: Vec3,
    world: bool,
}

impl Frame {
    /// The vectors at `q̄` (`qa_bar`, `qb_bar`) and, for a Jacobian pass, at `q` (else
    /// zero), and the rows' increments `[Δs, Δc]` from the node increments `da`, `db`
    /// (`Δ(p·k) = Δp·k̄ + p̄·Δk`, as `turn::row_increment` forms it, so the residual and
    /// `finish` take the same step).
    fn new(
        sp: &Split,
        bar: (&Nodes, &Nodes),
        it: Option<(&Nodes, &Nodes)>,
        d: (&Nodes, &Nodes),
    ) -> (Self, [f64; 2]) {
        let ((qa_bar, qb_bar), (da, db)) = (bar, d);
        let at = |f: &Factor| it.map_or(Vec3::zeros(), |(qa, qb)| f.at(qa, qb));
        let nb = sp.n.at(qa_bar, qb_bar);
        let n = at(&sp.n);
        let row = |pk: &([Factor; 2], bool)| {
            let f = &pk.0;
            let (pb, kb) = (f[0].at(qa_bar, qb_bar), f[1].at(qa_bar, qb_bar));
            let r = Row {
                pb,
                kb,
                p: at(&f[0]),
                k: at(&f[1]),
                kappa: nb.dot(&kb.cross(&pb)),
            };
            (r, row_increment(pk, (pb, kb), (da, db)))
        };
        let ((rs, ds), (rc, dc)) = (row(&sp.s), row(&sp.c));
        let world = matches!(sp.n, Factor::Fixed(_));
        (
            Self {
                rows: [rs, rc],
                nb,
                n,
                world,
            },
            [ds, dc],
        )
    }

    /// `(∂v₁/∂θ_B, ∂v₁/∂θ_A)` of row `v` at the iterate.
    fn d_value(&self, v: usize) -> (Vec3, Vec3) {
        let r = &self.rows[v];
        let b = r.k.cross(&r.p);
        (b, -b)
    }

    /// `(∂κ/∂θ_B, ∂κ/∂θ_A)` of row `v`.
    fn d_kappa(&self, v: usize) -> (Vec3, Vec3) {
        let r = &self.rows[v];
        let (nb, n) = (&self.nb, &self.n);
        let b = r.k.cross(&r.pb.cross(nb)) * 0.5;
        let a = if self.world {
            Vec3::zeros()
        } else {
            (nb * r.kb.dot(&r.p) - r.kb * r.p.dot(nb) + r.kb * r.pb.dot(n) - r.pb * r.kb.dot(n))
                * 0.5
        };
        (b, a)
    }

    /// Adds the load with coefficients `f = [f_s, f_c]`, their partials `df` (`TurnStep::jac`)
    /// and scale `scale` to `out`.
    fn add_load(&self, f: [f64; 2], df: &[f64; 4], scale: f64, jac: bool, out: &mut JointRow) {
        let [rs, rc] = &self.rows;
        out.r += scale * (f[0] * rs.kappa + f[1] * rc.kappa);
        if !jac {
            return;
        }
        let (vs, vc) = (self.d_value(0), self.d_value(1));
        for (i, row) in self.rows.iter().enumerate() {
            let (ks, kc) = (df[2 * i], df[2 * i + 1]);
            let (kb, ka) = self.d_kappa(i);
            let c = scale * row.kappa;
            let fi = scale * f[i];
            out.xc += (vs.0 * ks + vc.0 * kc) * c + kb * fi;
            out.xp += (vs.1 * ks + vc.1 * kc) * c + ka * fi;
        }
    }
}

/// Joint `j`'s loads and its couplings' reactions in joint space (`split` given); the
/// couplings' values, columns and rows go to `slots` (`couple`); `load`: whether the joint
/// carries loads of its own (`joint_loads::loaded`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn joint_row(
    model: &Model,
    ws: &mut Work,
    held: &Held,
    (j, sp): (usize, &Split),
    h: f64,
    jac: bool,
    load: bool,
    couplings: &[(usize, f64)],
    slots: &mut [Slot],
) -> JointRow {
    let jt = &model.joints[j];
    let DofRt::Turn(tr) = &jt.dofs[0] else {
        unreachable!("split joints are revolute");
    };
    let hh = 0.5 * h * h;
    let zero: Nodes = [Vec3::zeros(); 4];
    let (a, b) = (jt.parent, jt.child);
    let at = |x: &[f64], body: Option<usize>| body.map_or(zero, |p| body_nodes(x, p));
    let bar = (at(&ws.qbar, a), at(&ws.qbar, Some(b)));
    let it = jac.then(|| (at(&ws.q, a), at(&ws.q, Some(b))));
    let d = (at(&ws.dq, a), at(&ws.dq, Some(b)));
    let it = it.as_ref().map(|(qa, qb)| (qa, qb));
    let (fr, dsdc) = Frame::new(sp, (&bar.0, &bar.1), it, (&d.0, &d.1));
    let s0c0 = turn_start(ws, tr, jt.turn0, a, b);
    let mut out = JointRow::default();
    if load {
        let tau = jt
            .input
            .map_or(0.0, |i| actuator_input(0, held.inputs, i, jt.effort));
        if tau != 0.0 {
            out.r -= hh * tau * fr.nb.dot(&fr.nb);
            if jac && !fr.world {
                out.xp -= fr.n.cross(&fr.nb) * (hh * tau);
            }
        }
        let t0 = ws.ang[jt.turn0];
        let (k_s, c_d) = (held.stiffness[j], held.damping[j]);
        let arm = if jt.armature > 0.0 {
            [jt.armature, ws.arm[jt.arm0]]
        } else {
            [0.0; 2]
        };
        let fric = jt.friction.as_ref().map(|f| (f, ws.fric[jt.fric0]));
        let acts = (&jt.acts, held.inputs, held.gains);
        let stops = jt.stops.as_ref();
        let st = turn_step(s0c0, dsdc, t0, k_s, c_d, stops, arm, fric, acts, h);
        fr.add_load([st.fs, st.fc], &st.jac, -hh, jac, &mut out);
    }
    for &(c, w) in couplings {
        let mu = ws.mu[model.couplings[c].row];
        let tl = turn_load(s0c0, dsdc, mu * w);
        fr.add_load([tl.step.fs, tl.step.fc], &tl.step.jac, 1.0, jac, &mut out);
        let slot = &mut slots[c];
        slot.g += w * (ws.ang[jt.turn0] + tl.step.dt);
        if jac {
            let e = w * (tl.unit[0] * fr.rows[0].kappa + tl.unit[1] * fr.rows[1].kappa);
            let (vs, vc) = (fr.d_value(0), fr.d_value(1));
            let (ts, tc) = (w * tl.ddt[0], w * tl.ddt[1]);
            let rb = vs.0 * ts + vc.0 * tc;
            let col = ([e, 0.0, 0.0, 0.0, 0.0, 0.0], false);
            slot.put(
                (&model.couplings[c], j),
                (b, a),
                col,
                [rot6(&rb), rot6(&-rb)],
            );
        }
    }
    out
}

/// A rotational row as a twist row `(0, v)`.
fn rot6(v: &Vec3) -> V6 {
    [0.0, 0.0, 0.0, v.x, v.y, v.z]
}
