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
//! τ_J = clamp(Σ τ, lo_J, hi_J)               (over the joint's actuators; the joint's
//!                                             actuatorfrcrange, when given)
//! ```
//!
//! The gains `kp`, `kv` are tunable between steps: the state holds them (two per actuator,
//! `State::gains`), the step reads them with the inputs.
//!
//! In the step `q` and `q̇` are the stage's midpoint `q̄ = q₀ + Δ/2` and rate `Δ/h` (`Δ` the
//! coordinate's increment, `h` the stage size), and `τ_J` acts through the coordinate's exact
//! discrete gradient (`step::turn` for an angle, the slide row for a translation), so its work
//! over the stage is exactly `τ_J Δ`, all of it counted in `system.work` (whatever the gains,
//! and whether they change between steps or not). Newton takes
//! `∂τ/∂Δ = g ∂F/∂Δ`: `−g² (kp/2 + kv/h)` (position), `−g² kv/h` (velocity), 0 (motor, or a
//! clamped force), summed, and 0 where the sum is clamped. The position servo is then the
//! midpoint rule on a spring and damper, stable at any step.

use nalgebra::RealField;

use super::def::{ActuatorDef, ActuatorLaw, JointDef, JointType, ModelDef};

/// `x` as a `T`.
fn c<T: RealField + Copy>(x: f64) -> T {
    nalgebra::convert(x)
}

/// Which of MuJoCo's laws an actuator follows (its gains are the state's).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Servo {
    /// `F = u`.
    Motor,
    /// `F = kp (u − L) − kv L̇`.
    Position,
    /// `F = kv (u − L̇)`.
    Velocity,
}

/// A joint actuator as the step sees it: its law as MuJoCo's affine one,
/// `F = gain u_c + bias[0] L + bias[1] L̇` (motor: 1, 0, 0; position: kp, −kp, −kv; velocity:
/// kv, 0, −kv), the gains `[kp, kv]` read from the state.
#[derive(Clone, Copy, Debug)]
pub(crate) struct JointActuator {
    /// Its law.
    pub servo: Servo,
    /// Sign of the rate term `bias[1]`: −1 in the tangent's mirrored model (the damper
    /// negated), else 1.
    pub rate_sign: f64,
    /// Gear `g` (1).
    pub gear: f64,
    /// Control range `[lo, hi]` (±∞: unclamped).
    pub ctrl: [f64; 2],
    /// Force range `[lo, hi]` (±∞: unclamped).
    pub force: [f64; 2],
    /// Index of its control in the input vector.
    pub input: usize,
    /// Index in [`ModelDef::actuators`]: its gains are `gains[2 index]`, `gains[2 index + 1]`
    /// of the state.
    pub index: usize,
}

impl JointActuator {
    /// The runtime form of `def` (actuator `index` of the model), its control at input `input`.
    pub fn new(def: &ActuatorDef, index: usize, input: usize) -> Self {
        let full = [f64::NEG_INFINITY, f64::INFINITY];
        let servo = match def.law {
            ActuatorLaw::Motor => Servo::Motor,
            ActuatorLaw::Position { .. } => Servo::Position,
            ActuatorLaw::Velocity { .. } => Servo::Velocity,
        };
        Self {
            servo,
            rate_sign: 1.0,
            gear: def.gear,
            ctrl: def.ctrlrange.unwrap_or(full),
            force: def.forcerange.unwrap_or(full),
            input,
            index,
        }
    }

    /// `(gain, bias)` of the affine law (type docs) at the state's gains `gains` (two per
    /// actuator of the model).
    fn coefficients(&self, gains: &[f64]) -> (f64, [f64; 2]) {
        let g = |k: usize| gains.get(2 * self.index + k).copied().unwrap_or(0.0);
        match self.servo {
            Servo::Motor => (1.0, [0.0, 0.0]),
            Servo::Position => (g(0), [-g(0), -g(1) * self.rate_sign]),
            Servo::Velocity => (g(1), [0.0, -g(1) * self.rate_sign]),
        }
    }

    /// True when its law has a rate term (a servo: the tangent mirrors it).
    pub fn has_rate_term(&self) -> bool {
        self.servo != Servo::Motor
    }

    /// The generalised force `τ` (N·m or N) at the control `u` (its input value), coordinate
    /// `q` (rad or m) and rate `qd` (rad/s or m/s), module formulas, at the state's gains
    /// `gains`; generic over the scalar for the linear models (`tree_dynamics`).
    pub fn torque<T: RealField + Copy>(&self, gains: &[f64], u: T, q: T, qd: T) -> T {
        self.torque_with(self.coefficients(gains), u, q, qd)
    }

    /// [`JointActuator::torque`] at the law's coefficients `(gain, bias)`.
    fn torque_with<T: RealField + Copy>(
        &self,
        (gain, bias): (f64, [f64; 2]),
        u: T,
        q: T,
        qd: T,
    ) -> T {
        let g = c::<T>(self.gear);
        let u = clamp(u, self.ctrl);
        let f = u * c::<T>(gain) + g * q * c::<T>(bias[0]) + g * qd * c::<T>(bias[1]);
        clamp(f, self.force) * g
    }

    /// `(τ, ∂τ/∂Δ)` in a stage of size `h` (s) whose coordinate starts at `q0` (rad or m) and
    /// moves by `dq`, for the control input `u` and the state's gains `gains`: `τ` at
    /// `q̄ = q0 + dq/2`, `q̇ = dq/h`.
    pub fn stage(&self, gains: &[f64], u: f64, q0: f64, dq: f64, h: f64) -> (f64, f64) {
        let g = self.gear;
        let (gain, bias) = self.coefficients(gains);
        let tau = self.torque_with((gain, bias), u, q0 + 0.5 * dq, dq / h);
        let df = g * (0.5 * bias[0] + bias[1] / h);
        // the force is clamped where τ/g sits on a bound of the force range
        let f = tau / g;
        let clamped = df != 0.0 && (f <= self.force[0] || f >= self.force[1]);
        (tau, if clamped { 0.0 } else { g * df })
    }
}

