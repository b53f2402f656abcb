//! The tangent map of the step: exact derivatives of a stage's end `(q_{n+1}, v_{n+1})` with
//! respect to its start `(qₙ, vₙ)` and the inputs `u`, by the implicit function theorem on the
//! converged stage; carried through every stage and step of a run (`Work::tangent`).
//!
//! A perturbation of the state is a column: per body the twist increment `ξ = (δφ, δθ)` of its
//! coordinates (`δdᵢ = δθ × dᵢ`: the directors stay orthonormal, as the Newton update keeps
//! them), the nodal velocity perturbation `δv` (12 per body) and the input perturbation `δu`.
//! The stage solves `r(z; qₙ, vₙ, u) = 0` for `z = (q_{n+1}, μ)` (the multiplier form,
//! `newton`; the reduced iteration has the same root), so
//!
//! ```text
//! J_z X = −(∂r/∂qₙ Q(qₙ) ξ + ∂r/∂vₙ δv + ∂r/∂u δu)      J_z: the Newton matrix at the root
//! ∂r/∂vₙ δv = −h P̄ᵀ M δv                                 (joint rows: 0)
//! ∂r/∂qₙ Q(qₙ) ξ = J_sw ξ − 2 P̄ᵀ M Q(qₙ) ξ
//! ∂r/∂u δu = Σⱼ δuⱼ (r(u + s eⱼ) − r(u − s eⱼ)) / 2s     (r is affine in u; exact)
//! ξ' = X (its body part),  δq_{n+1} = Q(q_{n+1}) ξ',  δv_{n+1} = (2/h)(δq_{n+1} − δqₙ) − δvₙ
//! ```
//!
//! `J_sw` is the body block of the Newton matrix evaluated with the stage's ends swapped: the
//! iterate at `qₙ`, the start at `q_{n+1}` with rate `−v_{n+1}` (so `a = Δq − h vₙ` and the node
//! residual are unchanged), the turn angles swapped and every damper (joint, stop, a joint
//! actuator's rate term) negated.
//! Each load of the step is a function of `q̄` (symmetric in the ends), a discrete gradient
//! (symmetric in its ends) or a damper odd in the increment; swapped and negated, each is the
//! same function of `(qₙ, q_{n+1})` as before, so its derivative in the iterate is its derivative
//! in `qₙ`. Only the inertia `M (q − qₙ − h vₙ)` changes sign: hence `−2 P̄ᵀ M Q`.
//! The multipliers of the root are refined first by one solve (the residual is linear in `μ`),
//! since the reduced iteration does not carry them.
//!
//! Rotors (armature `a`, rate `ω` a state of the stage): their load `ρ = a (Δt − h ω₀) D` (`D` the
//! coordinate's discrete gradient, symmetric in the ends) is an inertia in `Δt`, so the swapped
//! evaluation (rotors started at `−ω₁`, the same value of `ρ`) takes its `Δt`-share with the
//! wrong sign; with `ṫ(ξ)` the coordinate's rate along a column at either end,
//!
//! ```text
//! ∂r/∂ω₀ δω = −a h P̄ᵀD δω,   correction −2a ṫₙ(ξ) P̄ᵀD,   δω₁ = (2/h)(ṫ₁(ξ') − ṫₙ(ξ)) − δω₀
//! ```
//!
//! A coupling's row `q_b(q_{n+1}) − r q_a(q_{n+1}) − o` does not depend on the start: its
//! right-hand side is the coupling's rate along the column at the end less that at the start.
//!
//! Cost per stage: two factorisations of the Newton matrix, one of the swapped one's assembly,
//! two residual evaluations per group of inputs that load disjoint bodies (a chain's joint
//! torques: two groups), and per column one product with the two Jacobians' summed body rows
//! and one back-substitution (four columns at a time, `linalg::tree::lanes`), each O(N) on a
//! tree.
//! Ground contact: its exact block replaces Newton's in the matrix at the root, the swapped
//! evaluations leave it out, and each column adds its share with both ends and the bristles
//! moved, then carries the bristles to the end (`contact_tangent`). Body–body contact marks
//! the tangent inexact; joint friction is not covered (`run::step_map` refuses it before a
//! tangent exists). Loop-closing joints are: their rows' right-hand sides go to the border of the
//! bordered solve and its off-tree couplings `X` join the products with the assembled matrix
//! (`linalg::border`).
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use super::contact::touching_features;
use super::contact_tangent::{bristle_column, column_share, moved, touching_points};
use super::error::StepError;
use super::increment::coupling_entry;
use super::joint_loads::Pair;
use super::newton::{evaluate, resolve, solve, stage_rates, Held, Mode, Work};
pub use super::tangent_state::Tangent;
use super::turn::{row_increment, turn_load};
use super::work::ContactJacobian;
use crate::math::{Mat3, Vec3};
use crate::mechanics::linalg::tree::lanes::{solve_factored_lanes, Lanes, LANES};
use crate::mechanics::linalg::tree::NMAX;
use crate::mechanics::model::constraint::DotRow;
use crate::mechanics::model::constraint::{body_nodes, read3, LinVec};
use crate::mechanics::model::kernels::project;
use crate::mechanics::model::runtime::{DofRt, InputSlot, Model};

