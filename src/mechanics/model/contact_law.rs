//! The contact laws of one contact point over a step, as exact discrete gradients and
//! dissipative terms: a one-sided linear spring with a Hunt–Crossley damper in the normal
//! direction, and Coulomb friction regularised by an elastic bristle that really sticks.
//!
//! Normal (penetration `x = −gap`, `⟨x⟩ = max(x, 0)`, stiffness `k`, damping `d` in s/m):
//!
//! ```text
//! V(x)  = ½k ⟨x⟩²
//! e     = (V(x₁) − V(x₀)) / (x₁ − x₀)        the one-sided spring's discrete gradient
//!                                               (`one_sided`, shared with the joint stops)
//! f     = e (1 + ψ(z)),  z = d Δx/h                         the normal force over the step
//! ψ(z)  = z  (z ≥ −½),   −1 + ½ e^{2z + 1}  (z < −½)       C¹, ψ ≥ −1, z ψ(z) ≥ 0
//! f Δx  = ΔV + D_n,   D_n = e ψ(z) Δx ≥ 0                   exact; D_n counted in the work
//! ```
//!
//! This is Hunt and Crossley's `k x (1 + d ẋ)` (in contact `e = k p̄`, the mean penetration, so
//! the damper grows from zero at contact) as long as the separation is slower than `1/(2d)`;
//! beyond that the damper fades smoothly instead of pulling (`f ≥ 0`), so the force stays C¹ in
//! the iterate and Newton converges through every impact.
//!
//! Friction: a bristle `s` (tangential deflection of the contact point from its anchor, part of
//! the state) with stiffness `k_t` and a damper `c_t = k_t d p̄`, its force limited to the cone
//! `C = μ f` of the same step's normal force. With `u` the tangential displacement of the
//! contact point over the step and `s* = s₀ + u/2` (the midpoint deflection, anchor fixed):
//!
//! ```text
//! F* = −k_t s* − c_t u/h                     the spring-damper with the anchor held
//! r  = |F*|/C,   λ = σ(r)/r                    σ(r) = r (r ≤ r₀),  1 − (1 − r₀) e^{−(r − r₀)/(1 − r₀)}
//! F  = λ F*,     s̄ = λ s*,   s₁ = 2 s̄ − s₀     (the anchor slides by 2(1 − λ) s*)
//! D_t = 2 k_t λ(1 − λ)|s*|² + λ c_t |u|²/h ≥ 0
//! F·u = −(½k_t|s₁|² − ½k_t|s₀|²) − D_t          exact for any λ ∈ (0, 1]
//! no normal force:  F = 0, s₁ = 0, D_t = ½k_t|s₀|²
//! ```
//!
//! `σ ≤ min(r, 1)`, so `|F| ≤ C`: below `r₀ = 0.9` of the cone the contact sticks (the bristle
//! deflects by `|F|/k_t` and nothing slides: a box holds on an incline up to `tan θ = 0.9 μ`);
//! above it the anchor slides, and in sustained sliding `σ → 1`, Coulomb's `|F| = μ f`. `σ` is
//! C¹ (a hard switch between sticking and sliding is not), so the force is C¹ in the iterate,
//! Newton converges through the switch, and friction never does positive work over a step.

use super::one_sided::gradient;
use super::scalar::{c, Real};
#[cfg(test)]
use crate::math::{Mat3, Vec3};
use nalgebra::Vector3;

/// The normal force of a contact point over a step, in `f64` or a dual number (the step's
/// tangent, `step::contact_tangent`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Normal<T = f64> {
    /// Force pushing the two sides apart, `f ≥ 0`, N.
    pub force: T,
    /// `∂f/∂x₁` (N/m), for the Jacobian.
    pub dforce: T,
    /// The elastic part `e = ΔV/Δx`, N.
    pub elastic: T,
    /// The mean penetration `p̄`, m.
    pub mean: T,
}

/// `ψ(z)` and `ψ'(z)` (module formulas).
fn psi<T: Real>(z: T) -> (T, T) {
    if z >= c(-0.5) {
        (z, T::one())
    } else {
        let t = (z * c(2.0) + T::one()).exp() * c(0.5);
        (t - T::one(), t * c(2.0))
    }
}

/// `max(x, 0)`.
fn positive<T: Real>(x: T) -> T {
    if x > T::zero() {
        x
    } else {
        T::zero()
    }
}

