//! Joint actuators: a control `u` acting on the coordinate `q` of a revolute or prismatic joint
//! through a gear `g` (MuJoCo's joint transmission with its motor, position and velocity laws).
//!
//! ```text
//! u_c = clamp(u, lo_u, hi_u)                 (ctrlrange, when given)
//! L = g q,   L̇ = g q̇                         (actuator length and rate)
//! F = u_c                                    motor
//!   = kp (u_c − L) − kv L̇                    position servo
//!   = kv (u_c − L̇)                           velocity servo
//! F_c = clamp(F, lo_F, hi_F)                 (forcerange, when given)
//! τ = g F_c                                  (generalised force on q, N·m or N)
//! ```
//!
//! In the step `q` and `q̇` are the stage's midpoint `q̄ = q₀ + Δ/2` and rate `Δ/h` (`Δ` the
//! coordinate's increment, `h` the stage size), and `τ` acts through the coordinate's exact
//! discrete gradient (`step::turn` for an angle, the slide row for a translation), so its work
//! over the stage is exactly `τ Δ`, all of it counted in `system.work`. Newton takes
//! `∂τ/∂Δ = g ∂F/∂Δ`: `−g² (kp/2 + kv/h)` (position), `−g² kv/h` (velocity), 0 (motor, or a
//! clamped force). The position servo is then the midpoint rule on a spring and damper, stable
//! at any step.

use nalgebra::RealField;

use super::def::{ActuatorDef, ActuatorLaw, JointType, ModelDef};

/// `x` as a `T`.
fn c<T: RealField + Copy>(x: f64) -> T {
    nalgebra::convert(x)
}

/// A joint actuator as the step sees it: its law as MuJoCo's affine one,
/// `F = gain u_c + bias[0] L + bias[1] L̇` (motor: 1, 0, 0; position: kp, −kp, −kv; velocity:
/// kv, 0, −kv).
#[derive(Clone, Copy, Debug)]
pub(crate) struct JointActuator {
    /// Gain on the control.
    pub gain: f64,
    /// Coefficients of the length and of the rate (the rate's is the damper, ≤ 0; negated in
    /// the tangent's mirrored model).
    pub bias: [f64; 2],
    /// Gear `g` (1).
    pub gear: f64,
    /// Control range `[lo, hi]` (±∞: unclamped).
    pub ctrl: [f64; 2],
    /// Force range `[lo, hi]` (±∞: unclamped).
    pub force: [f64; 2],
    /// Index of its control in the input vector.
    pub input: usize,
}

impl JointActuator {
    /// The runtime form of `def`, its control at input `input`.
    pub fn new(def: &ActuatorDef, input: usize) -> Self {
        let full = [f64::NEG_INFINITY, f64::INFINITY];
        let (gain, bias) = match def.law {
            ActuatorLaw::Motor => (1.0, [0.0, 0.0]),
            ActuatorLaw::Position { kp, kv } => (kp, [-kp, -kv]),
            ActuatorLaw::Velocity { kv } => (kv, [0.0, -kv]),
        };
        Self {
            gain,
            bias,
            gear: def.gear,
            ctrl: def.ctrlrange.unwrap_or(full),
            force: def.forcerange.unwrap_or(full),
            input,
        }
    }

    /// The generalised force `τ` (N·m or N) at the control `u` (its input value), coordinate
    /// `q` (rad or m) and rate `qd` (rad/s or m/s), module formulas; generic over the scalar
    /// for the linear models (`tree_dynamics`).
    pub fn torque<T: RealField + Copy>(&self, u: T, q: T, qd: T) -> T {
        let g = c::<T>(self.gear);
        let u = clamp(u, self.ctrl);
        let f =
            u * c::<T>(self.gain) + g * q * c::<T>(self.bias[0]) + g * qd * c::<T>(self.bias[1]);
        clamp(f, self.force) * g
    }

    /// `(τ, ∂τ/∂Δ)` in a stage of size `h` (s) whose coordinate starts at `q0` (rad or m) and
    /// moves by `dq`, for the control input `u`: `τ` at `q̄ = q0 + dq/2`, `q̇ = dq/h`.
    pub fn stage(&self, u: f64, q0: f64, dq: f64, h: f64) -> (f64, f64) {
        let g = self.gear;
        let tau = self.torque(u, q0 + 0.5 * dq, dq / h);
        let df = g * (0.5 * self.bias[0] + self.bias[1] / h);
        // the force is clamped where τ/g sits on a bound of the force range
        let f = tau / g;
        let clamped = df != 0.0 && (f <= self.force[0] || f >= self.force[1]);
        (tau, if clamped { 0.0 } else { g * df })
    }
}