impl Tangent {
    /// Carries the columns through the stage of size `h` that converged in `ws` (start `ws.qn`,
    /// `ws.vn`, end `ws.q`; called before the workspace moves to the end), module formulas.
    ///
    /// # Errors
    /// [`StepError::Singular`] when the Newton matrix at the root is singular.
    pub(crate) fn stage(
        &mut self,
        model: &Model,
        ws: &Work,
        held: &Held,
        h: f64,
    ) -> Result<(), StepError> {
        let nb = model.bodies.len();
        let nin = model.inputs.len();
        self.keep_start();
        // the Newton matrix at the root, with the root's multipliers
        let mut wt = ws.clone();
        wt.contact_jacobian = ContactJacobian::Exact;
        evaluate(model, &mut wt, held, h, Mode::Full);
        if !solve(model, &mut wt) {
            return Err(StepError::Singular);
        }
        for (j, jt) in model.joints.iter().enumerate() {
            for k in 0..jt.rows.len() {
                wt.mu[jt.row0 + k] += mu_entry(model, &wt, j, k);
            }
        }
        for (c, cp) in model.couplings.iter().enumerate() {
            wt.mu[cp.row] += coupling_entry(model, &wt, c);
        }
        evaluate(model, &mut wt, held, h, Mode::Full);
        if !solve(model, &mut wt) {
            return Err(StepError::Singular);
        }
        // the Jacobian's terms besides the inertia, at the root and swapped (module docs)
        let mut wz = ws.clone();
        wz.mu.copy_from_slice(&wt.mu);
        wz.inertia_in_jacobian = false;
        wz.contact_jacobian = ContactJacobian::Off;
        evaluate(model, &mut wz, held, h, Mode::Full);
        let mut sw = ws.clone();
        sw.mu.copy_from_slice(&wt.mu);
        sw.inertia_in_jacobian = false;
        sw.contact_jacobian = ContactJacobian::Off;
        let two_over_h = 2.0 / h;
        for i in 0..12 * nb {
            let v1 = ws.vn[i] + ws.vlo[i] + wt.acc[i] * two_over_h;
            sw.vn[i] = -v1;
            sw.vlo[i] = 0.0;
            sw.qn[i] = ws.q[i];
            sw.q[i] = ws.qn[i];
            sw.dq[i] = -ws.dq[i];
        }
        sw.ang.copy_from_slice(&ws.ang1);
        sw.ang1.copy_from_slice(&ws.ang);
        // a new stage start: the turn rows' start values are read anew (`Work::sc0`)
        sw.stage_id += 1;
        // the rotors start at −ω₁, so that their load −(2a/h²)(Δt − hω₀) keeps its value
        for (w, w1) in sw.arm.iter_mut().zip(&ws.arm1) {
            *w = -w1;
        }
        stage_rates(&mut sw, h);
        let negated: Vec<f64> = held.damping.iter().map(|c| -c).collect();
        let held_sw = Held {
            inputs: held.inputs,
            damping: &negated,
            stiffness: held.stiffness,
            gains: held.gains,
        };
        let mirror = self.mirror.as_deref().unwrap_or(model);
        evaluate(mirror, &mut sw, &held_sw, h, Mode::Full);
        let ru = self.input_columns(model, ws, &wt.mu, held, h);
        if self.inexact.is_none() {
            self.inexact = touching_features(model, ws, h);
        }
        let ground = model.contact.ground.as_ref();
        let ng = ground.map_or(0, |g| g.points.len());
        let touching = ground
            .map(|g| touching_points(g, ws, h))
            .unwrap_or_default();
        // per column: the end's twists and the start's bristles, for the bristles' columns
        let (mut xi_end, mut ds0) = (vec![0.0; 6 * nb], vec![0.0; 3 * ng]);
        let rotors = rotors(model, ws, h);
        let nf = model.nfric;
        let na = model.narm;
        // per column: the right-hand side, one solve, the end's perturbation
        let nr = model.nrows;
        let mut ys = vec![0.0; 6 * nb + nr];
        // the body rows of the two Jacobians' sum, once per stage (trees in blocks)
        let summed = (!model.dense).then(|| BodyRows::sum(model, &wz, &sw));
        let forms = row_forms(model, ws);
        // per body, the inertia's share `Σᵢ d̄ᵢ × Σⱼ Eᵢⱼ (δθ × Δdⱼ − h δḋⱼ)` as
        // `M_θ δθ − h Σⱼ ẽⱼ × δḋⱼ`: ẽⱼ = Σᵢ Eᵢⱼ d̄ᵢ, M_θ = Σⱼ ((ẽⱼ·Δdⱼ) 1 − Δdⱼ ẽⱼᵀ)
        let inertia_forms: Vec<(Mat3, [Vec3; 3])> = (0..nb)
            .map(|b| {
                let (qbar, inc) = (body_nodes(&ws.qbar, b), body_nodes(&ws.dq, b));
                let e = &model.bodies[b].e;
                let et: [Vec3; 3] = std::array::from_fn(|j| {
                    qbar[1] * e[(0, j)] + qbar[2] * e[(1, j)] + qbar[3] * e[(2, j)]
                });
                let mut mth = Mat3::zeros();
                for j in 0..3 {
                    mth +=
                        Mat3::identity() * et[j].dot(&inc[j + 1]) - inc[j + 1] * et[j].transpose();
                }
                (mth, et)
            })
            .collect();
        // per column: the right-hand side, one solve, the end's perturbation; in groups of
        // `LANES` columns solved together where the tree's factors stand alone
        let lanes_ok = !model.dense && !wt.border.is_active();
        let mut ybuf = vec![vec![0.0; 6 * nb + nr]; LANES];
        let mut rates = vec![vec![0.0; rotors.len()]; LANES];
        let mut lanes: Vec<Lanes> = if lanes_ok {
            vec![[[0.0; LANES]; NMAX]; nb]
        } else {
            Vec::new()
        };
        let mut sol = vec![[0.0; 6]; nb];
        for c0 in (0..self.cols).step_by(LANES) {
            let width = LANES.min(self.cols - c0);
            for l in 0..width {
                let c = c0 + l;
                let (y, rate_n) = (&mut ybuf[l], &mut rates[l]);
                let xi = &self.xi[c * 6 * nb..(c + 1) * 6 * nb];
                let dv = &self.dv[c * 12 * nb..(c + 1) * 12 * nb];
                let du = &self.du[c * nin..(c + 1) * nin];
                // a column at rest (an input's, at the map's start) loads only through its input
                if xi.iter().chain(dv).all(|&x| x == 0.0) {
                    y.fill(0.0);
                } else {
                    if let Some(sum) = &summed {
                        sum.times(model, [&wz, &sw], xi, y, &mut ys);
                    } else {
                        matvec(model, &wz, xi, y);
                        matvec(model, &sw, xi, &mut ys);
                    }
                    joint_rows(model, ws, &forms, xi, &mut y[6 * nb..]);
                    for b in 0..nb {
                        let br = &model.bodies[b];
                        let (mth, et) = &inertia_forms[b];
                        let dth = read3(xi, 6 * b + 3);
                        // P̄ᵀ M ((Q_{n+1} − Qₙ) ξ − h δv): the inertia's share, free of cancellation
                        let f = read3(dv, 12 * b) * (-h * br.mass);
                        let mut m = mth * dth;
                        for j in 0..3 {
                            m -= et[j].cross(&read3(dv, 12 * b + 3 + 3 * j)) * h;
                        }
                        for k in 0..3 {
                            y[6 * b + k] += ys[6 * b + k] + f[k];
                            y[6 * b + 3 + k] += ys[6 * b + 3 + k] + m[k];
                        }
                    }
                }
                for (i, &d) in du.iter().enumerate() {
                    if d != 0.0 {
                        for e in 0..6 * nb {
                            y[e] += d * ru[i * 6 * nb + e];
                        }
                    }
                }
                // the ground contact's share, both ends and the bristles moved (`contact_tangent`)
                if let Some(g) = ground {
                    let ds = &self.ds[c * 3 * ng..(c + 1) * 3 * ng];
                    if xi.iter().chain(ds).any(|&x| x != 0.0) {
                        column_share((g, &touching), ws, (xi, ds), h, y);
                    }
                }
                // the rotors: ∂r/∂ω₀ δω₀ = −a h P̄ᵀD δω₀, and the swapped evaluation's share of
                // the rotor load taken with the sign of an inertia (module docs): −2a ṫₙ(ξ) P̄ᵀD
                for (r, ro) in rotors.iter().enumerate() {
                    let jt = &model.joints[ro.joint];
                    let (pa, pb) = (jt.parent, Some(jt.child));
                    let at = |x: &[f64], b: Option<usize>| {
                        b.map_or([Vec3::zeros(); 4], |b| body_nodes(x, b))
                    };
                    rate_n[r] = coordinate_rate(
                        &jt.dofs[ro.dof],
                        &at(&ws.qn, pa),
                        &at(&ws.qn, pb),
                        &perturbation(&ws.qn, xi, pa),
                        &perturbation(&ws.qn, xi, pb),
                    );
                    let mut k = ro.index.map_or(0.0, |i| {
                        let w0 = self.dw[c * na + i];
                        -jt.armature * (h * w0 + 2.0 * rate_n[r])
                    });
                    // friction: its swapped share is the mirrored law's (`Tangent::mirror`),
                    // left is the bristle's, −(h²/2) ∂F/∂s₀ δs₀ P̄ᵀD
                    if let Some((i, [dfds, _, _])) = ro.fric {
                        k -= 0.5 * h * h * dfds * self.df[c * nf + i];
                    }
                    for e in 0..6 {
                        y[6 * jt.child + e] += k * ro.col_b[e];
                        if let Some(a) = pa {
                            y[6 * a + e] += k * ro.col_a[e];
                        }
                    }
                }
            }
            if lanes_ok {
                // J_z Y = −y for X = ξ + Y, every column of the group at once
                for (b, lb) in lanes.iter_mut().enumerate() {
                    for k in 0..6 {
                        for l in 0..LANES {
                            lb[k][l] = if l < width { -ybuf[l][6 * b + k] } else { 0.0 };
                        }
                    }
                    for k in 6..NMAX {
                        lb[k] = [0.0; LANES];
                    }
                }
                for jt in &model.joints {
                    for k in 0..jt.rows.len() {
                        for l in 0..width {
                            lanes[jt.child][6 + k][l] = -ybuf[l][6 * nb + jt.row0 + k];
                        }
                    }
                }
                solve_factored_lanes(&wt.blocks, &model.order, &model.parent, &mut lanes);
            }
            for l in 0..width {
                let c = c0 + l;
                let rate_n = &rates[l];
                if lanes_ok {
                    for (b, sb) in sol.iter_mut().enumerate() {
                        *sb = std::array::from_fn(|k| lanes[b][k][l]);
                    }
                } else {
                    // J_z Y = −y for X = ξ + Y
                    set_rhs(model, &mut wt, &ybuf[l]);
                    resolve(model, &mut wt);
                    for (b, sb) in sol.iter_mut().enumerate() {
                        *sb = std::array::from_fn(|k| rhs_entry(model, &wt, b, k));
                    }
                }
                // the bristles at the end: along ξ at the start, ξ + Y at the end
                if let Some(g) = ground {
                    let xi = &self.xi[c * 6 * nb..(c + 1) * 6 * nb];
                    for (b, sb) in sol.iter().enumerate() {
                        for k in 0..6 {
                            xi_end[6 * b + k] = xi[6 * b + k] + sb[k];
                        }
                    }
                    let ds = &mut self.ds[c * 3 * ng..(c + 1) * 3 * ng];
                    ds0.copy_from_slice(ds);
                    bristle_column((g, &touching), ws, [xi, &xi_end], &ds0, h, ds);
                }
                // δa = Q_{n+1} Y + (Q_{n+1} − Qₙ) ξ − h δv,  δv_{n+1} = δv + (2/h) δa
                let dvc = &mut self.dv[c * 12 * nb..(c + 1) * 12 * nb];
                let xic = &mut self.xi[c * 6 * nb..(c + 1) * 6 * nb];
                for b in 0..nb {
                    let (n1, inc) = (body_nodes(&ws.q, b), body_nodes(&ws.dq, b));
                    let yb = sol[b];
                    let (yp, yt) = (
                        Vec3::new(yb[0], yb[1], yb[2]),
                        Vec3::new(yb[3], yb[4], yb[5]),
                    );
                    let dth = read3(xic, 6 * b + 3);
                    let da: [Vec3; 4] = [
                        yp,
                        yt.cross(&n1[1]) + dth.cross(&inc[1]),
                        yt.cross(&n1[2]) + dth.cross(&inc[2]),
                        yt.cross(&n1[3]) + dth.cross(&inc[3]),
                    ];
                    for k in 0..4 {
                        for a in 0..3 {
                            let o = 12 * b + 3 * k + a;
                            let v = dvc[o];
                            dvc[o] = v + two_over_h * (da[k][a] - h * v);
                        }
                    }
                    for k in 0..6 {
                        xic[6 * b + k] += yb[k];
                    }
                }
                // ω₁ = 2Δt/h − ω₀: δω₁ = (2/h)(ṫ₁(ξ') − ṫₙ(ξ)) − δω₀; the friction bristles
                for (r, ro) in rotors.iter().enumerate() {
                    let jt = &model.joints[ro.joint];
                    let (pa, pb) = (jt.parent, Some(jt.child));
                    let at = |x: &[f64], b: Option<usize>| {
                        b.map_or([Vec3::zeros(); 4], |b| body_nodes(x, b))
                    };
                    let rate_1 = coordinate_rate(
                        &jt.dofs[ro.dof],
                        &at(&ws.q, pa),
                        &at(&ws.q, pb),
                        &perturbation(&ws.q, xic, pa),
                        &perturbation(&ws.q, xic, pb),
                    );
                    if let Some(i) = ro.index {
                        let w = &mut self.dw[c * na + i];
                        *w = two_over_h * (rate_1 - rate_n[r]) - *w;
                    }
                    // the bristle: δs₁ = ∂s₁/∂s₀ δs₀ + ∂s₁/∂u (ṫ₁(ξ') − ṫₙ(ξ))
                    if let Some((i, [_, dsds, dsdu])) = ro.fric {
                        let s = &mut self.df[c * nf + i];
                        *s = dsds * *s + dsdu * (rate_1 - rate_n[r]);
                    }
                }
            }
        }
        Ok(())
    }

