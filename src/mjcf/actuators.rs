//! Actuators: the joint of each becomes `actuated` (input `joint.J.tau` or `joint.J.f`), its
//! `effort` the smaller of `|gear| × ctrlrange` and `forcerange`; what is not reproduced (a
//! gear other than 1, servo laws, asymmetric ranges) is noted.

use std::collections::HashMap;

use super::lower::Outcome;
use super::model::{ActuatorKind, Model};
use crate::spec::{JointKind, Problem, Spec};

/// Marks the joints of the actuators as actuated, with their effort limit.
pub(super) fn actuators(
    m: &Model,
    joint_of: &HashMap<String, usize>,
    spec: &mut Spec,
    out: &mut Outcome,
    problems: &mut Vec<Problem>,
) {
    for a in &m.actuators {
        let Some(&k) = joint_of.get(a.joint.as_str()) else {
            problems.push(Problem::new(
                a.at.clone(),
                format!("joint \"{}\" does not exist", a.joint),
            ));
            continue;
        };
        let j = &mut spec.joint[k];
        let name = a.name.as_deref().unwrap_or(&a.joint);
        if j.kind == JointKind::Spherical {
            out.notes.push(format!("actuator '{name}' on ball joint '{}': not imported (triad's spherical inputs are torques about the parent axes)", a.joint));
            continue;
        }
        let input = if j.kind == JointKind::Revolute {
            "tau"
        } else {
            "f"
        };
        if j.actuated {
            out.notes.push(format!("actuator '{name}': joint '{}' already has an actuator; both act through joint.{}.{input}", a.joint, j.name));
        }
        j.actuated = true;
        let bound = |r: Option<[f64; 2]>, scale: f64| {
            r.map(|[lo, hi]| (lo * scale).abs().min((hi * scale).abs()))
        };
        let symmetric = |r: Option<[f64; 2]>| r.is_none_or(|[lo, hi]| lo == -hi);
        let effort = match (bound(a.ctrlrange, a.gear), bound(a.forcerange, 1.0)) {
            (Some(x), Some(y)) => Some(x.min(y)),
            (x, y) => x.or(y),
        }
        .filter(|e| *e > 0.0);
        j.effort = effort;
        let tail = format!(
            "the input is the joint's generalised force joint.{}.{input}",
            j.name
        );
        match a.kind {
            ActuatorKind::Motor if a.gear == 1.0 && symmetric(a.ctrlrange) && symmetric(a.forcerange) => {}
            ActuatorKind::Motor if a.gear == 1.0 => out.notes.push(format!(
                "actuator '{name}': an asymmetric ctrlrange/forcerange is clamped to ±{} (the smaller bound); {tail}",
                effort.unwrap_or(0.0)
            )),
            ActuatorKind::Motor => out.notes.push(format!(
                "actuator '{name}': gear {} is not applied: {tail} (= gear × ctrl; actuator.{name}.ctrl is not available yet)",
                a.gear
            )),
            ActuatorKind::Position | ActuatorKind::Velocity | ActuatorKind::General => {
                let kind = match a.kind {
                    ActuatorKind::Position => "position servo",
                    ActuatorKind::Velocity => "velocity servo",
                    _ => "general actuator",
                };
                out.notes.push(format!(
                    "actuator '{name}' ({kind}): MuJoCo's actuator law is not reproduced: {tail} (actuator.{name}.ctrl is not available yet)"
                ));
            }
        }
    }
}
