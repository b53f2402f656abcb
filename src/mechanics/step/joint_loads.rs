//! Joint loads of the Newton residual and Jacobian: actuator inputs (consistent torques `±τ n̄`
//! and slide forces, clamped to `±effort`), joint actuators (`model::joint_actuator`: their
//! generalised force `τ(q̄, Δ/h)` on the coordinate, with `∂τ/∂Δ`), linear springs, viscous dampers, one-sided stops
//! (`model::stops`) and rotors (armature `a`: the load `−(2a/h²)(Δ − h ω₀)` of the midpoint
//! rule on the coordinate with the rotor's rate `ω₀`, `turn`) on the joint coordinates (the midpoint
//! gradient of a slide, the `atan2` discrete gradient of `turn` for an angle, the rotation
//! increments for a spherical joint), added to the node forces of the joint's two bodies and,
//! in a Jacobian pass, to their coupling blocks (theory.md §4.2; residual scaled by `h²/2`).
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use super::turn::{row_increment, theta_jac, turn_step};
use super::work::{Held, Work};
use crate::math::{Mat3, Vec3};
use crate::mechanics::model::constraint::{body_nodes, read3, write3, DotRow, Nodes};
use crate::mechanics::model::kernels::{
    linvec_jac, node_block, outer, project, push_torque, rotation_increment, row_q, torque_jac,
};
use crate::mechanics::model::runtime::{DofRt, Model, TurnRt};
use crate::mechanics::model::sparse_row::SparseRow;

/// The two bodies of a joint at the iterate: parent `a` (`None`: the world, whose nodes are
/// zero) and child `b`, their nodes at the midpoint `q̄` and the iterate `q` (world frame), and
/// the directors of each.
pub(crate) struct Pair {
    /// Parent body.
    pub a: Option<usize>,
    /// Child body.
    pub b: usize,
    /// Parent nodes at `q̄`.
    pub qa_bar: Nodes,
    /// Child nodes at `q̄`.
    pub qb_bar: Nodes,
    /// Parent nodes at `q`.
    pub qa: Nodes,
    /// Child nodes at `q`.
    pub qb: Nodes,
    /// Parent directors at `q̄`.
    pub dbar_a: [Vec3; 3],
    /// Child directors at `q̄`.
    pub dbar_b: [Vec3; 3],
    /// Parent directors at `q`.
    pub d_a: [Vec3; 3],
    /// Child directors at `q`.
    pub d_b: [Vec3; 3],
}

impl Pair {
    /// The pair of joint bodies `a`, `b` at the workspace's iterate (`ws.qbar`, `ws.q`).
    pub fn new(ws: &Work, a: Option<usize>, b: usize) -> Self {
        let zero: Nodes = [Vec3::zeros(); 4];
        let qa_bar = a.map_or(zero, |a| body_nodes(&ws.qbar, a));
        let qb_bar = body_nodes(&ws.qbar, b);
        let qa = a.map_or(zero, |a| body_nodes(&ws.q, a));
        let qb = body_nodes(&ws.q, b);
        Self {
            a,
            b,
            qa_bar,
            qb_bar,
            qa,
            qb,
            dbar_a: [qa_bar[1], qa_bar[2], qa_bar[3]],
            dbar_b: [qb_bar[1], qb_bar[2], qb_bar[3]],
            d_a: [qa[1], qa[2], qa[3]],
            d_b: [qb[1], qb[2], qb[3]],
        }
    }
}

/// What one joint adds: node forces on each body (`fa`, `fb`, world frame, scaled residual
/// units) and, in a Jacobian pass, the node coupling `C_AB` (4 × 4) and the 6 × 6 blocks
/// (row body, column body: `x_ab` parent rows / child columns, …).
pub(crate) struct Acc {
    /// Node forces on the parent.
    pub fa: [Vec3; 4],
    /// Node forces on the child.
    pub fb: [Vec3; 4],
    /// Node coupling parent–child (row-major 4 × 4).
    pub cab: [f64; 16],
    /// Block parent rows, child columns.
    pub x_ab: [f64; 36],
    /// Block child rows, parent columns.
    pub x_ba: [f64; 36],
    /// Block parent rows, parent columns.
    pub x_aa: [f64; 36],
    /// Block child rows, child columns.
    pub x_bb: [f64; 36],
}

