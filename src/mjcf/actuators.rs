//! Actuators: each `<motor>`, `<position>`, `<velocity>` (or `<general>` equal to one of them,
//! `actuator_law`) on a hinge or slide becomes an `[[actuator]]` with its law, `gear`, and the
//! `ctrlrange`/`forcerange` MuJoCo clamps by (`ctrllimited`, `forcelimited`, autolimits): the
//! input `actuator.A.ctrl`. A ball or free joint's actuator is refused.

use std::collections::HashMap;

use super::lower::Outcome;
use super::model::Model;
use crate::import::names::Namer;
use crate::mechanics::ActuatorLaw;
use crate::spec::{ActuatorKind, ActuatorSpec, JointKind, Problem, Spec};

/// Adds the model's actuators to `spec` (its joints already lowered: `joint_of` maps MuJoCo
/// joint names to spec joints).
pub(super) fn actuators(
    m: &Model,
    joint_of: &HashMap<String, usize>,
    spec: &mut Spec,
    out: &mut Outcome,
    problems: &mut Vec<Problem>,
) {
    let mut names = Namer::default();
    for a in &m.actuators {
        let Some(&k) = joint_of.get(a.joint.as_str()) else {
            problems.push(Problem::new(
                a.at.clone(),
                format!("joint \"{}\" does not exist", a.joint),
            ));
            continue;
        };
        let j = &spec.joint[k];
        if !matches!(j.kind, JointKind::Revolute | JointKind::Prismatic) {
            problems.push(Problem::new(
                a.at.clone(),
                format!(
                    "actuator on joint \"{}\": only actuators on hinge and slide joints are supported",
                    a.joint
                ),
            ));
            continue;
        }
        let original = a.name.as_deref().unwrap_or(&a.joint);
        let name = names.name(original);
        let (kind, kp, kv) = match a.law {
            ActuatorLaw::Motor => (ActuatorKind::Motor, None, None),
            ActuatorLaw::Position { kp, kv } => {
                (ActuatorKind::Position, Some(kp), (kv != 0.0).then_some(kv))
            }
            ActuatorLaw::Velocity { kv } => (ActuatorKind::Velocity, None, Some(kv)),
        };
        let description = if a.name.as_deref() == Some(name.as_str()) {
            String::new()
        } else {
            a.name.as_ref().map_or_else(
                || format!("MJCF actuator on joint \"{}\"", a.joint),
                |n| format!("MJCF actuator \"{n}\""),
            )
        };
        out.actuators.push(a.at.clone());
        spec.actuator.push(ActuatorSpec {
            name,
            joint: j.name.clone(),
            kind,
            gear: a.gear,
            kp,
            kv,
            ctrlrange: a.ctrlrange,
            forcerange: a.forcerange,
            description,
        });
    }
}