    /// The inputs' columns of `r` (6 per body each) at the root `ws` with multipliers `mu`:
    /// central differences of the residual, exact as `r` is affine in `u` (module docs);
    /// inputs no column moves are left 0. Inputs that load disjoint bodies are perturbed
    /// together (`input_groups`): one pair of evaluations per group, each input's column read
    /// on its own bodies.
    fn input_columns(&self, model: &Model, ws: &Work, mu: &[f64], held: &Held, h: f64) -> Vec<f64> {
        let nb = model.bodies.len();
        let nin = model.inputs.len();
        let mut ru = vec![0.0; 6 * nb * nin];
        let mut inputs = held.inputs.to_vec();
        // one scratch copy: a residual evaluation rewrites every right-hand side it reads
        let mut wr = ws.clone();
        wr.mu.copy_from_slice(mu);
        let steps: Vec<f64> = (0..nin)
            .map(|i| {
                let used = (0..self.cols).any(|c| self.du[c * nin + i] != 0.0);
                if used {
                    step_for(model, i, held.inputs[i])
                } else {
                    0.0
                }
            })
            .collect();
        let mut r = [vec![0.0; 6 * nb], vec![0.0; 6 * nb]];
        for group in input_groups(model, &steps) {
            for (side, sign) in [(0, 1.0), (1, -1.0)] {
                for &(i, _) in &group {
                    inputs[i] = held.inputs[i] + sign * steps[i];
                }
                let hi = Held {
                    inputs: &inputs,
                    damping: held.damping,
                    stiffness: held.stiffness,
                    gains: held.gains,
                };
                evaluate(model, &mut wr, &hi, h, Mode::Residual);
                for b in 0..nb {
                    for k in 0..6 {
                        // the right-hand side holds −r
                        r[side][6 * b + k] = -rhs_entry(model, &wr, b, k);
                    }
                }
            }
            for &(i, bodies) in &group {
                inputs[i] = held.inputs[i];
                let s = steps[i];
                let mut take = |b: usize| {
                    for e in 6 * b..6 * b + 6 {
                        ru[i * 6 * nb + e] = (r[0][e] - r[1][e]) / (2.0 * s);
                    }
                };
                match bodies {
                    Some(bs) => bs.into_iter().flatten().for_each(&mut take),
                    None => (0..nb).for_each(&mut take),
                }
            }
        }
        ru
    }
}