impl Acc {
    /// All zero.
    pub fn new() -> Self {
        Self {
            fa: [Vec3::zeros(); 4],
            fb: [Vec3::zeros(); 4],
            cab: [0.0; 16],
            x_ab: [0.0; 36],
            x_ba: [0.0; 36],
            x_aa: [0.0; 36],
            x_bb: [0.0; 36],
        }
    }

    /// Zeroes the forces and (`jac`) the coupling blocks for the next joint.
    pub fn clear(&mut self, jac: bool) {
        self.fa = [Vec3::zeros(); 4];
        self.fb = [Vec3::zeros(); 4];
        if jac {
            self.cab.fill(0.0);
            for x in [
                &mut self.x_ab,
                &mut self.x_ba,
                &mut self.x_aa,
                &mut self.x_bb,
            ] {
                x.fill(0.0);
            }
        }
    }
}

/// `[s₀, c₀]` of turn coordinate `turn` (rows `tr` of the pair `a`, `b`) at the stage start
/// `ws.qn`: evaluated once per stage and kept (`Work::sc0`), as every Newton evaluation of
/// the stage reads them.
pub(crate) fn turn_start(
    ws: &mut Work,
    tr: &TurnRt,
    turn: usize,
    a: Option<usize>,
    b: usize,
) -> [f64; 2] {
    if ws.sc0_at[turn] != ws.stage_id {
        let zero: Nodes = [Vec3::zeros(); 4];
        let qa_n = a.map_or(zero, |a| body_nodes(&ws.qn, a));
        let qb_n = body_nodes(&ws.qn, b);
        ws.sc0[turn] = [tr.sin.eval(&qa_n, &qb_n), tr.cos.eval(&qa_n, &qb_n)];
        ws.sc0_at[turn] = ws.stage_id;
    }
    ws.sc0[turn]
}

/// Whether joint `j` carries any load (an actuator, a spring or a damper); most joints of a
/// chain do not, and their load pass is skipped.
pub(crate) fn loaded(model: &Model, held: &Held, j: usize) -> bool {
    let jt = &model.joints[j];
    jt.input.is_some()
        || jt.stops.is_some()
        || held.stiffness[j] != 0.0
        || held.damping[j] != 0.0
        || jt.armature != 0.0
        || jt.friction.is_some()
        || !jt.acts.is_empty()
}