/// The normal force over a step of size `h` from penetration `x0` to `x1` (module formulas).
#[must_use]
pub(crate) fn normal<T: Real>(k: f64, d: f64, x0: T, x1: T, h: f64) -> Normal<T> {
    let (e, de) = gradient(k, x0, x1);
    let mean = (positive(x0) + positive(x1)) * c(0.5);
    let dx = x1 - x0;
    let (p, dp) = psi(dx * c(d) / c(h));
    Normal {
        force: e * (T::one() + p),
        dforce: de * (T::one() + p) + e * dp * c(d) / c(h),
        elastic: e,
        mean,
    }
}

/// Where the bristle starts to yield, as a share of the cone.
pub(crate) const YIELD: f64 = 0.9;

/// `σ(r)` and `σ'(r)` (module formulas).
fn sigma<T: Real>(r: T) -> (T, T) {
    if r <= c(YIELD) {
        (r, T::one())
    } else {
        let w = 1.0 - YIELD;
        let t = (-(r - c(YIELD)) / c(w)).exp();
        (T::one() - t * c(w), t)
    }
}

/// The friction force of a contact point over a step, in `f64` or a dual number.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Friction<T: Real = f64> {
    /// Tangential force on the side that moved by `u`, N.
    pub force: Vector3<T>,
    /// Bristle deflection at the step's end, m.
    pub s1: Vector3<T>,
    /// Energy dissipated `D_t ≥ 0`, J.
    pub loss: T,
    /// `∂F/∂u = −stiff P_t − radial t̂ t̂ᵀ` (N/m) with `t̂ = dir`.
    pub stiff: T,
    /// See `stiff`.
    pub radial: T,
    /// The direction of the trial force `F*` (zero without one).
    pub dir: Vector3<T>,
    /// `∂F/∂C`, the force's change with the cone.
    pub dcap: Vector3<T>,
    /// `∂F/∂c_t`, the force's change with the damper (which follows the penetration).
    pub dct: Vector3<T>,
}