/// The bodies an input loads directly: a joint's input its two bodies, a body load its body;
/// `None` when not known (then it is perturbed alone and read on every body).
fn input_bodies(model: &Model, i: usize) -> Option<[Option<usize>; 2]> {
    let joint = |j: usize| {
        let jt = &model.joints[j];
        [jt.parent, Some(jt.child)]
    };
    match model.inputs[i] {
        InputSlot::JointTorque { joint: j, .. } | InputSlot::JointForce { joint: j } => {
            Some(joint(j))
        }
        InputSlot::BodyTorque { body, .. } | InputSlot::BodyForce { body, .. } => {
            Some([Some(body), None])
        }
        InputSlot::ActuatorCtrl { .. } => model
            .joints
            .iter()
            .position(|jt| jt.acts.list.iter().any(|a| a.input == i))
            .map(joint),
    }
}

/// The inputs with a non-zero step, in groups whose members load disjoint bodies (greedy, in
/// input order; an input of unknown bodies alone), each with its bodies.
#[allow(clippy::type_complexity)]
fn input_groups(model: &Model, steps: &[f64]) -> Vec<Vec<(usize, Option<[Option<usize>; 2]>)>> {
    let nb = model.bodies.len();
    let mut groups: Vec<Vec<(usize, Option<[Option<usize>; 2]>)>> = Vec::new();
    // per group, the bodies it loads
    let mut taken: Vec<Vec<bool>> = Vec::new();
    for (i, &s) in steps.iter().enumerate() {
        if s == 0.0 {
            continue;
        }
        let Some(bodies) = input_bodies(model, i) else {
            groups.push(vec![(i, None)]);
            taken.push(vec![true; nb]);
            continue;
        };
        let free = |t: &Vec<bool>| bodies.iter().flatten().all(|&b| !t[b]);
        let g = match taken.iter().position(free) {
            Some(g) => g,
            None => {
                groups.push(Vec::new());
                taken.push(vec![false; nb]);
                groups.len() - 1
            }
        };
        for &b in bodies.iter().flatten() {
            taken[g][b] = true;
        }
        groups[g].push((i, Some(bodies)));
    }
    groups
}