/// Adds the loads of joint `j` (stage size `h`, s) at the pair's iterate to `acc` (and the
/// consistent torques to `ws.mom`, the Hessian terms of the load rows to `ws.cbody`).
#[allow(clippy::too_many_lines, clippy::too_many_arguments)]
pub(crate) fn joint_loads(
    model: &Model,
    ws: &mut Work,
    held: &Held,
    j: usize,
    h: f64,
    jac: bool,
    p: &Pair,
    acc: &mut Acc,
) {
    let jt = &model.joints[j];
    let hh = 0.5 * h * h;
    let zero: Nodes = [Vec3::zeros(); 4];
    let (a, bb) = (p.a, p.b);
    let (qa_bar, qb_bar, qa, qb) = (&p.qa_bar, &p.qb_bar, &p.qa, &p.qb);
    let (dbar_a, dbar_b, d_a, d_b) = (&p.dbar_a, &p.dbar_b, &p.d_a, &p.d_b);
    let Acc {
        fa,
        fb,
        cab,
        x_ab,
        x_ba,
        x_aa,
        x_bb,
    } = acc;
    let add_row =
        |row: &DotRow,
         coef: f64,
         fa: &mut [Vec3; 4],
         fb: &mut [Vec3; 4],
         cb: &mut [[f64; 16]],
         cab: &mut [f64; 16]| { add_dot_row(row, coef, p, jac, (fa, fb, cb, cab)) };
    let c_d = held.damping[j];
    let k_s = held.stiffness[j];
    let mut turn = jt.turn0;
    let mut sph_t = Vec3::zeros();
    for (dk, dof) in jt.dofs.iter().enumerate() {
        let act = jt
            .input
            .map_or(0.0, |i| actuator_input(dk, held.inputs, i, jt.effort));
        // the rotor: armature and its rate at the stage start (`turn`)
        let arm = if jt.armature > 0.0 {
            [jt.armature, ws.arm[jt.arm0 + dk]]
        } else {
            [0.0; 2]
        };
        // friction and its bristle's deflection at the stage start
        let fric = jt.friction.as_ref().map(|fr| (fr, ws.fric[jt.fric0 + dk]));
        match dof {
            DofRt::Slide(row) => {
                let qa_n = a.map_or(zero, |a| body_nodes(&ws.qn, a));
                let qb_n = body_nodes(&ws.qn, bb);
                let s0 = row.eval(&qa_n, &qb_n);
                let s1 = row.eval(qa, qb);
                let ds = s1 - s0;
                let (f_stop, df_stop) = jt.stops.map_or((0.0, 0.0), |st| st.force(s0, ds, h));
                let rotor = 2.0 * arm[0] / (h * h);
                // the rotor's Δ − hω is O(h²): Δ from the increments, without the
                // cancellation of s₁ − s₀
                let (mut f_rotor, mut f_fric, mut df_fric) = (0.0, 0.0, 0.0);
                if rotor != 0.0 || fric.is_some() {
                    let dqa = a.map_or(zero, |a| body_nodes(&ws.dq, a));
                    let dqb = body_nodes(&ws.dq, bb);
                    let dsr = row_increment(row, qa_bar, qb_bar, &dqa, &dqb);
                    f_rotor = rotor * (dsr - h * arm[1]);
                    if let Some((fr, s_0)) = fric {
                        let st = fr.step(s_0, dsr, h);
                        (f_fric, df_fric) = (st.force, st.dforce);
                    }
                }
                let (f_act, df_act) = jt.acts.stage(held.inputs, held.gains, s0, ds, h);
                let coef =
                    act - 0.5 * k_s * (s0 + s1) - c_d * ds / h + f_stop - f_rotor + f_fric + f_act;
                let stiff = k_s != 0.0
                    || c_d != 0.0
                    || df_stop != 0.0
                    || rotor != 0.0
                    || fric.is_some()
                    || df_act != 0.0;
                if coef == 0.0 && !stiff {
                    // idle, or stops that neither end of the step has reached
                    continue;
                }
                let grad = add_row(row, -hh * coef, fa, fb, &mut ws.cbody, cab);
                if jac && stiff {
                    // rank-one term d(−hh·coef)/dx = hh (k/2 + c/h − ∂f_stop/∂s₁) ∇s(q) Q
                    let kap = hh * (0.5 * k_s + c_d / h + rotor - df_stop - df_fric - df_act);
                    let mut g1 = [Vec3::zeros(); 8];
                    row.gradient(qa, qb, &mut g1);
                    let cb_ = project(&grad[4..], dbar_b);
                    let rb_ = row_q(&g1[4..], d_b);
                    outer(x_bb, kap, &cb_, &rb_);
                    if a.is_some() {
                        let ca_ = project(&grad[..4], dbar_a);
                        let ra_ = row_q(&g1[..4], d_a);
                        outer(x_aa, kap, &ca_, &ra_);
                        outer(x_ab, kap, &ca_, &rb_);
                        outer(x_ba, kap, &cb_, &ra_);
                    }
                }
            }
            DofRt::Turn(tr) => {
                // actuator: the consistent torque ±act n̄, its work act·δ (nothing to
                // do for an unactuated or idle joint, the common case in a chain)
                if act != 0.0 {
                    let nbar = tr.axis.eval(qa_bar, qb_bar);
                    push_torque(&mut ws.mom, bb, a, &(nbar * (hh * act)));
                    if jac {
                        let jb = linvec_jac(&tr.axis.b, d_b);
                        let ja = linvec_jac(&tr.axis.a, d_a);
                        torque_jac(x_bb, x_ba, x_ab, x_aa, hh * act, &jb, &ja, a.is_some());
                    }
                }
                // the angle step, and the spring and damper as the discrete gradient
                // F = f β (c̄ ∇s(q̄) − s̄ ∇c(q̄)) of `turn`
                let t0 = ws.ang[turn];
                let loaded = k_s != 0.0
                    || c_d != 0.0
                    || jt.stops.is_some()
                    || arm[0] != 0.0
                    || fric.is_some()
                    || !jt.acts.is_empty();
                if loaded {
                    let dqa = a.map_or(zero, |a| body_nodes(&ws.dq, a));
                    let dqb = body_nodes(&ws.dq, bb);
                    let [s0, c0] = turn_start(ws, tr, turn, a, bb);
                    let ds = row_increment(&tr.sin, qa_bar, qb_bar, &dqa, &dqb);
                    let dc = row_increment(&tr.cos, qa_bar, qb_bar, &dqa, &dqb);
                    let stops = jt.stops.as_ref();
                    let acts = (&jt.acts, held.inputs, held.gains);
                    let st = turn_step([s0, c0], [ds, dc], t0, k_s, c_d, stops, arm, fric, acts, h);
                    if st.fs == 0.0 && st.fc == 0.0 && st.jac == [0.0; 4] {
                        // stops that neither end of the step has reached, and nothing else
                        turn += 1;
                        continue;
                    }
                    let [ss, sc] = &tr.sparse;
                    let gs = add_sparse_row(ss, -hh * st.fs, p, jac, (fa, fb, &mut ws.cbody, cab));
                    let gc = add_sparse_row(sc, -hh * st.fc, p, jac, (fa, fb, &mut ws.cbody, cab));
                    if jac {
                        let xs = (&mut *x_ab, &mut *x_ba, &mut *x_aa, &mut *x_bb);
                        turn_jac(tr, p, (&gs, &gc), &st.jac, -hh, xs);
                    }
                }
                turn += 1;
            }
        }
    }
    if let Some(axes) = &jt.sph_axes {
        // relative rotation increment θᴮ − θᴬ of the two bodies
        let th_b = rotation_increment(&body_nodes(&ws.qn, bb), qb);
        let th_a = a.map_or(Vec3::zeros(), |a| {
            rotation_increment(&body_nodes(&ws.qn, a), qa)
        });
        let rel = th_b - th_a;
        let mut tv = -rel * (c_d / h);
        for (k, ax) in axes.iter().enumerate() {
            let act = jt.input.map_or(0.0, |i| held.inputs[i + k]);
            if act != 0.0 {
                let abar = ax.eval(qa_bar, qb_bar);
                tv += abar * act;
                if jac {
                    let jb = linvec_jac(&ax.b, d_b);
                    let ja = linvec_jac(&ax.a, d_a);
                    torque_jac(x_bb, x_ba, x_ab, x_aa, hh * act, &jb, &ja, a.is_some());
                }
            }
        }
        // friction: the bristle's torque on the relative rotation (`joint_friction`)
        let mut stiff = Mat3::identity() * (c_d / h);
        if let Some(fr) = &jt.friction {
            let s0 = sph_bristle(ws, jt.fric0, a, &ws.qn);
            let (f, k, _, _) = fr.step3(s0, rel, h);
            tv += f;
            stiff += k;
        }
        sph_t += tv;
        push_torque(&mut ws.mom, bb, a, &(sph_t * hh));
        if jac && stiff != Mat3::zeros() {
            // d(hh K (θᴮ − θᴬ))/dε through the exact ∂θ/∂ε of each body, K = −∂τ/∂θ
            let kap = stiff * hh;
            let qa_n = a.map_or(zero, |a| body_nodes(&ws.qn, a));
            let qb_n = body_nodes(&ws.qn, bb);
            let jb = kap * theta_jac(&qb_n, qb);
            let ja = a.map(|_| kap * theta_jac(&qa_n, qa));
            for r in 0..3 {
                for c in 0..3 {
                    let o = (r + 3) * 6 + 3 + c;
                    x_bb[o] += jb[(r, c)];
                    if let Some(ja) = &ja {
                        x_aa[o] += ja[(r, c)];
                        x_ab[o] -= jb[(r, c)];
                        x_ba[o] -= ja[(r, c)];
                    }
                }
            }
        }
    }
}

