//! The nodal reparametrization `q = Φ(u, qₙ)` of a tree (theory.md §4.5), parents before
//! children, as increments (`R_b − I` and `Δφ_b`, so that nothing cancels):
//!
//! ```text
//! revolute, cylindrical, planar:  R_c = R_p exp(ϑ â₃ₙ)
//! universal:                      R_c = R_p exp(α â₁ₙ) exp(β b̂₂ₙ)
//! prismatic, fixed:               R_c = R_p          spherical, free root: R_c absolute
//! Δφ_c = Δφ_p + (R_p − I) ρᴬₙ + Δr − (R_c − I) ρᴮₙ
//! Δr = (R_p − I) rₙ + Σ s_k R_p a_kₙ   (slide pairs; 0 for the others, whose r is fixed)
//! ```
//!
//! Each rule keeps every row of its pair at its stage-start value: `a_i·b_j` because the child
//! turns with the parent and about axes the rows leave free, `r·a_k` because `r` turns with
//! the parent and slides only along the free axes. `dᵢ = R_b dᵢₙ`, `Δdᵢ = (R_b − I) dᵢₙ`.
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use super::super::assemble::{read3, write3};
use super::super::def::JointType as T;
use super::super::kernels::{body_nodes, expm1_so3};
use super::super::model::Model;
use super::super::work::{Work, SETTLE_EVERY};
use super::maps::levers;
use super::settle::settle;
use super::{JointStart, RedWork};
use crate::math::{Mat3, Vec3};

/// Rotation vector of the rotation matrix `r` (angle in `[0, π]`).
fn log_so3(r: &Mat3) -> Vec3 {
    let v = Vec3::new(
        r[(2, 1)] - r[(1, 2)],
        r[(0, 2)] - r[(2, 0)],
        r[(1, 0)] - r[(0, 1)],
    ) * 0.5;
    let s = v.norm();
    if s == 0.0 {
        return v;
    }
    let c = 0.5 * (r.trace() - 1.0);
    v * (s.atan2(c) / s)
}

/// `R − I` of the rotation nearest (by its rotation vector) to `I + e`.
fn rotation(e: &Mat3) -> Mat3 {
    expm1_so3(&log_so3(&(Mat3::identity() + e)))
}

/// `R − I` of the rotation that takes the directors `dₙ` of body `b` to those of `q`
/// (`Σᵢ Δdᵢ dᵢₙᵀ`).
fn increment(ws: &Work, b: usize) -> Mat3 {
    let n = body_nodes(&ws.qn, b);
    let d = body_nodes(&ws.dq, b);
    let mut e = Mat3::zeros();
    for i in 1..4 {
        e += d[i] * n[i].transpose();
    }
    e
}

/// Stage start: records the joints' start data and turns the predictor's iterate (`ws.dq`,
/// `ws.q`, any body increments) into joint increments, then places the bodies (`ws.q`, `ws.dq`
/// satisfy the joint rows).
///
/// Parents before children, each joint's increments are read off the *placed* parent and the
/// predicted child, and the child is placed at once: the joint takes up what the rows of its
/// parent could not follow of the prediction, so the placed bodies stay as close to the
/// predicted ones as the joints allow. (Relative increments read off two predicted bodies
/// drop their off-axis parts, which add up down a chain: at N = 1000 the placed tip strayed
/// 6e-3 from the prediction, whose own error was 1e-5.)
pub(crate) fn prepare(model: &Model, rw: &mut RedWork, ws: &mut Work) {
    if ws.memory.settle == 0 {
        settle(model, ws);
        ws.memory.settle = SETTLE_EVERY;
    }
    ws.memory.settle -= 1;
    let zero = [Vec3::zeros(); 4];
    for b in 0..model.bodies.len() {
        rw.e[b] = increment(ws, b);
        rw.dphi[b] = read3(&ws.dq, 12 * b);
        rw.u[b] = [0.0; 6];
    }
    for &b in &model.order {
        let Some(j) = model.tree_joint[b] else {
            rw.eabs[b] = rotation(&rw.e[b]);
            let d = rw.dphi[b];
            rw.u[b][3..6].copy_from_slice(d.as_slice());
            place_body(model, rw, ws, b);
            continue;
        };
        let g = &model.joints[j].geom;
        let p = model.parent[b];
        let qa = p.map_or(zero, |p| body_nodes(&ws.qn, p));
        let qb = body_nodes(&ws.qn, b);
        let (rho_a, rho_b) = levers(g, &qa, &qb);
        let s = JointStart {
            a: std::array::from_fn(|k| g.a[k].eval(&qa, &qb)),
            b2: g.b[1].eval(&qa, &qb),
            r: g.r.eval(&qa, &qb),
            rho_a,
            rho_b,
        };
        rw.start[b] = s;
        let (ep, dp) = p.map_or((Mat3::zeros(), Vec3::zeros()), |p| (rw.e[p], rw.dphi[p]));
        let eb = rw.e[b];
        let rel = log_so3(&((Mat3::identity() + ep).transpose() * (Mat3::identity() + eb)));
        let dr = rw.dphi[b] + eb * s.rho_b - dp - ep * s.rho_a - ep * s.r;
        let slide = |k: usize| dr.dot(&(s.a[k] + ep * s.a[k]));
        let u = &mut rw.u[b];
        match g.kind {
            T::Spherical => rw.eabs[b] = rotation(&eb),
            T::Revolute => u[0] = rel.dot(&s.a[2]),
            T::Universal => {
                u[0] = rel.dot(&s.a[0]);
                u[1] = rel.dot(&s.b2);
            }
            T::Cylindrical => {
                u[0] = rel.dot(&s.a[2]);
                u[1] = slide(2);
            }
            T::Prismatic => u[0] = slide(2),
            T::Planar => {
                u[0] = rel.dot(&s.a[2]);
                u[1] = slide(0);
                u[2] = slide(1);
            }
            T::Fixed => {}
        }
        place_body(model, rw, ws, b);
    }
}