/// The linear part of `v` at the nodes `qa`, `qb` (its constant left out).
#[inline]
fn linear(v: &LinVec, qa: &[Vec3; 4], qb: &[Vec3; 4]) -> Vec3 {
    let mut out = Vec3::zeros();
    for k in 0..4 {
        out += qa[k] * v.a[k] + qb[k] * v.b[k];
    }
    out
}

/// Per joint row (by its index among the rows), its right-hand side in `joint_rows` as a
/// linear form on the columns' twists, `G_A·ξ_A + G_B·ξ_B` (6 each; `G_A` zero for the world),
/// formed once per stage from `(u₁, w₁, Δu, Δw)` (function docs): with `δ₀[0] = δφ`,
/// `δ₀[k] = δθ × nₖ`, `Δδ[k] = δθ × Δdₖ` (k ≥ 1) and `(δθ × x)·y = δθ·(x × y)`,
///
/// ```text
/// G.φ = c_w[0] Δu + c_u[0] Δw
/// G.θ = Σ_{k≥1} c_w[k] (Δdₖ × u₁ + nₖ × Δu) + c_u[k] (Δdₖ × w₁ + nₖ × Δw)
/// ```
///
/// (`c` the row's coefficients of the body's nodes; every term O(h), as in `joint_rows`).
fn row_forms(model: &Model, ws: &Work) -> Vec<[[f64; 6]; 2]> {
    let zero = [Vec3::zeros(); 4];
    let of = |x: &[f64], b: Option<usize>| b.map_or(zero, |b| body_nodes(x, b));
    let mut out = vec![[[0.0; 6]; 2]; model.nrows];
    for jt in &model.joints {
        let (a, b) = (jt.parent, Some(jt.child));
        let (qa1, qb1) = (of(&ws.q, a), of(&ws.q, b));
        let (dqa, dqb) = (of(&ws.dq, a), of(&ws.dq, b));
        let (n0a, n0b) = (of(&ws.qn, a), of(&ws.qn, b));
        for (k, row) in jt.rows.iter().enumerate() {
            let (u1, w1) = (row.u.eval(&qa1, &qb1), row.w.eval(&qa1, &qb1));
            let (du, dw) = (linear(&row.u, &dqa, &dqb), linear(&row.w, &dqa, &dqb));
            let form = |cw: &[f64; 4], cu: &[f64; 4], n0: &[Vec3; 4], inc: &[Vec3; 4]| {
                let phi = du * cw[0] + dw * cu[0];
                let mut th = Vec3::zeros();
                for i in 1..4 {
                    th += (inc[i].cross(&u1) + n0[i].cross(&du)) * cw[i]
                        + (inc[i].cross(&w1) + n0[i].cross(&dw)) * cu[i];
                }
                [phi.x, phi.y, phi.z, th.x, th.y, th.z]
            };
            let ga = if a.is_some() {
                form(&row.w.a, &row.u.a, &n0a, &dqa)
            } else {
                [0.0; 6]
            };
            out[jt.row0 + k] = [ga, form(&row.w.b, &row.u.b, &n0b, &dqb)];
        }
    }
    out
}