/// Where a row's node forces and couplings go: the parent's and the child's node forces, the
/// per-body node couplings and the parent–child coupling.
pub(crate) type NodeSinks<'a> = (
    &'a mut [Vec3; 4],
    &'a mut [Vec3; 4],
    &'a mut [[f64; 16]],
    &'a mut [f64; 16],
);

/// Adds `coef ∇g(q̄)` of `row` to the node forces `fa`, `fb` and (`jac`) `½ coef S` to the node
/// couplings (`cb` per body, `cab` parent–child); returns `∇g(q̄)` over the eight nodes.
pub(crate) fn add_dot_row(
    row: &DotRow,
    coef: f64,
    p: &Pair,
    jac: bool,
    sinks: NodeSinks<'_>,
) -> [Vec3; 8] {
    add_sparse_row(&SparseRow::new(row, p.a.is_some()), coef, p, jac, sinks)
}

/// [`add_dot_row`] of a row already compiled for the pair (`TurnRt::sparse`).
pub(crate) fn add_sparse_row(
    sr: &SparseRow,
    coef: f64,
    p: &Pair,
    jac: bool,
    (fa, fb, cb, cab): NodeSinks<'_>,
) -> [Vec3; 8] {
    let mut buf = [Vec3::zeros(); 8];
    let grad = sr.grad_at(&p.qa_bar, &p.qb_bar, &mut buf);
    sr.add_forces(grad, coef, fa, fb);
    if jac {
        sr.add_hessian(0.5 * coef, cb, p.a, p.b, cab);
    }
    sr.expand(grad)
}

