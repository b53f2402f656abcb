//! The iterate of the reduced iteration: each body's increment over the stage (`R_b − I`,
//! `Δφ_b`, so that nothing cancels), updated by its own twist, and the joints' defects at it.
//!
//! A joint's defect is where its rows would place the child, parent held, with the joint
//! increments read off the two bodies (`read_off`, exact where the rows hold), as a twist:
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

use super::super::work::{Work, SETTLE_EVERY};
use super::maps::levers;
use super::settle::settle;
use super::work::{JointStart, RedWork};
use crate::math::{Mat3, Vec3};
use crate::mechanics::model::constraint::body_nodes;
use crate::mechanics::model::constraint::{read3, write3};
use crate::mechanics::model::def::JointType as T;
use crate::mechanics::model::kernels::expm1_so3;
use crate::mechanics::model::runtime::Model;

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

/// `R − I` for the rotation `R` nearest to `I + e` when `I + e` is orthogonal to round-off:
/// one Newton–Schulz step `X (3I − XᵀX)/2` in increments, `e − (I + e) S/2` with
/// `S = XᵀX − I = e + eᵀ + eᵀe` (squares the orthogonality error, nothing cancels).
fn rotation(e: &Mat3) -> Mat3 {
    let s = e + e.transpose() + e.transpose() * e;
    e - (Mat3::identity() + e) * s * 0.5
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

/// Stage start: settles `qₙ` onto the rows every [`SETTLE_EVERY`] stages, records the joints'
/// start data and makes each body of the predictor (`ws.dq`, `ws.q`) rigid: its increment is
/// the rotation nearest to the predicted directors' (`rw.e`) and its centre-of-mass shift
/// (`rw.dphi`). The bodies are not placed on the joint rows: the iteration corrects their
/// defects (`defects`) within its linear solves, as the multiplier form does. (Placing the
/// predictor parents first carries each joint's defect into its whole subtree: on chain1000 the
/// placed start was 4× further from the solution than the prediction, and the placed iterates
/// turned the far bodies along arcs, which made the reduced equations 1000× more nonlinear than
/// the multiplier form's.)
pub(crate) fn prepare(model: &Model, rw: &mut RedWork, ws: &mut Work) {
    if ws.memory.settle == 0 {
        settle(model, ws);
        ws.stage_id += 1;
        ws.memory.settle = SETTLE_EVERY;
    }
    ws.memory.settle -= 1;
    let zero = [Vec3::zeros(); 4];
    for b in 0..model.bodies.len() {
        // the nearest rotation, not the increment itself: read off directors that are
        // orthonormal only to round-off, the increment is a rotation only to round-off, and
        // carried from stage to stage that error grew (heavy top: to 1e-2 within 2 s)
        rw.e[b] = rotation(&increment(ws, b));
        rw.dphi[b] = read3(&ws.dq, 12 * b);
        write_body(ws, b, &rw.e[b], &rw.dphi[b]);
        let Some(j) = model.tree_joint[b] else {
            continue;
        };
        let g = &model.joints[j].geom;
        let qa = model.parent[b].map_or(zero, |p| body_nodes(&ws.qn, p));
        let qb = body_nodes(&ws.qn, b);
        let (rho_a, rho_b) = levers(g, &qa, &qb);
        let a: [Vec3; 3] = std::array::from_fn(|k| g.a[k].eval(&qa, &qb));
        // b₂ serves the universal pair only, r the slide pairs only
        let b2 = match g.kind {
            T::Universal => g.b[1].eval(&qa, &qb),
            _ => Vec3::zeros(),
        };
        let r = match g.kind {
            T::Cylindrical | T::Prismatic | T::Planar => g.r.eval(&qa, &qb),
            _ => Vec3::zeros(),
        };
        // the turn about a₃ (the pairs that have one)
        let (skew3, plane3) = match g.kind {
            T::Revolute | T::Cylindrical | T::Planar => (
                a[1] * a[0].transpose() - a[0] * a[1].transpose(),
                a[0] * a[0].transpose() + a[1] * a[1].transpose(),
            ),
            _ => (Mat3::zeros(), Mat3::zeros()),
        };
        rw.start[b] = JointStart {
            a,
            b2,
            r,
            rho_a,
            rho_b,
            skew3,
            plane3,
        };
    }
}

/// Reads body `b`'s joint increments off its parent's increments and its own (`rw.u[b]`, and
/// `rw.eabs[b]` for a spherical joint or a free root): the joint's own motion, without the
/// parts its rows forbid.
fn read_off(model: &Model, rw: &mut RedWork, b: usize) {
    let eb = rw.e[b];
    let Some(j) = model.tree_joint[b] else {
        rw.eabs[b] = eb;
        let d = rw.dphi[b];
        rw.u[b][3..6].copy_from_slice(d.as_slice());
        return;
    };
    let s = &rw.start[b];
    let (ep, dp) =
        model.parent[b].map_or((Mat3::zeros(), Vec3::zeros()), |p| (rw.e[p], rw.dphi[p]));
    let turn = (Mat3::identity() + ep).transpose() * (Mat3::identity() + eb);
    // the turn about a₃ₙ (only the pairs that have one)
    let about3 = || log_so3(&turn).dot(&s.a[2]);
    let dr = rw.dphi[b] + eb * s.rho_b - dp - ep * s.rho_a - ep * s.r;
    let slide = |k: usize| dr.dot(&(s.a[k] + ep * s.a[k]));
    let u = &mut rw.u[b];
    match model.joints[j].geom.kind {
        T::Spherical => rw.eabs[b] = eb,
        T::Revolute => u[0] = about3(),
        T::Universal => {
            // turn = exp(α â₁ₙ) exp(β b̂₂ₙ) with a₁ₙ ⟂ b₂ₙ: turn b₂ₙ = exp(α â₁ₙ) b₂ₙ and
            // turnᵀ a₁ₙ = exp(−β b̂₂ₙ) a₁ₙ (exact where the rows hold, so no defect appears)
            let (a1, b2) = (s.a[0], s.b2);
            let v = turn * b2;
            let w = turn.transpose() * a1;
            u[0] = b2.cross(&v).dot(&a1).atan2(b2.dot(&v));
            u[1] = w.cross(&a1).dot(&b2).atan2(a1.dot(&w));
        }
        T::Cylindrical => {
            u[0] = about3();
            u[1] = slide(2);
        }
        T::Prismatic => u[0] = slide(2),
        T::Planar => {
            u[0] = about3();
            u[1] = slide(0);
            u[2] = slide(1);
        }
        T::Fixed => {}
    }
}

/// Where the rows of body `b`'s joint place it (`R − I`, `Δφ`) from its parent's increments
/// and its joint increments `rw.u[b]`, `rw.eabs[b]`.
fn placed(model: &Model, rw: &RedWork, b: usize) -> (Mat3, Vec3) {
    let u = rw.u[b];
    let Some(j) = model.tree_joint[b] else {
        return (rw.eabs[b], Vec3::new(u[3], u[4], u[5]));
    };
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

/// Writes body `b`'s increments (`R − I`, `Δφ`) to `ws.dq` and `ws.q`.
fn write_body(ws: &mut Work, b: usize, e: &Mat3, dphi: &Vec3) {
    let at = 12 * b..12 * b + 12;
    let (qn, q, dq) = (&ws.qn[at.clone()], &mut ws.q[at.clone()], &mut ws.dq[at]);
    write3(dq, 0, dphi);
    write3(q, 0, &(read3(qn, 0) + dphi));
    for i in 0..3 {
        let at = 3 + 3 * i;
        let n = read3(qn, at);
        let inc = e * n;
        write3(dq, at, &inc);
        write3(q, at, &(n + inc));
    }
}

/// The joints' defects at the iterate, as body twists (`rw.c`): `c_b` takes body `b`, its
/// parent held, to where its joint's rows place it with the joint increments read off the two
/// bodies (zero for free roots). A linear solve whose body twists are `x_c = A x_p + S u + c_c`
/// corrects the defects to first order (`G c = −g`, `G S = 0`), as the multiplier form's does.
pub(crate) fn defects(model: &Model, rw: &mut RedWork) {
    for &b in &model.order {
        if model.tree_joint[b].is_none() {
            rw.c[b] = [0.0; 6];
            continue;
        }
        let (e, dphi) = target(model, rw, b);
        // R_placed R_bᵀ − I = (E_placed − E_b)(I + E_b)ᵀ without cancellation; its axial vector
        // (first order: the defect's square is corrected by the next solve), from the
        // off-diagonal entries only: d_ij = (row i of E_placed − E_b)·(row j of I + E_b)
        let x = e - rw.e[b];
        let y = Mat3::identity() + rw.e[b];
        let d = |i: usize, j: usize| {
            x[(i, 0)] * y[(j, 0)] + x[(i, 1)] * y[(j, 1)] + x[(i, 2)] * y[(j, 2)]
        };
        let turn = Vec3::new(d(2, 1) - d(1, 2), d(0, 2) - d(2, 0), d(1, 0) - d(0, 1)) * 0.5;
        let shift = dphi - rw.dphi[b];
        rw.c[b] = [shift.x, shift.y, shift.z, turn.x, turn.y, turn.z];
    }
}

/// Where the rows of body `b`'s joint place it, parent held (`R − I`, `Δφ`): as `placed` with
/// the increments of `read_off`, but for the pairs that turn about `a₃` without a
/// trigonometric call. With the relative turn `T = R_pᵀ R_b` in the start joint frame,
/// `M = Aᵀ T A`, the turn about `a₃ₙ` nearest to it has `(sin ϑ, cos ϑ) ∝ (M₁₀ − M₀₁, M₀₀ + M₁₁)`
/// and `R − I = sin ϑ (a₂a₁ᵀ − a₁a₂ᵀ) + (cos ϑ − 1)(a₁a₁ᵀ + a₂a₂ᵀ)`, `cos ϑ − 1 =
/// −sin²ϑ/(1 + cos ϑ)` (nothing cancels).
fn target(model: &Model, rw: &mut RedWork, b: usize) -> (Mat3, Vec3) {
    let Some(j) = model.tree_joint[b] else {
        return (rw.e[b], rw.dphi[b]);
    };
    let kind = model.joints[j].geom.kind;
    if kind == T::Universal {
        read_off(model, rw, b);
        return placed(model, rw, b);
    }
    let s = &rw.start[b];
    let (ep, dp) =
        model.parent[b].map_or((Mat3::zeros(), Vec3::zeros()), |p| (rw.e[p], rw.dphi[p]));
    let eb = rw.e[b];
    let e = match kind {
        T::Revolute | T::Cylindrical | T::Planar => {
            // T − I = E_pᵀ + E_b + E_pᵀ E_b, applied to a₁ₙ and a₂ₙ
            let [a1, a2, _] = s.a;
            let t = |a: &Vec3| {
                let x = eb * a;
                ep.tr_mul(&(a + x)) + x
            };
            let (t1, t2) = (t(&a1), t(&a2));
            let s2 = a2.dot(&t1) - a1.dot(&t2);
            let c2 = 2.0 + a1.dot(&t1) + a2.dot(&t2);
            // |(s2, c2)| ≈ 2 (no overflow to guard against)
            let n = (s2 * s2 + c2 * c2).sqrt();
            let (sn, cm1) = if c2 > 0.0 {
                // sin ϑ = s2/n, cos ϑ − 1 = −s2²/(n (n + c2)): one division
                let q = 1.0 / (n * (n + c2));
                (s2 * (n + c2) * q, -s2 * s2 * q)
            } else {
                (s2 / n, c2 / n - 1.0)
            };
            let x = s.skew3 * sn + s.plane3 * cm1;
            ep + x + ep * x
        }
        T::Spherical => eb,
        _ => ep,
    };
    let ep_rho_a = ep * s.rho_a;
    // the slides along the free axes (the slide pairs only)
    let slid = |ks: &[usize]| {
        let ep_r = ep * s.r;
        let dr = rw.dphi[b] + eb * s.rho_b - dp - ep_rho_a - ep_r;
        let mut out = ep_r;
        for &k in ks {
            let a = s.a[k] + ep * s.a[k];
            out += a * dr.dot(&a);
        }
        out
    };
    let slid = match kind {
        T::Prismatic | T::Cylindrical => slid(&[2]),
        T::Planar => slid(&[0, 1]),
        _ => Vec3::zeros(),
    };
    (e, dp + ep_rho_a + slid - e * s.rho_b)
}

/// Scaled size of the body updates of the last solve (`rw.dx`): `max_b |δφ_b|/lc, |δθ_b|`.
pub(crate) fn size(model: &Model, rw: &RedWork) -> f64 {
    rw.dx.iter().fold(0.0_f64, |upd, x| {
        let dphi = Vec3::new(x[0], x[1], x[2]);
        let dth = Vec3::new(x[3], x[4], x[5]);
        upd.max(dphi.norm() / model.lc).max(dth.norm())
    })
}

/// Applies the body twists of the last solve (`rw.dx`) to each body's own increments: the
/// rotation `exp(δθ)` and the shift `δφ` (`rw.e`, `rw.dphi`, `ws.dq`, `ws.q`).
///
/// The bodies stay rigid; their joint rows err by the square of the update, which the next
/// solve corrects (`defects`). The round-off of an update stays each body's own. (An update
/// carried by joint increments of ≈ 16 digits loses the last correction of a joint near the
/// root below the last place of its increment, and the residual stays at the subtree's inertia
/// times that last place, `∝ N³` down a chain.)
pub(crate) fn update(model: &Model, rw: &mut RedWork, ws: &mut Work) {
    for b in 0..model.bodies.len() {
        let x = rw.dx[b];
        let turn = expm1_so3(&Vec3::new(x[3], x[4], x[5]));
        rw.e[b] = turn + rw.e[b] + turn * rw.e[b];
        rw.dphi[b] += Vec3::new(x[0], x[1], x[2]);
        write_body(ws, b, &rw.e[b], &rw.dphi[b]);
    }
}

/// Test support: places every body, parents first, from the joint increments `rw.u`,
/// `rw.eabs` (the nodal reparametrization `Φ(u)`); with `read` it first reads each joint's
/// increments off the bodies (`read_off`).
#[cfg(test)]
pub(crate) fn place(model: &Model, rw: &mut RedWork, ws: &mut Work, read: bool) {
    for &b in &model.order {
        if read {
            read_off(model, rw, b);
        }
        let (e, dphi) = placed(model, rw, b);
        rw.e[b] = e;
        rw.dphi[b] = dphi;
        write_body(ws, b, &e, &dphi);
    }
}