/// The joint rows' right-hand side `∇g(q_{n+1}) Q_{n+1} ξ − ∇g(qₙ) Qₙ ξ` (the second term is 0
/// for a column tangent to the rows at `qₙ`, but for round-off that is carried, not corrected),
/// free of cancellation: for `g = u·w − c` with `u`, `w` affine in the nodes (linear parts
/// `L_u`, `L_w`), `δ₀ = Qₙ ξ`, `Δδ = (Q_{n+1} − Qₙ) ξ = (0, δθ × Δdᵢ)` and `Δu = L_u(Δq)`:
///
/// ```text
/// L_w(Δδ)·u₁ + L_w(δ₀)·Δu + L_u(Δδ)·w₁ + L_u(δ₀)·Δw
/// ```
///
/// (the value `O(h)|ξ|` is formed from terms of its own size, not from `O(|ξ|)` ones).
fn joint_rows(model: &Model, ws: &Work, forms: &[[[f64; 6]; 2]], xi: &[f64], out: &mut [f64]) {
    let zero = [Vec3::zeros(); 4];
    let of = |x: &[f64], b: Option<usize>| b.map_or(zero, |b| body_nodes(x, b));
    // the joint rows by their forms on the twists (`row_forms`)
    for jt in &model.joints {
        let xb = &xi[6 * jt.child..6 * jt.child + 6];
        let xa = jt.parent.map(|a| &xi[6 * a..6 * a + 6]);
        for k in 0..jt.rows.len() {
            let [ga, gb] = &forms[jt.row0 + k];
            out[jt.row0 + k] = dot_pair((gb, xb), (ga, xa));
        }
    }
    // a coupling's row g = q_b(q_{n+1}) − r q_a(q_{n+1}) − o does not depend on the stage's
    // start (its start angle and increment cancel): its right-hand side is the coupling's rate
    // along the column at the end, less that at the start (0 for a column tangent to it)
    for cp in &model.couplings {
        let mut v = 0.0;
        for (j, w) in [(cp.b, 1.0), (cp.a, -cp.ratio)] {
            let jt = &model.joints[j];
            let (a, b) = (jt.parent, Some(jt.child));
            let (d0a, d0b) = (perturbation(&ws.qn, xi, a), perturbation(&ws.qn, xi, b));
            let (d1a, d1b) = (perturbation(&ws.q, xi, a), perturbation(&ws.q, xi, b));
            let rate = |qa: &[Vec3; 4], qb: &[Vec3; 4], da: &[Vec3; 4], db: &[Vec3; 4]| {
                coordinate_rate(&jt.dofs[0], qa, qb, da, db)
            };
            v += w
                * (rate(&of(&ws.q, a), &of(&ws.q, b), &d1a, &d1b)
                    - rate(&of(&ws.qn, a), &of(&ws.qn, b), &d0a, &d0b));
        }
        out[cp.row] = v;
    }
}

/// A coordinate with a rotor (a joint's armature) or friction at the root of a stage: its
/// joint and coordinate, its index among the rotors, its friction bristle's index with the
/// law's partials `[∂F/∂s₀, ∂s₁/∂s₀, ∂s₁/∂u]` at the root's increment, and the projected
/// discrete gradient `P̄ᵀD` of its coordinate on the joint's child and parent
/// (`D = β (c̄ ∇s(q̄) − s̄ ∇c(q̄))` of a turn, `∇s(q̄)` of a slide), the direction of its loads.
struct Rotor {
    joint: usize,
    dof: usize,
    index: Option<usize>,
    fric: Option<(usize, [f64; 3])>,
    col_b: [f64; 6],
    col_a: [f64; 6],
}