/// The projected gradients of a turn coordinate's `s` and `c` that [`turn_jac`] forms, child
/// then parent (6-vectors on the body twists; the parent's zero for the world): rows
/// `∇s(q)Q`, `∇c(q)Q` at the iterate and columns `P̄ᵀ∇s(q̄)`, `P̄ᵀ∇c(q̄)` at the midpoint.
pub(crate) struct TurnRows {
    /// `[∇s(q)Q]` child, parent.
    pub rs: [[f64; 6]; 2],
    /// `[∇c(q)Q]` child, parent.
    pub rc: [[f64; 6]; 2],
    /// `[P̄ᵀ∇s(q̄)]` child, parent.
    pub cs: [[f64; 6]; 2],
    /// `[P̄ᵀ∇c(q̄)]` child, parent.
    pub cc: [[f64; 6]; 2],
}

/// The Jacobian blocks of a turn load `scale (f_s ∇s(q̄) + f_c ∇c(q̄))` through the load's
/// coefficients: `Σᵢⱼ scale ∂fᵢ/∂j₁ P̄ᵀ∇i(q̄) ⊗ ∇j(q)Q` with `dfs = [∂f_s/∂s₁, ∂f_s/∂c₁,
/// ∂f_c/∂s₁, ∂f_c/∂c₁]` and the midpoint gradients `gs`, `gc` over the eight nodes (the
/// Hessian of `s`, `c` at fixed coefficients is [`add_dot_row`]'s); returns the projected
/// gradients it formed.
pub(crate) fn turn_jac(
    tr: &TurnRt,
    p: &Pair,
    (gs, gc): (&[Vec3; 8], &[Vec3; 8]),
    dfs: &[f64; 4],
    scale: f64,
    (x_ab, x_ba, x_aa, x_bb): (
        &mut [f64; 36],
        &mut [f64; 36],
        &mut [f64; 36],
        &mut [f64; 36],
    ),
) -> TurnRows {
    let mut g1 = [Vec3::zeros(); 8];
    tr.sin.gradient(&p.qa, &p.qb, &mut g1);
    let (rs_b, rs_a) = (row_q(&g1[4..], &p.d_b), row_q(&g1[..4], &p.d_a));
    tr.cos.gradient(&p.qa, &p.qb, &mut g1);
    let (rc_b, rc_a) = (row_q(&g1[4..], &p.d_b), row_q(&g1[..4], &p.d_a));
    let mix = |ws_: f64, wc: f64, rs: &[f64; 6], rc: &[f64; 6]| {
        std::array::from_fn::<f64, 6, _>(|i| scale * (ws_ * rs[i] + wc * rc[i]))
    };
    let j = dfs;
    let (ms_b, mc_b) = (mix(j[0], j[1], &rs_b, &rc_b), mix(j[2], j[3], &rs_b, &rc_b));
    let (cs_b, cc_b) = (project(&gs[4..], &p.dbar_b), project(&gc[4..], &p.dbar_b));
    outer(x_bb, 1.0, &cs_b, &ms_b);
    outer(x_bb, 1.0, &cc_b, &mc_b);
    let (mut cs_a, mut cc_a) = ([0.0; 6], [0.0; 6]);
    if p.a.is_some() {
        let (ms_a, mc_a) = (mix(j[0], j[1], &rs_a, &rc_a), mix(j[2], j[3], &rs_a, &rc_a));
        (cs_a, cc_a) = (project(&gs[..4], &p.dbar_a), project(&gc[..4], &p.dbar_a));
        outer(x_ba, 1.0, &cs_b, &ms_a);
        outer(x_ba, 1.0, &cc_b, &mc_a);
        outer(x_ab, 1.0, &cs_a, &ms_b);
        outer(x_ab, 1.0, &cc_a, &mc_b);
        outer(x_aa, 1.0, &cs_a, &ms_a);
        outer(x_aa, 1.0, &cc_a, &mc_a);
    }
    TurnRows {
        rs: [rs_b, rs_a],
        rc: [rc_b, rc_a],
        cs: [cs_b, cs_a],
        cc: [cc_b, cc_a],
    }
}