/// Why actuator `a` of `def` cannot be built, if it cannot: its joint must be a revolute or
/// prismatic tree joint, its gear finite and non-zero, its gains finite and ≥ 0, its ranges
/// finite with `lo ≤ hi`.
pub(crate) fn invalid(def: &ModelDef, a: &ActuatorDef) -> Option<String> {
    let Some(jd) = def.joints.get(a.joint) else {
        return Some(format!("actuator '{}': unknown joint {}", a.name, a.joint));
    };
    let why = if !matches!(jd.kind, JointType::Revolute | JointType::Prismatic) {
        format!(
            "drives joint '{}' of type {}: only revolute and prismatic joints take actuators",
            jd.name,
            jd.kind.name()
        )
    } else if jd.loop_closing {
        format!(
            "drives joint '{}', which closes a loop: only tree joints take actuators",
            jd.name
        )
    } else if !(a.gear.is_finite() && a.gear != 0.0) {
        format!("gear must be finite and non-zero (got {})", a.gear)
    } else if let Some(g) = match a.law {
        ActuatorLaw::Motor => None,
        ActuatorLaw::Position { kp, kv } => {
            [kp, kv].into_iter().find(|g| !(g.is_finite() && *g >= 0.0))
        }
        ActuatorLaw::Velocity { kv } => Some(kv).filter(|g| !(g.is_finite() && *g >= 0.0)),
    } {
        format!("gains must be finite and >= 0 (got {g})")
    } else if let Some([lo, hi]) = [a.ctrlrange, a.forcerange]
        .into_iter()
        .flatten()
        .find(|[lo, hi]| !(lo.is_finite() && hi.is_finite() && lo <= hi))
    {
        format!("ranges must be finite with lo <= hi (got [{lo}, {hi}])")
    } else {
        return None;
    };
    Some(format!("actuator '{}': {why}", a.name))
}

/// `x` clamped to `[lo, hi]` (a NaN stays NaN).
fn clamp<T: RealField + Copy>(x: T, [lo, hi]: [f64; 2]) -> T {
    if x < c::<T>(lo) {
        c::<T>(lo)
    } else if x > c::<T>(hi) {
        c::<T>(hi)
    } else {
        x
    }
}

/// `(τ, ∂τ/∂Δ)` summed over the actuators `acts` of one coordinate (module formulas) for the
/// inputs `inputs`.
pub(crate) fn stage_sum(
    acts: &[JointActuator],
    inputs: &[f64],
    q0: f64,
    dq: f64,
    h: f64,
) -> (f64, f64) {
    acts.iter().fold((0.0, 0.0), |(t, d), a| {
        let u = inputs.get(a.input).copied().unwrap_or(0.0);
        let (ta, da) = a.stage(u, q0, dq, h);
        (t + ta, d + da)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn act(law: ActuatorLaw, gear: f64, force: Option<[f64; 2]>) -> JointActuator {
        JointActuator::new(
            &ActuatorDef {
                name: "a".into(),
                joint: 0,
                law,
                gear,
                ctrlrange: Some([-2.0, 3.0]),
                forcerange: force,
            },
            0,
        )
    }

    #[test]
    fn laws_clamps_and_their_derivative() {
        let h = 0.01;
        for law in [
            ActuatorLaw::Motor,
            ActuatorLaw::Position { kp: 30.0, kv: 2.0 },
            ActuatorLaw::Velocity { kv: 5.0 },
        ] {
            for force in [None, Some([-4.0, 1.0])] {
                let a = act(law, -1.7, force);
                for &(u, q0, dq) in &[(0.5, 0.3, 0.01), (9.0, -0.2, 0.02), (-2.5, 1.0, -0.03)] {
                    let (t, dt) = a.stage(u, q0, dq, h);
                    let uc = f64::clamp(u, -2.0, 3.0);
                    let (l, ld) = (-1.7 * (q0 + 0.5 * dq), -1.7 * dq / h);
                    let f = match law {
                        ActuatorLaw::Motor => uc,
                        ActuatorLaw::Position { kp, kv } => kp * (uc - l) - kv * ld,
                        ActuatorLaw::Velocity { kv } => kv * (uc - ld),
                    };
                    let f = force.map_or(f, |[lo, hi]| f.clamp(lo, hi));
                    assert!((t - -1.7 * f).abs() < 1e-12, "{law:?} {t} {f}");
                    let e = 1e-7;
                    let fd =
                        (a.stage(u, q0, dq + e, h).0 - a.stage(u, q0, dq - e, h).0) / (2.0 * e);
                    assert!(
                        (dt - fd).abs() < 1e-5 * (1.0 + fd.abs()),
                        "{law:?} {dt} {fd}"
                    );
                }
            }
        }
    }
}