/// The coordinates with rotors or friction of `model` at the root `ws` (the midpoint
/// `ws.qbar`, the increments `ws.dq`) of a stage of size `h`.
fn rotors(model: &Model, ws: &Work, h: f64) -> Vec<Rotor> {
    let mut out = Vec::with_capacity(model.narm + model.nfric);
    for (j, jt) in model.joints.iter().enumerate() {
        if (jt.armature <= 0.0 && jt.friction.is_none()) || jt.sph_axes.is_some() {
            continue;
        }
        let p = Pair::new(ws, jt.parent, jt.child);
        let zero = [Vec3::zeros(); 4];
        let dqa = jt.parent.map_or(zero, |a| body_nodes(&ws.dq, a));
        let dqb = body_nodes(&ws.dq, jt.child);
        let qa_n = jt.parent.map_or(zero, |a| body_nodes(&ws.qn, a));
        let qb_n = body_nodes(&ws.qn, jt.child);
        for (dk, dof) in jt.dofs.iter().enumerate() {
            let grad = |row: &DotRow| {
                let mut g = [Vec3::zeros(); 8];
                row.gradient(&p.qa_bar, &p.qb_bar, &mut g);
                (project(&g[4..], &p.dbar_b), project(&g[..4], &p.dbar_a))
            };
            // the coordinate's increment as the residual took it
            let (col_b, col_a, inc) = match dof {
                DofRt::Slide(row) => {
                    let (b, a) = grad(row);
                    (b, a, row_increment(row, &p.qa_bar, &p.qb_bar, &dqa, &dqb))
                }
                DofRt::Turn(tr) => {
                    let (s0, c0) = (tr.sin.eval(&qa_n, &qb_n), tr.cos.eval(&qa_n, &qb_n));
                    let ds = row_increment(&tr.sin, &p.qa_bar, &p.qb_bar, &dqa, &dqb);
                    let dc = row_increment(&tr.cos, &p.qa_bar, &p.qb_bar, &dqa, &dqb);
                    let load = turn_load([s0, c0], [ds, dc], 1.0);
                    let u = load.unit;
                    let ((sb, sa), (cb, ca)) = (grad(&tr.sin), grad(&tr.cos));
                    (
                        std::array::from_fn(|e| u[0] * sb[e] + u[1] * cb[e]),
                        std::array::from_fn(|e| u[0] * sa[e] + u[1] * ca[e]),
                        load.step.dt,
                    )
                }
            };
            let fric = jt.friction.as_ref().map(|fr| {
                let i = jt.fric0 + dk;
                (i, fr.partials(ws.fric[i], inc, h))
            });
            out.push(Rotor {
                joint: j,
                dof: dk,
                index: (jt.armature > 0.0).then_some(jt.arm0 + dk),
                fric,
                col_b,
                col_a,
            });
        }
    }
    out
}

/// The node perturbations `[δφ, δθ × dᵢ]` of body `b` (zeros for the world) at nodes `q` for
/// the twist column `xi`.
fn perturbation(q: &[f64], xi: &[f64], b: Option<usize>) -> [Vec3; 4] {
    b.map_or([Vec3::zeros(); 4], |b| {
        moved(&body_nodes(q, b), &xi[6 * b..6 * b + 6])
    })
}

/// The rate of a joint's coordinate at nodes `qa`, `qb` along node perturbations `da`, `db`
/// (`DofRt::rate_gradient`).
fn coordinate_rate(
    dof: &DofRt,
    qa: &[Vec3; 4],
    qb: &[Vec3; 4],
    da: &[Vec3; 4],
    db: &[Vec3; 4],
) -> f64 {
    let g = dof.rate_gradient(qa, qb);
    (0..4)
        .map(|k| g[k].dot(&da[k]) + g[4 + k].dot(&db[k]))
        .sum()
}

/// The half-width of the central difference of input `i` at `u`: 1 (the residual is affine
/// in `u`, so any width is exact but for round-off), narrowed to stay inside an actuator's
/// effort limit (a joint actuator's control: inside its control range); 0 when the input is at
/// or beyond its limit (the clamped force does not move).
fn step_for(model: &Model, i: usize, u: f64) -> f64 {
    let act = model
        .joints
        .iter()
        .flat_map(|jt| &jt.acts.list)
        .find(|a| a.input == i);
    if let Some(a) = act {
        let room = (u - a.ctrl[0]).min(a.ctrl[1] - u);
        return if room <= 0.0 {
            0.0
        } else {
            (0.5 * room).min(1.0)
        };
    }
    let effort = model
        .joints
        .iter()
        .find(|jt| {
            jt.input
                .is_some_and(|first| (first..first + jt.dofs.len()).contains(&i))
                && jt.sph_axes.is_none()
        })
        .map_or(f64::INFINITY, |jt| jt.effort);
    let room = effort - u.abs();
    if room <= 0.0 {
        0.0
    } else {
        (0.5 * room).min(1.0)
    }
}

/// Entry `k` (< 6) of body `b`'s right-hand side (or solution) in the workspace's system.
fn rhs_entry(model: &Model, ws: &Work, b: usize, k: usize) -> f64 {
    if model.dense {
        ws.drhs[6 * b + k]
    } else {
        ws.blocks[b].r[k]
    }
}

/// The solution entry of multiplier `k` of joint `j` (after a solve).
fn mu_entry(model: &Model, ws: &Work, j: usize, k: usize) -> f64 {
    let jt = &model.joints[j];
    if model.dense {
        ws.drhs[6 * model.bodies.len() + jt.row0 + k]
    } else if let Some(l) = ws.border.lrow[j] {
        ws.border.rc[l + k]
    } else {
        ws.blocks[jt.child].r[6 + k]
    }
}

/// Sets the right-hand side to `−y` (the body rows, then the joint rows in `row0` order).
fn set_rhs(model: &Model, ws: &mut Work, y: &[f64]) {
    let nb = model.bodies.len();
    if model.dense {
        for (r, v) in ws.drhs.iter_mut().zip(y) {
            *r = -v;
        }
        return;
    }
    for b in 0..nb {
        for k in 0..6 {
            ws.blocks[b].r[k] = -y[6 * b + k];
        }
    }
    for (j, jt) in model.joints.iter().enumerate() {
        for k in 0..jt.rows.len() {
            let v = -y[6 * nb + jt.row0 + k];
            match ws.border.lrow.get(j).copied().flatten() {
                Some(l) => ws.border.rc[l + k] = v,
                None => ws.blocks[jt.child].r[6 + k] = v,
            }
        }
    }
    let nj = model.joints.len();
    for (c, cp) in model.couplings.iter().enumerate() {
        if let Some(l) = ws.border.lrow[nj + c] {
            ws.border.rc[l] = -y[6 * nb + cp.row];
        }
    }
}

