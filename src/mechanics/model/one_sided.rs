//! The one-sided linear spring of the joint stops (`stops`) and of contact's normal law
//! (`contact_law`), written once: its energy and its discrete gradient in closed form.
//!
//! ```text
//! V(x)  = ½k ⟨x⟩²                              (⟨x⟩ = max(x, 0), the penetration)
//! e     = (V(x₁) − V(x₀)) / (x₁ − x₀):
//!         both in contact (x₀, x₁ > 0):      k (x₀ + x₁)/2
//!         entering (x₀ ≤ 0 < x₁):            ½k x₁² / (x₁ − x₀)
//!         leaving  (x₁ ≤ 0 < x₀):            ½k x₀² / (x₀ − x₁)
//!         neither:                           0
//! ∂e/∂x₁: k/2;  ½k x₁(x₁ − 2x₀)/(x₁ − x₀)²;  ½k x₀²/(x₀ − x₁)²;  0
//! ```
//!
//! Nothing divides by a small increment: a quotient appears only when the step crosses
//! `x = 0`, and then `|x₁ − x₀| ≥ |x₁|, |x₀|`. `e` is continuous in `x₁`.

use super::scalar::{c, Real};

/// Stored energy `½k⟨x⟩²` of a penetration `x` (J for `k` in N/m and `x` in m, or N·m/rad and
/// rad).
#[must_use]
pub(crate) fn energy(k: f64, x: f64) -> f64 {
    let p = x.max(0.0);
    0.5 * k * p * p
}

/// The discrete gradient `e` of `½k⟨x⟩²` from `x0` to `x1` and `∂e/∂x₁` (module formulas), in
/// `f64` or a dual number.
#[must_use]
pub(crate) fn gradient<T: Real>(k: f64, x0: T, x1: T) -> (T, T) {
    let (zero, hk) = (T::zero(), c::<T>(0.5 * k));
    match (x0 > zero, x1 > zero) {
        (false, false) => (zero, zero),
        (true, true) => (hk * (x0 + x1), hk),
        (false, true) => {
            let d = x1 - x0;
            (hk * x1 * x1 / d, hk * x1 * (x1 - x0 * c(2.0)) / (d * d))
        }
        (true, false) => {
            let d = x0 - x1;
            (hk * x0 * x0 / d, hk * x0 * x0 / (d * d))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `e Δx = ΔV` in every case, and `∂e/∂x₁` against differences.
    #[test]
    fn the_gradient_is_exact_and_its_derivative_right() {
        let k = 3e4;
        for &(x0, x1) in &[
            (-0.1, -0.2),
            (0.01, 0.03),
            (-0.02, 0.05),
            (0.04, -0.01),
            (0.02, 0.02),
        ] {
            let (e, de) = gradient(k, x0, x1);
            let dv = energy(k, x1) - energy(k, x0);
            assert!(
                (e * (x1 - x0) - dv).abs() <= 1e-15 * (1.0 + dv.abs()),
                "{x0} {x1}"
            );
            let h = 1e-8;
            let fd = (gradient(k, x0, x1 + h).0 - gradient(k, x0, x1 - h).0) / (2.0 * h);
            assert!(
                (de - fd).abs() <= 1e-5 * (1.0 + fd.abs()),
                "{x0} {x1}: {de} {fd}"
            );
        }
    }
}
