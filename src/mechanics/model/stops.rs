//! One-sided joint stops on a joint coordinate `t` (an angle or a slide), as an exact discrete
//! gradient, and the actuator effort limit.
//!
//! Beyond the upper limit the coordinate penetrates by `u = t − upper`, below the lower one by
//! `w = lower − t`; each stop is a one-sided spring with a Hunt–Crossley damper:
//!
//! ```text
//! V(t)  = ½k ⟨u⟩² + ½k ⟨w⟩²                     (⟨x⟩ = max(x, 0), the penetration)
//! g     = (V(t₁) − V(t₀)) / Δt                   the discrete gradient of the one-sided
//!                                                spring (`one_sided`: the contact's normal
//!                                                law uses the same), x = u, or w with g's
//!                                                sign flipped
//! f     = −g − c p̄ Δt/h,   p̄ = ½(⟨x₀⟩ + ⟨x₁⟩)      the force on the coordinate over the step
//! f Δt  = −(V(t₁) − V(t₀)) − c p̄ Δt²/h             (exact: the stop's energy and its loss)
//! ```
//!
//! Nothing divides by a small increment (`one_sided`). The force is continuous in `t₁` (the damper grows
//! from zero with the penetration, so it neither jumps at contact nor pulls at separation);
//! `∂f/∂t₁` is piecewise smooth, enough for Newton. The loss `c p̄ Δt²/h ≥ 0` is counted in the
//! work; `V` in the energy.

use super::one_sided::{energy, gradient};

/// The stops and effort limit of one joint coordinate (SI units of the coordinate: rad or m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Stops {
    /// Lower limit (−∞: none).
    pub lower: f64,
    /// Upper limit (+∞: none).
    pub upper: f64,
    /// Stop stiffness `k`, N·m/rad or N/m.
    pub stiffness: f64,
    /// Hunt–Crossley stop damping `c`, N·m·s/rad² or N·s/m².
    pub damping: f64,
}

impl Stops {
    /// Stored energy `V(t)`, J.
    pub fn energy(&self, t: f64) -> f64 {
        energy(self.stiffness, t - self.upper) + energy(self.stiffness, self.lower - t)
    }

    /// Mean penetration `p̄` over a step from `t0` by `dt` and `∂p̄/∂t₁`.
    fn mean_penetration(&self, t0: f64, dt: f64) -> (f64, f64) {
        let t1 = t0 + dt;
        let (u0, u1) = (t0 - self.upper, t1 - self.upper);
        let (w0, w1) = (self.lower - t0, self.lower - t1);
        let p = 0.5 * (u0.max(0.0) + u1.max(0.0) + w0.max(0.0) + w1.max(0.0));
        let dp = 0.5 * (f64::from(u8::from(u1 > 0.0)) - f64::from(u8::from(w1 > 0.0)));
        (p, dp)
    }

    /// The force `f` on the coordinate over a step of size `h` from `t0` by `dt`, and
    /// `∂f/∂t₁` (module formulas).
    pub fn force(&self, t0: f64, dt: f64, h: f64) -> (f64, f64) {
        let t1 = t0 + dt;
        let k = self.stiffness;
        let (gu, dgu) = gradient(k, t0 - self.upper, t1 - self.upper);
        // w = lower − t: the gradient in t is minus the gradient in w, its t₁-derivative equal
        let (gw, dgw) = gradient(k, self.lower - t0, self.lower - t1);
        let (p, dp) = self.mean_penetration(t0, dt);
        let c = self.damping / h;
        let f = -gu + gw - c * p * dt;
        let df = -dgu - dgw - c * (dp * dt + p);
        (f, df)
    }

    /// Energy the stop damper dissipates over the step, `c p̄ Δt²/h ≥ 0`, J.
    pub fn loss(&self, t0: f64, dt: f64, h: f64) -> f64 {
        self.damping * self.mean_penetration(t0, dt).0 * dt * dt / h
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const STOP: Stops = Stops {
        lower: -0.5,
        upper: 0.8,
        stiffness: 3.0e4,
        damping: 40.0,
    };

    #[test]
    fn the_force_does_exactly_the_stop_work() {
        let h = 1e-3;
        // free, entering, inside, leaving, through both limits, at rest inside
        for &(t0, dt) in &[
            (0.1, 0.3),
            (0.7, 0.2),
            (0.85, 0.01),
            (0.82, -0.05),
            (-0.45, -0.2),
            (-0.6, 0.3),
            (-0.7, 1.7),
            (0.9, 0.0),
        ] {
            let (f, _) = STOP.force(t0, dt, h);
            let want = -(STOP.energy(t0 + dt) - STOP.energy(t0)) - STOP.loss(t0, dt, h);
            assert!(
                (f * dt - want).abs() <= 1e-12 * (1.0 + want.abs()),
                "{t0} {dt}: {} vs {want}",
                f * dt
            );
            assert!(STOP.loss(t0, dt, h) >= 0.0);
        }
    }

    #[test]
    fn the_derivative_matches_differences() {
        let h = 1e-3;
        for &(t0, dt) in &[(0.7, 0.2), (0.85, 0.01), (0.82, -0.05), (-0.45, -0.2)] {
            let (_, df) = STOP.force(t0, dt, h);
            let e = 1e-7;
            let fd = (STOP.force(t0, dt + e, h).0 - STOP.force(t0, dt - e, h).0) / (2.0 * e);
            assert!(
                (df - fd).abs() <= 1e-5 * (1.0 + fd.abs()),
                "{t0} {dt}: {df} {fd}"
            );
        }
    }

    #[test]
    fn the_force_is_continuous_across_contact() {
        let h = 1e-3;
        let t0 = 0.7;
        let at = STOP.upper - t0;
        let below = STOP.force(t0, at - 1e-12, h).0;
        let above = STOP.force(t0, at + 1e-12, h).0;
        assert!((below - above).abs() < 1e-6, "{below} {above}");
        assert_eq!(STOP.force(0.0, 0.1, h), (0.0, 0.0));
    }
}
