//! The stage start put back onto the constraint manifold (a position projection, velocities
//! unchanged), so that round-off does not pile up in the joint rows.
//!
//! The placement `Φ(u, qₙ)` keeps every joint row at its value at `qₙ`, so the round-off of
//! each stage stays in the rows and adds up over a run as a random walk (chain100 at
//! h = 1e-3: the largest row grew from 5e-15 to 2.5e-13 over 8000 steps). The multiplier form
//! solves `g(q) = 0` at every stage and does not drift. Once every
//! [`SETTLE_EVERY`](super::super::work::SETTLE_EVERY) reduced stages, `qₙ` is replaced by the
//! nearby configuration `q̂ₙ` whose rows hold to round-off; the correction is of the size of
//! the rows' violation (1e-15 m), its change of the potential energy far below the energy
//! balance's own round-off, and the stage then starts from `q̂ₙ` as from any state. Measured
//! over 8000 steps at h = 1e-3: the largest row ends at 2.4e-15 (chain30), 5.6e-15 (chain100)
//! and 1.2e-14 (chain200), against 5.9e-14, 2.1e-13 and 5.5e-13 without.
//!
//! `q̂ₙ` (parents before children), with `A = [a₁ a₂ a₃]` of the settled parent, `B` of the
//! child and `rel = AᵀB`:
//!
//! ```text
//! free root, spherical child:        D̂ = D (3I − DᵀD)/2       (one Newton–Schulz step)
//! revolute, cylindrical, planar:     B̂ = A Rz(θ),  θ = atan2(rel₁₀ − rel₀₁, rel₀₀ + rel₁₁)
//! universal:                         B̂ = A Rx(α) Ry(β),  α = atan2(rel₂₁, rel₁₁), β = atan2(rel₀₂, rel₀₀)
//!                                    (sines and cosines normalised, no trigonometric call)
//! prismatic, fixed:                  B̂ = A
//! D̂ = B̂ Cᵀ                           (b_k = Σᵢ C_ik dᵢ, C the child's constant joint frame)
//! φ̂ from r(q̂) = r̂:  r̂ = 0 (point pairs), (r·a₃)a₃ (prismatic, cylindrical),
//!                    (r·a₁)a₁ + (r·a₂)a₂ (planar)
//! ```

use super::super::work::Work;
use crate::math::{Mat3, Vec3};
use crate::mechanics::model::body::rotation;
use crate::mechanics::model::def::JointType as T;
use crate::mechanics::model::joint::body_nodes;
use crate::mechanics::model::runtime::Model;

/// One Newton–Schulz step towards the nearest rotation: `X (3I − XᵀX)/2` (squares an
/// orthonormality error).
fn orthonormal(x: &Mat3) -> Mat3 {
    x * (Mat3::identity() * 3.0 - x.transpose() * x) * 0.5
}

/// Rotation about axis `k` of the frame (0: x, 1: y, 2: z) by the angle whose sine and cosine
/// are proportional to `s` and `c` (normalised here: no trigonometric call).
fn axis_rotation(k: usize, s: f64, c: f64) -> Mat3 {
    let n = s.hypot(c);
    let (s, c) = (s / n, c / n);
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    let mut m = Mat3::identity();
    m[(i, i)] = c;
    m[(j, j)] = c;
    m[(j, i)] = s;
    m[(i, j)] = -s;
    m
}

/// Settles the stage start `ws.qn` in place.
pub(crate) fn settle(model: &Model, ws: &mut Work) {
    for &b in &model.order {
        let o = 12 * b;
        let qb = body_nodes(&ws.qn, Some(b));
        let d = rotation(&ws.qn[o..]);
        let (phi, dh) = match model.tree_joint[b] {
            None => (qb[0], orthonormal(&d)),
            Some(j) => {
                let g = &model.joints[j].geom;
                let qa = body_nodes(&ws.qn, model.parent[b]);
                let (a, bm) = g.axes(&qa, &qb);
                // b_k = Σᵢ C_ik dᵢ
                let c = Mat3::from_fn(|i, k| g.b[k].b[i + 1]);
                let rel = a.transpose() * bm;
                let turn = match g.kind {
                    T::Revolute | T::Cylindrical | T::Planar => Some(axis_rotation(
                        2,
                        rel[(1, 0)] - rel[(0, 1)],
                        rel[(0, 0)] + rel[(1, 1)],
                    )),
                    T::Universal => Some(
                        axis_rotation(0, rel[(2, 1)], rel[(1, 1)])
                            * axis_rotation(1, rel[(0, 2)], rel[(0, 0)]),
                    ),
                    T::Prismatic | T::Fixed => Some(Mat3::identity()),
                    T::Spherical => None,
                };
                let dh = turn.map_or_else(|| orthonormal(&d), |t| a * t * c.transpose());
                // r = r.c + Σ r.a qa + r.b[0] φ + Σᵢ r.b[i] dᵢ, r.b[0] = 1
                let rb = &g.r;
                let fixed = |dh: &Mat3| {
                    let mut v = rb.c;
                    for (x, c) in qa.iter().zip(&rb.a) {
                        v += x * *c;
                    }
                    for i in 0..3 {
                        v += dh.column(i) * rb.b[i + 1];
                    }
                    v
                };
                let r = fixed(&d) + qb[0] * rb.b[0];
                let along = |k: usize| a.column(k) * r.dot(&a.column(k));
                let target = match g.kind {
                    T::Prismatic | T::Cylindrical => along(2),
                    T::Planar => along(0) + along(1),
                    _ => Vec3::zeros(),
                };
                ((target - fixed(&dh)) / rb.b[0], dh)
            }
        };
        let settled = [
            phi,
            dh.column(0).into_owned(),
            dh.column(1).into_owned(),
            dh.column(2).into_owned(),
        ];
        for (k, v) in settled.iter().enumerate() {
            ws.qn[o + 3 * k..o + 3 * k + 3].copy_from_slice(v.as_slice());
        }
    }
}