/// The friction force over a step of size `h` (module formulas): bristle stiffness `kt`,
/// damper `ct` (N·s/m), cone `cap = μ f` (N), deflection `s0` at the step's start and the
/// tangential displacement `u` of the contact point.
#[must_use]
pub(crate) fn friction<T: Real>(
    kt: f64,
    ct: T,
    cap: T,
    s0: Vector3<T>,
    u: Vector3<T>,
    h: f64,
) -> Friction<T> {
    let zero = T::zero();
    #[allow(clippy::eq_op)] // NaN test
    if cap != cap || cap <= zero || kt <= 0.0 {
        return Friction {
            force: Vector3::zeros(),
            s1: Vector3::zeros(),
            loss: s0.norm_squared() * c(0.5 * kt.max(0.0)),
            stiff: zero,
            radial: zero,
            dir: Vector3::zeros(),
            dcap: Vector3::zeros(),
            dct: Vector3::zeros(),
        };
    }
    let (kt_, h_) = (c::<T>(kt), c::<T>(h));
    let star = s0 + u * c::<T>(0.5);
    let trial = -star * kt_ - u * (ct / h_);
    let size = trial.norm_squared().sqrt();
    let r = size / cap;
    let (sig, dsig) = sigma(r);
    let (lam, dlam) = if r > c(YIELD) {
        (sig / r, (dsig * r - sig) / (r * r))
    } else {
        (T::one(), zero)
    };
    let a = kt_ * c(0.5) + ct / h_;
    let dir = if size > zero {
        trial / size
    } else {
        Vector3::zeros()
    };
    // ∂trial/∂c_t = −u/h, ∂r/∂c_t = t̂·(−u/h)/C
    let dtrial = -u / h_;
    let dct = dtrial * lam + trial * (dlam * dir.dot(&dtrial) / cap);
    Friction {
        force: trial * lam,
        s1: star * (lam * c::<T>(2.0)) - s0,
        loss: kt_ * c(2.0) * lam * (T::one() - lam) * star.norm_squared()
            + lam * ct * u.norm_squared() / h_,
        stiff: a * lam,
        radial: a * r * dlam,
        dir,
        dcap: trial * (-dlam * r / cap),
        dct,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::model::one_sided::energy;

    #[test]
    fn the_normal_force_does_the_exact_work() {
        let (k, d, h) = (1e5, 2.0, 1e-3);
        for &(x0, x1) in &[
            (-0.01, -0.002),
            (-0.002, 0.001),
            (0.001, 0.0015),
            (0.0015, 0.0004),
            (0.0004, -0.003),
            (0.002, 0.002),
            (0.003, -0.0001),
        ] {
            let n = normal(k, d, x0, x1, h);
            let dv = energy(k, x1) - energy(k, x0);
            assert!((n.elastic * (x1 - x0) - dv).abs() <= 1e-15 * (1.0 + dv.abs()));
            let loss = (n.force - n.elastic) * (x1 - x0);
            assert!(n.force >= 0.0);
            assert!(loss >= -1e-18, "{x0} {x1}: loss {loss}");
            assert!(n.force >= 0.0);
        }
    }

    #[test]
    fn the_normal_derivative_matches_differences() {
        let (k, d, h) = (1e5, 2.0, 1e-3);
        for &(x0, x1) in &[(-0.002_f64, 0.001_f64), (0.001, 0.0015), (0.0015, 0.0004)] {
            let e = 1e-9;
            let fd =
                (normal(k, d, x0, x1 + e, h).force - normal(k, d, x0, x1 - e, h).force) / (2.0 * e);
            let n = normal(k, d, x0, x1, h);
            assert!(
                (n.dforce - fd).abs() <= 1e-5 * fd.abs().max(1.0),
                "{} {fd}",
                n.dforce
            );
        }
    }

    #[test]
    fn friction_never_does_positive_work_and_balances_exactly() {
        let (kt, ct, h) = (1e5, 200.0, 1e-3);
        let mut seed = 0x1234_5678_u64;
        let mut rnd = || {
            seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for _ in 0..10_000 {
            let s0 = Vec3::new(rnd(), rnd(), 0.0) * 2e-4;
            let u = Vec3::new(rnd(), rnd(), 0.0) * 10f64.powf(-7.0 + 4.0 * (rnd() + 0.5));
            let cap = (rnd() + 0.5) * 30.0;
            let f = friction(kt, ct, cap, s0, u, h);
            let dv = 0.5 * kt * (f.s1.norm_squared() - s0.norm_squared());
            let balance = f.force.dot(&u) + dv + f.loss;
            let stored = 0.5 * kt * (f.s1.norm_squared() + s0.norm_squared());
            let scale = stored + f.loss + f.force.norm() * u.norm() + 1e-30;
            assert!(
                balance.abs() <= 1e-12 * scale,
                "balance {balance} of {scale}"
            );
            assert!(f.loss >= 0.0);
            assert!(
                f.force.norm() <= cap * (1.0 + 1e-12),
                "{} > {cap}",
                f.force.norm()
            );
        }
    }

    #[test]
    fn friction_derivative_matches_differences() {
        let (kt, ct, h, cap) = (1e5, 200.0, 1e-3, 10.0);
        let s0 = Vec3::new(5e-5, -2e-5, 0.0);
        for u in [
            Vec3::new(1e-5, 2e-6, 0.0),
            Vec3::new(8e-5, -3e-5, 0.0),
            Vec3::new(3e-4, 1e-4, 0.0),
            Vec3::new(-2e-3, 5e-4, 0.0),
        ] {
            let f = friction(kt, ct, cap, s0, u, h);
            let p = Mat3::identity() - Vec3::z() * Vec3::z().transpose();
            let jac = -(p * f.stiff) - f.dir * f.dir.transpose() * f.radial;
            for k in 0..2 {
                let mut e = Vec3::zeros();
                e[k] = 1e-10;
                let fd = (friction(kt, ct, cap, s0, u + e, h).force
                    - friction(kt, ct, cap, s0, u - e, h).force)
                    / 2e-10;
                let col = jac.column(k);
                assert!(
                    (fd - col).norm() <= 1e-4 * fd.norm().max(1.0),
                    "{u}: {fd} vs {col}"
                );
            }
            let dc = (friction(kt, ct, cap + 1e-6, s0, u, h).force
                - friction(kt, ct, cap - 1e-6, s0, u, h).force)
                / 2e-6;
            assert!(
                (dc - f.dcap).norm() <= 1e-5 * dc.norm().max(1.0),
                "{u}: {dc} vs {}",
                f.dcap
            );
        }
    }

    #[test]
    fn a_held_load_below_the_yield_does_not_creep() {
        // a steady tangential load of 0.85 C on a body at rest: the bristle settles, s₁ = s₀
        let (kt, ct, h, cap) = (1e5, 0.0, 1e-3, 10.0);
        let s0 = Vec3::new(0.85 * cap / kt, 0.0, 0.0);
        let f = friction(kt, ct, cap, s0, Vec3::zeros(), h);
        assert_eq!(f.s1, s0);
        assert_eq!(f.loss, 0.0);
    }

    #[test]
    fn no_normal_force_releases_the_bristle() {
        let f = friction(
            1e5,
            0.0,
            0.0,
            Vec3::new(1e-4, 0.0, 0.0),
            Vec3::new(1e-3, 0.0, 0.0),
            1e-3,
        );
        assert_eq!(f.force, Vec3::zeros());
        assert_eq!(f.s1, Vec3::zeros());
        assert!((f.loss - 0.5 * 1e5 * 1e-8).abs() < 1e-15);
    }
}