/// Places every body from the joint increments: `rw.e`, `rw.dphi`, `ws.dq`, `ws.q`.
pub(crate) fn place(model: &Model, rw: &mut RedWork, ws: &mut Work) {
    for &b in &model.order {
        place_body(model, rw, ws, b);
    }
}

/// Places body `b` from its joint increments and its placed parent.
fn place_body(model: &Model, rw: &mut RedWork, ws: &mut Work, b: usize) {
    let u = rw.u[b];
    let (e, dphi) = match model.tree_joint[b] {
        None => (rw.eabs[b], Vec3::new(u[3], u[4], u[5])),
        Some(j) => {
            let s = &rw.start[b];
            let (ep, dp) =
                model.parent[b].map_or((Mat3::zeros(), Vec3::zeros()), |p| (rw.e[p], rw.dphi[p]));
            let rel = |x: Mat3| ep + x + ep * x;
            let along = |k: usize, v: f64| (s.a[k] + ep * s.a[k]) * v;
            let (e, dr) = match model.joints[j].geom.kind {
                T::Spherical => (rw.eabs[b], Vec3::zeros()),
                T::Revolute => (rel(expm1_so3(&(s.a[2] * u[0]))), Vec3::zeros()),
                T::Universal => {
                    let x1 = expm1_so3(&(s.a[0] * u[0]));
                    let x2 = expm1_so3(&(s.b2 * u[1]));
                    (rel(x1 + x2 + x1 * x2), Vec3::zeros())
                }
                T::Cylindrical => (rel(expm1_so3(&(s.a[2] * u[0]))), ep * s.r + along(2, u[1])),
                T::Prismatic => (ep, ep * s.r + along(2, u[0])),
                T::Planar => (
                    rel(expm1_so3(&(s.a[2] * u[0]))),
                    ep * s.r + along(0, u[1]) + along(1, u[2]),
                ),
                T::Fixed => (ep, Vec3::zeros()),
            };
            (e, dp + ep * s.rho_a + dr - e * s.rho_b)
        }
    };
    rw.e[b] = e;
    rw.dphi[b] = dphi;
    let o = 12 * b;
    write3(&mut ws.dq, o, &dphi);
    write3(&mut ws.q, o, &(read3(&ws.qn, o) + dphi));
    for i in 0..3 {
        let at = o + 3 + 3 * i;
        let inc = e * read3(&ws.qn, at);
        write3(&mut ws.dq, at, &inc);
        write3(&mut ws.q, at, &(read3(&ws.qn, at) + inc));
    }
}

/// Scaled size of the body updates of the last solve (`rw.dx`): `max_b |δφ_b|/lc, |δθ_b|`.
pub(crate) fn size(model: &Model, rw: &RedWork) -> f64 {
    rw.dx.iter().fold(0.0_f64, |upd, x| {
        let dphi = Vec3::new(x[0], x[1], x[2]);
        let dth = Vec3::new(x[3], x[4], x[5]);
        upd.max(dphi.norm() / model.lc).max(dth.norm())
    })
}

/// Applies the solution of the last solve (`rw.res`: `δu` per body, `rw.dx`: body twists)
/// to the joint increments and places the bodies.
pub(crate) fn update(model: &Model, rw: &mut RedWork, ws: &mut Work) {
    for b in 0..model.bodies.len() {
        let x = rw.dx[b];
        let dth = Vec3::new(x[3], x[4], x[5]);
        let du = rw.res[b];
        let kind = model.tree_joint[b].map(|j| model.joints[j].geom.kind);
        match kind {
            None | Some(T::Spherical) => {
                let x = expm1_so3(&dth);
                rw.eabs[b] = rw.eabs[b] + x + x * rw.eabs[b];
                if kind.is_none() {
                    for k in 3..6 {
                        rw.u[b][k] += du[k];
                    }
                }
            }
            Some(_) => {
                for k in 0..6 {
                    rw.u[b][k] += du[k];
                }
            }
        }
    }
    place(model, rw, ws);
}

/// Applies the body twists of the last solve (`rw.dx`) to each body's own increments, to first
/// order (`Δφ += δφ`, `Δdᵢ += δθ × dᵢ`), without placing: the update that a stage accepts.
///
/// Its joint rows then err by `O(|δx|²)`, below `1e-20` at an accepted update. What it gains
/// is round-off that stays each body's own: an update placed through the joints is carried by
/// joint increments of ≈ 16 digits, so the last correction of a joint near the root, below the
/// last place of its increment, is lost, and the residual stays at the subtree's inertia times
/// that last place (`∝ N³` down a chain). Applied to the bodies, the correction is kept.
pub(crate) fn update_bodies(model: &Model, rw: &RedWork, ws: &mut Work) {
    for b in 0..model.bodies.len() {
        let x = rw.dx[b];
        let o = 12 * b;
        let dth = Vec3::new(x[3], x[4], x[5]);
        let dphi = read3(&ws.dq, o) + Vec3::new(x[0], x[1], x[2]);
        write3(&mut ws.dq, o, &dphi);
        write3(&mut ws.q, o, &(read3(&ws.qn, o) + dphi));
        for i in 0..3 {
            let at = o + 3 + 3 * i;
            let inc = read3(&ws.dq, at) + dth.cross(&read3(&ws.q, at));
            write3(&mut ws.dq, at, &inc);
            write3(&mut ws.q, at, &(read3(&ws.qn, at) + inc));
        }
    }
}
