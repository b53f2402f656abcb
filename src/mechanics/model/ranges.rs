//! The valid range of every parameter of a model and of its solver settings, in one place:
//! `triad check` (the spec validator), `fmi2SetReal`/`fmi2SetInteger` and restored FMU states
//! all apply these rules, so a value one of them accepts the others accept too.
//!
//! Scalar rules (each `Err` is the message after the parameter's name, e.g. `must be >= 0
//! (got -1)`):
//!
//! | parameter | range |
//! |---|---|
//! | mass (kg) | `0 ≤ m < ∞` |
//! | inertia entry (kg·m²) | finite; the tensor: symmetric, principal moments `I₁ ≥ 0` and `I₁ + I₂ ≥ I₃` |
//! | damping, stiffness, stop damping | `0 ≤ x < ∞` |
//! | effort, stop stiffness | `0 < x < ∞` |
//! | gravity, initial values, limits | finite; `lower < upper` |
//! | `max_step` (s) | `[MAX_STEP_MIN, MAX_STEP_MAX]` |
//! | `tolerance` (1) | `[TOLERANCE_MIN, TOLERANCE_MAX)` |
//! | `order` | 2 or 4 |
//! | `stages` | 3 or 5 |
//! | `max_substeps` | `[1, MAX_SUBSTEPS_MAX]` |
//! | `rtol` (1) | 0 (fixed steps) or `[RTOL_MIN, RTOL_MAX]` |
//! | `atol` (1) | `[0, RTOL_MAX]` |
//! | `min_step` (s) | `[MAX_STEP_MIN, MAX_STEP_MAX]` |

use super::def::ModelDef;
use crate::math::Mat3;
use nalgebra::SymmetricEigen;

/// Smallest `solver.max_step`, s: below it a step's velocities are dominated by the round-off
/// of the positions (the velocity error grows like ε·|q|/h).
pub const MAX_STEP_MIN: f64 = 1e-9;
/// Largest `solver.max_step`, s.
pub const MAX_STEP_MAX: f64 = 1e3;
/// Smallest Newton tolerance: a scaled residual below it is round-off, never reached reliably.
pub const TOLERANCE_MIN: f64 = 1e-14;
/// Newton tolerances from here on are too loose to keep the invariants meaningful.
pub const TOLERANCE_MAX: f64 = 1e-3;
/// Smallest non-zero `solver.rtol`: tighter local errors are round-off.
pub const RTOL_MIN: f64 = 1e-12;
/// Largest `solver.rtol` and `solver.atol`: a looser tolerance controls nothing.
pub const RTOL_MAX: f64 = 0.1;
/// Largest `solver.max_substeps` (the largest `fmi2Integer`).
pub const MAX_SUBSTEPS_MAX: f64 = 2_147_483_647.0;

/// `v` as a reader expects it: plain for ordinary magnitudes, exponent form otherwise.
fn show(v: f64) -> String {
    let a = v.abs();
    if v == 0.0 || !v.is_finite() || (1e-5..1e16).contains(&a) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// Any finite number (gravity components, initial values, position limits, inertia entries).
///
/// # Errors
/// NaN or ±∞.
pub fn any_finite(v: f64) -> Result<(), String> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(format!("must be finite (got {})", show(v)))
    }
}

/// `0 ≤ v < ∞`: masses, damping, stiffness, stop damping.
///
/// # Errors
/// Negative or non-finite.
pub fn non_negative(v: f64) -> Result<(), String> {
    any_finite(v)?;
    if v >= 0.0 {
        Ok(())
    } else {
        Err(format!("must be >= 0 (got {})", show(v)))
    }
}

/// `v` finite and `≠ 0`: actuator gears.
///
/// # Errors
/// Zero or non-finite.
pub fn non_zero(v: f64) -> Result<(), String> {
    any_finite(v)?;
    if v == 0.0 {
        Err("must be non-zero".to_string())
    } else {
        Ok(())
    }
}

/// `0 < v < ∞`: effort limits and stop stiffness.
///
/// # Errors
/// Zero, negative or non-finite.
pub fn positive(v: f64) -> Result<(), String> {
    any_finite(v)?;
    if v > 0.0 {
        Ok(())
    } else {
        Err(format!("must be > 0 (got {})", show(v)))
    }
}

/// `solver.max_step`, s.
///
/// # Errors
/// Outside `[MAX_STEP_MIN, MAX_STEP_MAX]`.
pub fn max_step(v: f64) -> Result<(), String> {
    if (MAX_STEP_MIN..=MAX_STEP_MAX).contains(&v) {
        Ok(())
    } else {
        Err(format!(
            "must be in [{MAX_STEP_MIN:e}, {MAX_STEP_MAX:e}] s (got {})",
            show(v)
        ))
    }
}

/// `solver.tolerance`, the Newton tolerance on the scaled residual.
///
/// # Errors
/// Outside `[TOLERANCE_MIN, TOLERANCE_MAX)`.
pub fn tolerance(v: f64) -> Result<(), String> {
    if (TOLERANCE_MIN..TOLERANCE_MAX).contains(&v) {
        Ok(())
    } else {
        Err(format!(
            "must be in [{TOLERANCE_MIN:e}, {TOLERANCE_MAX:e}) (got {})",
            show(v)
        ))
    }
}

