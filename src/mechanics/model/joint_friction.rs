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
//! Below `YIELD·C` (0.9 of the limit) nothing slides: the coordinate deflects by at most
//! `0.9 δ` (the creep bound: it holds below breakaway to within `δ`, and does not drift while
//! the load stays below it); above it the anchor slides and in sustained sliding `|F| → C`.
//! `σ` is C¹, so Newton converges through stick and slip, and friction never does positive work.
//! `½k s²` is part of the energy, `D` of the work.

use super::contact_law::friction;
use crate::math::Vec3;

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

    /// The step of size `h` from deflection `s0` by the increment `u` (module formulas).
    #[must_use]
    pub fn step(&self, s0: f64, u: f64, h: f64) -> FrictionStep {
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
        let fr = JointFriction { limit: 0.5 };
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