/// `a·x + b·y` over six entries, `b·y` left out without `y` (a body at the ground).
#[inline(always)]
fn dot_pair((a, x): (&[f64], &[f64]), (b, y): (&[f64], Option<&[f64]>)) -> f64 {
    let mut v = 0.0;
    for e in 0..6 {
        v += a[e] * x[e];
    }
    if let Some(y) = y {
        for e in 0..6 {
            v += b[e] * y[e];
        }
    }
    v
}

/// The body rows of the sum of two Newton matrices in tree blocks, restricted to the body
/// columns (a column `X` has no multiplier part): per body its diagonal `D`, its parent's
/// columns `U` and its columns in the parent's rows `L`, 6 × 6 each.
struct BodyRows {
    d: Vec<[f64; 36]>,
    u: Vec<[f64; 36]>,
    l: Vec<[f64; 36]>,
}

impl BodyRows {
    /// The body rows of `a + b` (both assembled in blocks).
    fn sum(model: &Model, a: &Work, b: &Work) -> Self {
        let nb = model.bodies.len();
        let mut out = Self {
            d: vec![[0.0; 36]; nb],
            u: vec![[0.0; 36]; nb],
            l: vec![[0.0; 36]; nb],
        };
        for k in 0..nb {
            let (ba, bb) = (&a.blocks[k], &b.blocks[k]);
            for r in 0..6 {
                for s in 0..6 {
                    out.d[k][6 * r + s] = ba.d[r * NMAX + s] + bb.d[r * NMAX + s];
                    out.u[k][6 * r + s] = ba.u[r * 6 + s] + bb.u[r * 6 + s];
                    out.l[k][6 * r + s] = ba.l[r * NMAX + s] + bb.l[r * NMAX + s];
                }
            }
        }
        out
    }

    /// `y ← (A + B) x` on the body rows (`ys`, scratch, takes the loops' border couplings of
    /// the second; the joint rows of `y` are left for `joint_rows`).
    fn times(&self, model: &Model, ab: [&Work; 2], x: &[f64], y: &mut [f64], ys: &mut [f64]) {
        let nb = model.bodies.len();
        y[..6 * nb].fill(0.0);
        for b in 0..nb {
            let xb = &x[6 * b..6 * b + 6];
            let xp = model.parent[b].map(|p| &x[6 * p..6 * p + 6]);
            for r in 0..6 {
                let (d, u) = (&self.d[b][6 * r..6 * r + 6], &self.u[b][6 * r..6 * r + 6]);
                let acc = dot_pair((d, xb), (u, xp));
                y[6 * b + r] += acc;
            }
            if let Some(p) = model.parent[b] {
                for r in 0..6 {
                    let l = &self.l[b][6 * r..6 * r + 6];
                    let mut acc = 0.0;
                    for s in 0..6 {
                        acc += l[s] * xb[s];
                    }
                    y[6 * p + r] += acc;
                }
            }
        }
        for w in ab {
            if w.border.is_active() {
                ys[..6 * nb].fill(0.0);
                w.border.add_couplings_times(x, &mut ys[..6 * nb]);
                for (a, b) in y[..6 * nb].iter_mut().zip(&ys[..6 * nb]) {
                    *a += b;
                }
            }
        }
        ys[..6 * nb].fill(0.0);
    }
}

/// `y = J x` over the body columns of the assembled (not factored) Newton matrix of `ws`, every
/// row (the body rows, then the joint rows in `row0` order): the diagonal blocks `D`, the
/// parent couplings `U` (the child's rows) and `L` (the parent's body rows), and the border's
/// off-tree couplings of loop-closing joints (their rows' entries are overwritten by
/// `joint_rows`, so the border's row part `C_t` is not needed).
fn matvec(model: &Model, ws: &Work, x: &[f64], y: &mut [f64]) {
    let nb = model.bodies.len();
    y.fill(0.0);
    if model.dense {
        let nd = ws.drhs.len();
        for r in 0..nd {
            y[r] = (0..6 * nb).map(|s| ws.dense[r * nd + s] * x[s]).sum();
        }
        return;
    }
    // the row of entry r of block b in y
    let row = |b: usize, r: usize| -> usize {
        if r < 6 {
            6 * b + r
        } else {
            let j = model.tree_joint[b].expect("a block's rows belong to its tree joint");
            6 * nb + model.joints[j].row0 + r - 6
        }
    };
    for b in 0..nb {
        let blk = &ws.blocks[b];
        for r in 0..blk.n {
            let mut acc = 0.0;
            for s in 0..6 {
                acc += blk.d[r * NMAX + s] * x[6 * b + s];
            }
            if let Some(p) = model.parent[b] {
                for s in 0..6 {
                    acc += blk.u[r * 6 + s] * x[6 * p + s];
                }
            }
            y[row(b, r)] += acc;
        }
        if let Some(p) = model.parent[b] {
            for r in 0..6 {
                let mut acc = 0.0;
                for s in 0..6 {
                    acc += blk.l[r * NMAX + s] * x[6 * b + s];
                }
                y[6 * p + r] += acc;
            }
        }
    }
    if ws.border.is_active() {
        ws.border.add_couplings_times(x, &mut y[..6 * nb]);
    }
}
