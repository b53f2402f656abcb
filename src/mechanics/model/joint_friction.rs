//! Coulomb friction on a joint coordinate, regularised as the contact friction is
//! (`contact_law`): an elastic bristle that really sticks, in one dimension.
//!
//! With the friction limit `C` (N·m or N), the bristle's deflection `s` (state, rad or m), its
//! stiffness `k = C/δ` and damper `c = k τ`, and the coordinate's increment `u` over a step:
//!
//! ```text
//! s* = s₀ + u/2,  F* = −k s* − c u/h,  r = |F*|/C,  λ = σ(r)/r    (σ of `contact_law`)
//! F  = λ F*,  s₁ = 2λ s* − s₀
//! F u = −(½k s₁² − ½k s₀²) − D,   D = 2kλ(1 − λ) s*² + λ c u²/h ≥ 0     (exact)
//! ```
//!
//! On a spherical joint the bristle is a vector `s` (rad, kept in the parent's axes: it turns
//! with the parent; a stage reads and writes it in the parent's axes at its start, so a joint
//! that turns as one body keeps it) on the relative rotation increment `u = θᴮ − θᴬ` of the
//! stage (world),
//! and the law is the contact's in three dimensions, the torque `F` limited to the cone
//! `|F| ≤ C` (isotropic, not MuJoCo's per-axis box):
//!
//! ```text
//! s₀ = R_A(qₙ) s₀ᴬ,   F, s₁ = friction(k, c, C, s₀, u),   s₁ᴬ = R_A(qₙ)ᵀ s₁,   F u = −Δ(½k|s|²) − D
//! ∂F/∂u = −(stiff 1 + radial t̂ t̂ᵀ)
//! ```
//!
//! Below `YIELD·C` (0.9 of the limit) nothing slides: the coordinate deflects by at most
//! `0.9 δ` (the creep bound: it holds below breakaway to within `δ`, and does not drift while
//! the load stays below it); above it the anchor slides and in sustained sliding `|F| → C`.
//! `σ` is C¹, so Newton converges through stick and slip, and friction never does positive work.
//! `½k s²` is part of the energy, `D` of the work.

use super::contact_law::friction;
use crate::math::{Mat3, Vec3};
use nalgebra::Vector3;
use num_dual::Dual64;

/// The bristle's deflection at the friction limit, rad or m: `k = C/δ`.
pub const DEFLECTION: f64 = 1e-4;

/// The bristle damper's time constant, s: `c = k τ` (about a third of critical damping for a
/// joint of 0.01 kg·m² at C = 0.5 N·m).
pub const TIME_CONSTANT: f64 = 1e-3;

/// The friction of one joint coordinate (module formulas).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct JointFriction {
    /// The limit `C`, N·m or N (> 0).
    pub limit: f64,
    /// Whether the law is taken of the negated increment, `F(s₀, −u)` (the step tangent's
    /// swapped evaluation, `step::tangent`; false in every run).
    pub mirrored: bool,
}

/// What friction does over one step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FrictionStep {
    /// Force on the coordinate `F`, N·m or N.
    pub force: f64,
    /// `∂F/∂u`.
    pub dforce: f64,
    /// Deflection at the step's end `s₁`.
    pub s1: f64,
    /// Energy dissipated `D ≥ 0`, J.
    pub loss: f64,
}

impl JointFriction {
    /// Bristle stiffness `k = C/δ`.
    #[must_use]
    pub fn stiffness(&self) -> f64 {
        self.limit / DEFLECTION
    }

    /// The step of size `h` from deflection `s0` by the increment `u` (module formulas; a
    /// mirrored law at `−u`, its `dforce` the derivative in `u`).
    #[must_use]
    pub fn step(&self, s0: f64, u: f64, h: f64) -> FrictionStep {
        if self.mirrored {
            let st = self.law(s0, -u, h);
            return FrictionStep {
                dforce: -st.dforce,
                ..st
            };
        }
        self.law(s0, u, h)
    }

    /// The step of size `h` of a spherical joint's bristle `s0` (world axes) by the relative
    /// rotation increment `u` (world, rad), module formulas: the torque on the child (N·m,
    /// world), `−∂F/∂u` (3 × 3), the bristle at the end (world) and the loss (J).
    #[must_use]
    pub fn step3(&self, s0: Vec3, u: Vec3, h: f64) -> (Vec3, Mat3, Vec3, f64) {
        let k = self.stiffness();
        let f = friction(k, k * TIME_CONSTANT, self.limit, s0, u, h);
        let stiff = Mat3::identity() * f.stiff + f.dir * f.dir.transpose() * f.radial;
        (f.force, stiff, f.s1, f.loss)
    }

    /// `∂F/∂s₀`, `∂s₁/∂s₀` and `∂s₁/∂u` of the step of size `h` from `s0` by `u` (the step
    /// tangent's bristle columns), by dual numbers.
    #[must_use]
    pub fn partials(&self, s0: f64, u: f64, h: f64) -> [f64; 3] {
        let k = self.stiffness();
        let at = |ds: f64, du: f64| {
            let x = |v: f64, d: f64| {
                Vector3::new(Dual64::new(v, d), Dual64::from(0.0), Dual64::from(0.0))
            };
            friction(
                k,
                Dual64::from(k * TIME_CONSTANT),
                Dual64::from(self.limit),
                x(s0, ds),
                x(u, du),
                h,
            )
        };
        let (by_s, by_u) = (at(1.0, 0.0), at(0.0, 1.0));
        [by_s.force.x.eps, by_s.s1.x.eps, by_u.s1.x.eps]
    }

    /// The law itself (module formulas).
    fn law(&self, s0: f64, u: f64, h: f64) -> FrictionStep {
        let k = self.stiffness();
        let f = friction(
            k,
            k * TIME_CONSTANT,
            self.limit,
            Vec3::new(s0, 0.0, 0.0),
            Vec3::new(u, 0.0, 0.0),
            h,
        );
        FrictionStep {
            force: f.force.x,
            dforce: -f.stiff - f.radial * f.dir.x * f.dir.x,
            s1: f.s1.x,
            loss: f.loss,
        }
    }

    /// The bristle's energy `½ k s²`, J.
    #[must_use]
    pub fn energy(&self, s: f64) -> f64 {
        0.5 * self.stiffness() * s * s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_work_is_exact_and_never_positive_and_the_derivative_right() {
        let fr = JointFriction {
            limit: 0.5,
            mirrored: false,
        };
        let h = 1e-3;
        for &(s0, u) in &[
            (0.0, 1e-7),
            (2e-5, -3e-6),
            (8e-5, 5e-5),
            (-9e-5, -2e-4),
            (5e-5, 1e-2),
        ] {
            let st = fr.step(s0, u, h);
            let de = fr.energy(st.s1) - fr.energy(s0);
            assert!(st.loss >= 0.0);
            assert!(
                (st.force * u + de + st.loss).abs() <= 1e-12 * (de.abs() + st.loss + 1e-12),
                "{s0} {u}"
            );
            assert!(st.force.abs() <= fr.limit);
            let e = 1e-10;
            let fd = (fr.step(s0, u + e, h).force - fr.step(s0, u - e, h).force) / (2.0 * e);
            assert!(
                (st.dforce - fd).abs() <= 1e-5 * fd.abs().max(1.0),
                "{} {fd}",
                st.dforce
            );
        }
    }
}
