//! Final pass of a stage at the converged iterate: what the velocity update, the work account,
//! the joint angles and the next predictor need, and nothing of the residual.
//!
//! ```text
//! a_b   = Δq_b − h vₙ,b                      (12 per body; v_{n+1} = vₙ + 2a/h in the caller)
//! θ_b   = ½ Σᵢ d̄ⁱ × Δdᵢ                      (rotation increment, rad, world frame)
//! W     = Σ f·Δφ + Σ m·θ_b + Σ_joints (τ n̄·(θ_B − θ_A) + F Δs − c Δs²/h − c Δϑ²/h
//!         − c_stop p̄ Δϑ²/h + τ_act Δ …)      (τ, F clamped to ±effort; τ_act: the joint
//!                                            actuators' `model::joint_actuator` force)
//! ϑ_{n+1} = ϑₙ + Δϑ                          (unwrapped joint angles)
//! ω_{n+1} = 2Δϑ/h − ωₙ                        (rotor rates of joints with an armature)
//! s_{n+1}, D                                 (joint friction bristles and their loss, in W)
//! ```
//!
//! The work terms are the exact discrete work of the loads as they enter the residual (the
//! consistent torques, the discrete gradients of the springs and dampers), summed in the order
//! of the residual evaluation. Angles of joints with a spring or damper take the step `Δϑ` of
//! the `atan2` discrete gradient (`turn::turn_step`), the angle the spring acted on; the other
//! angles are read off the directors: `ϑ_{n+1}` is `atan2(s₁, c₁)` shifted by a multiple of 2π
//! to lie nearest `ϑₙ` (`assemble::unwrap`), the same angle to round-off (`atan2(s, c)` is the
//! joint coordinate) at a fraction of the cost.
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use super::contact::contact_finish;
use super::joint_loads::{actuator_input, sph_bristle, turn_start};
use super::turn::{row_increment, turn_step};
use super::work::{Held, Work};
use crate::math::Vec3;
use crate::mechanics::model::assemble::unwrap;
use crate::mechanics::model::constraint::body_nodes;
use crate::mechanics::model::constraint::Nodes;
use crate::mechanics::model::constraint::{read3, write3};
use crate::mechanics::model::kernels::rotation_increment;
use crate::mechanics::model::runtime::{DofRt, Model};