/// The actuators driving one joint coordinate, and the clamp of their summed generalised force
/// (the joint's `actuatorfrcrange`).
#[derive(Clone, Debug)]
pub(crate) struct JointActuators {
    /// The actuators.
    pub list: Vec<JointActuator>,
    /// The sum of their generalised forces is clamped to `[lo, hi]`, N·m or N (±∞: unclamped).
    pub range: [f64; 2],
}

impl Default for JointActuators {
    fn default() -> Self {
        Self {
            list: Vec::new(),
            range: [f64::NEG_INFINITY, f64::INFINITY],
        }
    }
}

impl JointActuators {
    /// True when no actuator drives the joint.
    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// `(τ_J, ∂τ_J/∂Δ)` summed over the actuators and clamped (module formulas) for the inputs
    /// `inputs` and the state's gains `gains`, in a stage of size `h` from `q0` by `dq`.
    pub fn stage(&self, inputs: &[f64], gains: &[f64], q0: f64, dq: f64, h: f64) -> (f64, f64) {
        let (t, d) = self.list.iter().fold((0.0, 0.0), |(t, d), a| {
            let u = inputs.get(a.input).copied().unwrap_or(0.0);
            let (ta, da) = a.stage(gains, u, q0, dq, h);
            (t + ta, d + da)
        });
        let [lo, hi] = self.range;
        if t <= lo {
            (lo, 0.0)
        } else if t >= hi {
            (hi, 0.0)
        } else {
            (t, d)
        }
    }

    /// `τ_J` at the inputs `u`, coordinate `q` and rate `qd` (module formulas), at the state's
    /// gains `gains`; generic over the scalar for the linear models (`tree_dynamics`).
    pub fn torque<T: RealField + Copy>(&self, gains: &[f64], u: &[T], q: T, qd: T) -> T {
        let sum = self
            .list
            .iter()
            .fold(T::zero(), |t, a| t + a.torque(gains, u[a.input], q, qd));
        clamp(sum, self.range)
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

/// Why the actuator force range `[lo, hi]` of joint `jd` (its `actuatorfrcrange`) cannot be
/// built, if it cannot: the joint must be revolute or prismatic, the range finite with
/// `lo < hi`.
pub(crate) fn invalid_range(jd: &JointDef, [lo, hi]: [f64; 2]) -> Option<String> {
    if !matches!(jd.kind, JointType::Revolute | JointType::Prismatic) {
        Some(format!(
            "joint '{}': an actuator force range needs a revolute or prismatic joint, not {}",
            jd.name,
            jd.kind.name()
        ))
    } else if !(lo.is_finite() && hi.is_finite() && lo < hi) {
        Some(format!(
            "joint '{}': the actuator force range must be finite with lo < hi (got [{lo}, {hi}])",
            jd.name
        ))
    } else {
        None
    }
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
                let gains = law.gains();
                for &(u, q0, dq) in &[(0.5, 0.3, 0.01), (9.0, -0.2, 0.02), (-2.5, 1.0, -0.03)] {
                    let (t, dt) = a.stage(&gains, u, q0, dq, h);
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
                    let fd = (a.stage(&gains, u, q0, dq + e, h).0
                        - a.stage(&gains, u, q0, dq - e, h).0)
                        / (2.0 * e);
                    assert!(
                        (dt - fd).abs() < 1e-5 * (1.0 + fd.abs()),
                        "{law:?} {dt} {fd}"
                    );
                }
            }
        }
    }

    #[test]
    fn summed_force_clamped_by_the_joint_range() {
        let (h, q0, dq) = (0.01, 0.2, 0.01);
        let motor = act(ActuatorLaw::Motor, 2.0, None);
        let mut servo = act(ActuatorLaw::Position { kp: 30.0, kv: 2.0 }, 1.0, None);
        servo.index = 1;
        servo.input = 1;
        let gains = [0.0, 0.0, 30.0, 2.0];
        let acts = JointActuators {
            list: vec![motor, servo],
            range: [-1.0, 4.0],
        };
        // inside the range: the sum and its derivative
        let inputs = [0.5, 0.25];
        let (t, d) = acts.stage(&inputs, &gains, q0, dq, h);
        let (t0, d0) = motor.stage(&gains, 0.5, q0, dq, h);
        let (t1, d1) = servo.stage(&gains, 0.25, q0, dq, h);
        assert!((t - (t0 + t1)).abs() < 1e-15 && (d - (d0 + d1)).abs() < 1e-15);
        assert!((acts.torque(&gains, &inputs, q0 + 0.5 * dq, dq / h) - t).abs() < 1e-15);
        // beyond it: the bound, no derivative
        for (inputs, bound) in [([3.0, 0.5], 4.0), ([-3.0, -0.5], -1.0)] {
            assert_eq!(acts.stage(&inputs, &gains, q0, dq, h), (bound, 0.0));
            assert_eq!(acts.torque(&gains, &inputs, q0, 0.0), bound);
        }
        // new gains change the servo's force
        let stiffer = [0.0, 0.0, 60.0, 2.0];
        let (t2, _) = servo.stage(&stiffer, 0.25, q0, dq, h);
        assert!((t2 - t1 - 30.0 * (0.25 - (q0 + 0.5 * dq))).abs() < 1e-12);
    }
}