/// Value of the actuator input driving dof `dk` of a joint whose inputs start at `first`,
/// clamped to `±effort`.
pub(crate) fn actuator_input(dk: usize, inputs: &[f64], first: usize, effort: f64) -> f64 {
    inputs
        .get(first + dk)
        .copied()
        .unwrap_or(0.0)
        .clamp(-effort, effort)
}

/// Adds what joint `p` accumulated in `acc` (its loads and, in the multiplier form, its rows)
/// to the node residual and, if `jac`, to the bodies' diagonal blocks; completes the coupling
/// blocks `acc.x_ab` (parent rows, child columns) and `acc.x_ba`. True if those are to be
/// used (a Jacobian pass of a joint with a parent body).
pub(crate) fn apply_joint(ws: &mut Work, p: &Pair, acc: &mut Acc, jac: bool) -> bool {
    let (a, bb) = (p.a, p.b);
    if let Some(a) = a {
        for k in 0..4 {
            let v = read3(&ws.rn, 12 * a + 3 * k) + acc.fa[k];
            write3(&mut ws.rn, 12 * a + 3 * k, &v);
        }
    }
    for k in 0..4 {
        let v = read3(&ws.rn, 12 * bb + 3 * k) + acc.fb[k];
        write3(&mut ws.rn, 12 * bb + 3 * k, &v);
    }
    if !jac {
        return false;
    }
    for (x, y) in ws.xbody[bb].iter_mut().zip(&acc.x_bb) {
        *x += y;
    }
    let Some(a) = a else { return false };
    for (x, y) in ws.xbody[a].iter_mut().zip(&acc.x_aa) {
        *x += y;
    }
    // the extra blocks complete in place (zeroed again for the next joint)
    node_block(&acc.cab, &p.dbar_a, &p.d_b, &mut acc.x_ab);
    let mut cba = [0.0; 16];
    for n in 0..4 {
        for m in 0..4 {
            cba[4 * n + m] = acc.cab[4 * m + n];
        }
    }
    node_block(&cba, &p.dbar_b, &p.d_a, &mut acc.x_ba);
    true
}

/// A spherical joint's friction bristle (kept in the parent's axes at `fric0`, `ws.fric`) in
/// world axes with the parent's directors at the nodes `q` (`joint_friction`).
pub(crate) fn sph_bristle(ws: &Work, fric0: usize, parent: Option<usize>, q: &[f64]) -> Vec3 {
    let s = read3(&ws.fric, fric0);
    match parent {
        Some(a) => {
            let n = body_nodes(q, a);
            n[1] * s.x + n[2] * s.y + n[3] * s.z
        }
        None => s,
    }
}