/// Fills `ws.acc`, `ws.theta` and `ws.ang1` at the converged iterate `ws.q` (increments
/// `ws.dq`) of a stage of size `h` (s) and adds each joint's damper loss to `ws.loss`; returns
/// the stage's discrete work of the inputs minus the energy its dampers dissipated (J).
pub(crate) fn finish(model: &Model, ws: &mut Work, held: &Held, h: f64) -> f64 {
    let nb = model.bodies.len();
    ws.set_midpoint();
    for b in 0..nb {
        ws.set_acc(b);
        let th = rotation_increment(&body_nodes(&ws.qn, b), &body_nodes(&ws.q, b));
        for k in 0..3 {
            ws.theta[3 * b + k] = th[k];
        }
    }
    let mut work = 0.0;
    for &(b, at) in &model.body_forces {
        let f = Vec3::new(held.inputs[at], held.inputs[at + 1], held.inputs[at + 2]);
        work += f.dot(&read3(&ws.dq, 12 * b));
    }
    let zero: Nodes = [Vec3::zeros(); 4];
    for (j, jt) in model.joints.iter().enumerate() {
        let (a, bb) = (jt.parent, jt.child);
        let node = |x: &[f64], b: Option<usize>| b.map_or(zero, |b| body_nodes(x, b));
        let th_rel =
            read3(&ws.theta, 3 * bb) - a.map_or(Vec3::zeros(), |a| read3(&ws.theta, 3 * a));
        let c_d = held.damping[j];
        let k_s = held.stiffness[j];
        // what this joint's dampers give back (≤ 0 in a forward stage)
        let mut gained = 0.0;
        let mut turn = jt.turn0;
        for (dk, dof) in jt.dofs.iter().enumerate() {
            let act = jt
                .input
                .map_or(0.0, |i| actuator_input(dk, held.inputs, i, jt.effort));
            // the rotor's rate at the end: ω₁ = 2Δ/h − ω₀ (with Δ as the residual took it)
            let arm = (jt.armature > 0.0).then_some(jt.arm0 + dk);
            // the friction bristle's end and loss, with the increment the residual took
            let fric = jt.friction.as_ref().map(|fr| (fr, jt.fric0 + dk));
            match dof {
                DofRt::Slide(row) => {
                    let s0 = row.eval(&node(&ws.qn, a), &node(&ws.qn, Some(bb)));
                    let s1 = row.eval(&node(&ws.q, a), &node(&ws.q, Some(bb)));
                    let ds = s1 - s0;
                    if arm.is_some() || fric.is_some() {
                        // Δ as the residual took it (`joint_loads`: from the increments)
                        let (qa_bar, qb_bar) = (node(&ws.qbar, a), node(&ws.qbar, Some(bb)));
                        let (dqa, dqb) = (node(&ws.dq, a), node(&ws.dq, Some(bb)));
                        let dsr = row_increment(row, &qa_bar, &qb_bar, &dqa, &dqb);
                        if let Some(i) = arm {
                            ws.arm1[i] = 2.0 * dsr / h - ws.arm[i];
                        }
                        if let Some((fr, i)) = fric {
                            let st = fr.step(ws.fric[i], dsr, h);
                            ws.fric1[i] = st.s1;
                            gained -= st.loss;
                        }
                    }
                    work += (act + jt.acts.stage(held.inputs, held.gains, s0, ds, h).0) * ds;
                    gained -= c_d * ds * ds / h + jt.stops.map_or(0.0, |st| st.loss(s0, ds, h));
                }
                DofRt::Turn(tr) => {
                    if act != 0.0 {
                        let nbar = tr.axis.eval(&node(&ws.qbar, a), &node(&ws.qbar, Some(bb)));
                        work += act * nbar.dot(&th_rel);
                    }
                    let t0 = ws.ang[turn];
                    if k_s != 0.0
                        || c_d != 0.0
                        || jt.stops.is_some()
                        || arm.is_some()
                        || fric.is_some()
                        || !jt.acts.is_empty()
                    {
                        let (qa_bar, qb_bar) = (node(&ws.qbar, a), node(&ws.qbar, Some(bb)));
                        let (dqa, dqb) = (node(&ws.dq, a), node(&ws.dq, Some(bb)));
                        let [s0, c0] = turn_start(ws, tr, turn, a, bb);
                        // the increments as the residual took them (`joint_loads`, or the
                        // reduced iteration's `joint_space`: the same sums)
                        let [ds, dc] = match ws.red.split.get(j).copied().flatten() {
                            Some(sp) => sp.increments((&qa_bar, &qb_bar), (&dqa, &dqb)),
                            None => [
                                row_increment(&tr.sin, &qa_bar, &qb_bar, &dqa, &dqb),
                                row_increment(&tr.cos, &qa_bar, &qb_bar, &dqa, &dqb),
                            ],
                        };
                        let stops = jt.stops.as_ref();
                        let rotor = arm.map_or([0.0; 2], |i| [jt.armature, ws.arm[i]]);
                        let fr0 = fric.map(|(fr, i)| (fr, ws.fric[i]));
                        let acts = (&jt.acts, held.inputs, held.gains);
                        let st =
                            turn_step([s0, c0], [ds, dc], t0, k_s, c_d, stops, rotor, fr0, acts, h);
                        ws.ang1[turn] = t0 + st.dt;
                        if !jt.acts.is_empty() {
                            // the joint actuators' work τ Δt (module formulas of `turn`)
                            work += jt.acts.stage(held.inputs, held.gains, t0, st.dt, h).0 * st.dt;
                        }
                        if let Some(i) = arm {
                            ws.arm1[i] = 2.0 * st.dt / h - ws.arm[i];
                        }
                        if let Some((fr, i)) = fric {
                            let fs = fr.step(ws.fric[i], st.dt, h);
                            ws.fric1[i] = fs.s1;
                            gained -= fs.loss;
                        }
                        gained -=
                            c_d * st.dt * st.dt / h + stops.map_or(0.0, |s| s.loss(t0, st.dt, h));
                    } else {
                        let (qa, qb) = (node(&ws.q, a), node(&ws.q, Some(bb)));
                        let t1 = tr.sin.eval(&qa, &qb).atan2(tr.cos.eval(&qa, &qb));
                        ws.ang1[turn] = unwrap(t0, t1);
                    }
                    turn += 1;
                }
            }
        }
        if let Some(axes) = &jt.sph_axes {
            let rel = th_rel;
            gained -= c_d * rel.norm_squared() / h;
            // the friction bristle's end (back in the parent's axes of the stage's start, as
            // it was read: the increment adds in the parent's axes) and its loss
            if let Some(fr) = &jt.friction {
                let s0 = sph_bristle(ws, jt.fric0, a, &ws.qn);
                let (_, _, s1, loss) = fr.step3(s0, rel, h);
                let s1 = match a {
                    Some(a) => {
                        let n = body_nodes(&ws.qn, a);
                        Vec3::new(n[1].dot(&s1), n[2].dot(&s1), n[3].dot(&s1))
                    }
                    None => s1,
                };
                write3(&mut ws.fric1, jt.fric0, &s1);
                gained -= loss;
            }
            for (k, ax) in axes.iter().enumerate() {
                let act = jt.input.map_or(0.0, |i| held.inputs[i + k]);
                if act != 0.0 {
                    let abar = ax.eval(&node(&ws.qbar, a), &node(&ws.qbar, Some(bb)));
                    work += act * abar.dot(&rel);
                }
            }
        }
        work += gained;
        ws.loss[j] -= gained;
    }
    for b in 0..nb {
        for &(tb, at) in model.body_torques.iter().filter(|t| t.0 == b) {
            let m = Vec3::new(held.inputs[at], held.inputs[at + 1], held.inputs[at + 2]);
            work += m.dot(&read3(&ws.theta, 3 * tb));
        }
    }
    if !model.contact.is_empty() {
        work += contact_finish(model, ws, h);
    }
    work
}
