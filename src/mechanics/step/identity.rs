//! The spurious roots of a stage, refused before the stage is taken.
//!
//! The equations are solved in the bodies' projected rows `P̄ᵀ R̃` (six per body, the internal
//! constraints eliminated), with `P̄ = [ω × d̄ᵢ]` at the midpoint directors
//! `d̄ᵢ = (dᵢⁿ + dᵢⁿ⁺¹)/2`. With the scaled node residual `R̃` (`newton`: inertia, gravity,
//! loads, and in the multiplier form the rows' `Σ μ_k ∇g_k(q̄)`) and the joint torques `m_b`:
//!
//! ```text
//! Σ_b Δq_b·R̃_b + θ_b·(m_b − h²/2 τ_b) = (h²/2)(E_{n+1} − E_n − W) − Σ_k μ_k Δg_k
//! |d̄ᵢ|² = (1 + dᵢⁿ·dᵢⁿ⁺¹)/2 = cos²(α/2)      (α the turn of dᵢ within the stage)
//! ```
//!
//! (`θ_b` the rotation increment, `τ_b` the body torque inputs). For a solution of the full
//! equations the rows hold (`Δg = 0`) and the left side vanishes, so `E_{n+1} − E_n = W`
//! exactly. Where a midpoint director vanishes (a body turned by π within the stage) `P̄`
//! loses rank, and a root of the projected rows need not solve the full equations: it leaves
//! the energy off by any amount (a double pendulum at h = 0.08 s, its second link turned by
//! exactly π within one step, went from 10 J to 507 J; the heavy top at h = 0.15 s, spinning
//! 4.5 rad per step, met a root 2.5 rad away with the identity off by 5.7 J of 27 J after a
//! Newton iteration that wandered from a poor start). Such a stage is refused like one that
//! did not converge, and redone as two half stages:
//! - every stage: refused where a midpoint director has nearly collapsed (`narrowest`,
//!   `|d̄ᵢ|² < ` [`COLLAPSED`]: a turn of more than ≈ 143° within the stage);
//! - the identity (`balanced`) must hold to [`SHARE`] of the sizes of its terms and of
//!   `Σ |Δq|·|M Δq|` (about `h²` times the kinetic energy: the multiplier form's `R̃` vanishes
//!   at a solution, so only this term gives it a scale there): the stages of either form that
//!   turned a body by more than ≈ 37° ([`LARGE_TURN`]). (The reduced form used to check every
//!   stage, 4 % of the double pendulum's step at h = 1e-3 and 3 % of chain100's. Below that
//!   turn, over the tests and the runs of `bench/large_steps.sh`, its check failed only where
//!   it means nothing: steps of 1e-6 s from rest, whose whole exchange is below the Newton
//!   tolerance, and the test-only naive torque, which breaks the identity by design.)

// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use super::work::{Held, Work};
use crate::math::Vec3;
use crate::mechanics::model::constraint::{body_nodes, read3};
use crate::mechanics::model::kernels::rotation_increment;
use crate::mechanics::model::runtime::Model;

/// Share of the sum of the identity's terms' sizes within which it must vanish: far above the
/// round-off of a converged stage, far below what a rank-deficient root leaves (of the order
/// of the terms themselves).
const SHARE: f64 = 1e-4;

/// Whether the identity holds for the increments `ws.dq` with `ws.rn`, `ws.mom` of the last
/// evaluation (at an iterate within the final update of `ws.q`) of a stage of size `h` (s): to
/// [`SHARE`] of the sum of the terms' sizes and of `Σ |Δq|·|M Δq|`.
pub(crate) fn balanced(model: &Model, ws: &Work, held: &Held, h: f64) -> bool {
    let hh = 0.5 * h * h;
    let (mut sum, mut size) = (0.0_f64, 0.0_f64);
    for (b, br) in model.bodies.iter().enumerate() {
        let dq = body_nodes(&ws.dq, b);
        for k in 0..4 {
            let r = read3(&ws.rn, 12 * b + 3 * k);
            let t = dq[k].dot(&r);
            sum += t;
            // (M Δq)_k: m Δφ, Σⱼ Eᵢⱼ Δdⱼ
            let inertia = if k == 0 {
                dq[0] * br.mass
            } else {
                dq[1] * br.e[(k - 1, 0)] + dq[2] * br.e[(k - 1, 1)] + dq[3] * br.e[(k - 1, 2)]
            };
            size += dq[k].norm() * (r.norm() + inertia.norm());
        }
        let mut m = read3(&ws.mom, 3 * b);
        for &(tb, at) in &model.body_torques {
            if tb == b {
                m -= Vec3::new(held.inputs[at], held.inputs[at + 1], held.inputs[at + 2]) * hh;
            }
        }
        if m != Vec3::zeros() {
            let th = rotation_increment(&body_nodes(&ws.qn, b), &body_nodes(&ws.q, b));
            sum += th.dot(&m);
            size += th.norm() * m.norm();
        }
    }
    sum.abs() <= SHARE * size
}

/// `|d̄ᵢ|²` below which a midpoint director counts as collapsed: `cos²(α/2)` at α ≈ 143°. A
/// stage that turns a body that far is far from resolving its motion; towards π the rotation
/// increment and the joint angles read through the reciprocal midpoint basis grow as
/// `1/|d̄ᵢ|`, at π the projection loses rank. (A floating tree under random torques at
/// h = 0.05, order 4, `tests/floating_base.rs`: a light child turned 2.6 rad within a stage;
/// taken, the step's damper account gave back 0.42 J of 6.4 J kinetic energy; halved, the run
/// keeps `E − W` within 2.5e-14.)
pub(crate) const COLLAPSED: f64 = 0.1;

/// `|d̄ᵢ|²` below which a stage's identity is checked (`cos²(α/2)` at α ≈ 37°): only
/// a Newton iteration that went that far meets a spurious root, and only there is the identity
/// far above the round-off of the stage's own energy exchange. (At tiny steps from rest the
/// whole exchange is below the Newton tolerance, and the identity holds to it, not to
/// [`SHARE`] of the terms.)
pub(crate) const LARGE_TURN: f64 = 0.9;

/// The smallest `|d̄ᵢ|² = (1 + dᵢⁿ·dᵢⁿ⁺¹)/2` over the bodies and directors of the stage from
/// `ws.qn` to `ws.q` (1 for a stage that turns nothing).
pub(crate) fn narrowest(model: &Model, ws: &Work) -> f64 {
    let mut least = 1.0_f64;
    for b in 0..model.bodies.len() {
        let (a, c) = (body_nodes(&ws.qn, b), body_nodes(&ws.q, b));
        for i in 1..4 {
            least = least.min(0.5 * (1.0 + a[i].dot(&c[i])));
        }
    }
    least
}