/// `solver.order`: 2 or 4.
///
/// # Errors
/// Any other value.
pub fn order(v: f64) -> Result<u8, String> {
    match v {
        2.0 => Ok(2),
        4.0 => Ok(4),
        _ => Err(format!("must be 2 or 4 (got {})", show(v))),
    }
}

/// `solver.stages`: the stages of the order-4 composition, 3 (triple jump) or 5 (Suzuki's).
///
/// # Errors
/// Any other value.
pub fn stages(v: f64) -> Result<u8, String> {
    match v {
        3.0 => Ok(3),
        5.0 => Ok(5),
        _ => Err(format!("must be 3 or 5 (got {})", show(v))),
    }
}

/// `solver.rtol`: 0 (fixed internal steps) or in `[RTOL_MIN, RTOL_MAX]` (error control).
///
/// # Errors
/// Anything else.
pub fn rtol(v: f64) -> Result<(), String> {
    if v == 0.0 || (RTOL_MIN..=RTOL_MAX).contains(&v) {
        Ok(())
    } else {
        Err(format!(
            "must be 0 (fixed steps) or in [{RTOL_MIN:e}, {RTOL_MAX}] (got {})",
            show(v)
        ))
    }
}

/// `solver.atol`: in `[0, RTOL_MAX]`.
///
/// # Errors
/// Anything else.
pub fn atol(v: f64) -> Result<(), String> {
    if (0.0..=RTOL_MAX).contains(&v) {
        Ok(())
    } else {
        Err(format!("must be in [0, {RTOL_MAX}] (got {})", show(v)))
    }
}

/// `solver.min_step`, the floor of an error-controlled step: as `max_step`.
///
/// # Errors
/// Outside `[MAX_STEP_MIN, MAX_STEP_MAX]`.
pub fn min_step(v: f64) -> Result<(), String> {
    max_step(v)
}

/// `solver.max_substeps`: a whole number in `[1, MAX_SUBSTEPS_MAX]`.
///
/// # Errors
/// Anything else.
pub fn max_substeps(v: f64) -> Result<u32, String> {
    if v.fract() == 0.0 && (1.0..=MAX_SUBSTEPS_MAX).contains(&v) {
        Ok(v as u32)
    } else {
        Err(format!(
            "must be a whole number in [1, {MAX_SUBSTEPS_MAX}] (got {})",
            show(v)
        ))
    }
}

/// An inertia tensor about the centre of mass, body axes, kg·m²: finite, symmetric, principal
/// moments non-negative and satisfying the triangle inequality (tolerances 1e-12 relative).
///
/// # Errors
/// What is wrong, with the principal moments.
pub fn inertia(m: &Mat3) -> Result<(), String> {
    if m.iter().any(|x| !x.is_finite()) {
        return Err("has a non-finite entry".into());
    }
    let scale = m.amax().max(f64::MIN_POSITIVE);
    if (m - m.transpose()).amax() > 1e-12 * scale {
        return Err("is not symmetric".into());
    }
    let eig = SymmetricEigen::new(*m).eigenvalues;
    let mut e = [eig[0], eig[1], eig[2]];
    e.sort_by(f64::total_cmp);
    if e.iter().any(|x| !x.is_finite()) {
        Err("is too large to handle (its principal moments overflow)".into())
    } else if e[0] < -1e-12 * scale {
        Err(format!(
            "has a negative principal moment (principal moments {}, {}, {})",
            sig(e[0]),
            sig(e[1]),
            sig(e[2])
        ))
    } else if e[0] + e[1] < e[2] * (1.0 - 1e-12) {
        Err(format!("violates the triangle inequality: principal moments {} + {} < {}, which no mass distribution has", sig(e[0]), sig(e[1]), sig(e[2])))
    } else {
        Ok(())
    }
}

/// `x` rounded to 6 significant digits, printed plainly (for messages).
fn sig(x: f64) -> String {
    format!("{:.5e}", x)
        .parse::<f64>()
        .map_or_else(|_| x.to_string(), |r| r.to_string())
}

/// The rules that involve several parameters of a lowered model (each body's inertia tensor,
/// each joint's `lower < upper`), as `(element, message)` pairs; empty when all hold. The
/// scalar rules are applied where each value is set.
#[must_use]
pub fn cross_checks(def: &ModelDef) -> Vec<(String, String)> {
    let mut out = Vec::new();
    for b in &def.bodies {
        if let Err(e) = inertia(&b.inertia) {
            out.push((format!("body.{}.inertia", b.name), e));
        }
    }
    for j in &def.joints {
        let l = &j.limits;
        if l.lower.is_finite() && l.upper.is_finite() && l.lower >= l.upper {
            out.push((
                format!("joint.{}.upper", j.name),
                format!("must be greater than lower ({} <= {})", l.upper, l.lower),
            ));
        }
    }
    out
}
