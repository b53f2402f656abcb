//! Checks of `[[actuator]]`: names, the driven joint (a revolute or prismatic tree joint), the
//! gear, the gains each kind takes, the ranges.

use std::collections::HashMap;

use crate::spec::error::{did_you_mean, Report};
use crate::spec::schema::{ActuatorKind, JointKind, Spec};

use super::common::is_identifier;

/// Every actuator check; `joint_index` maps joint names to their index in `spec.joint`.
pub(super) fn check(spec: &Spec, report: &mut Report, joint_index: &HashMap<&str, usize>) {
    let mut seen: HashMap<&str, usize> = HashMap::new();
    for (i, a) in spec.actuator.iter().enumerate() {
        let p = format!("actuator[{i}]");
        if !is_identifier(&a.name) {
            report.push(format!("{p}.name"), format!("\"{}\" is not an identifier: use letters, digits and _ and do not start with a digit", a.name));
        }
        if let Some(first) = seen.insert(a.name.as_str(), i) {
            report.push(
                format!("{p}.name"),
                format!(
                    "duplicate actuator name \"{}\" (also actuator[{first}])",
                    a.name
                ),
            );
            seen.insert(a.name.as_str(), first);
        }
        match joint_index.get(a.joint.as_str()).map(|&k| &spec.joint[k]) {
            None => {
                let hint = did_you_mean(&a.joint, joint_index.keys().copied());
                report.push(
                    format!("{p}.joint"),
                    format!("no joint named \"{}\"{hint}", a.joint),
                );
            }
            Some(j) if !matches!(j.kind, JointKind::Revolute | JointKind::Prismatic) => {
                report.push(
                    format!("{p}.joint"),
                    format!(
                        "joint \"{}\" is {}: actuators drive revolute and prismatic joints only (use the joint's own inputs, actuated = true)",
                        a.joint,
                        crate::spec::lower::joint_type(j.kind).name()
                    ),
                );
            }
            Some(j) if j.is_loop_closing() => report.push(
                format!("{p}.joint"),
                format!(
                    "joint \"{}\" closes a loop: actuators drive tree joints only",
                    a.joint
                ),
            ),
            Some(_) => {}
        }
        if !(a.gear.is_finite() && a.gear != 0.0) {
            report.push(
                format!("{p}.gear"),
                format!("must be finite and non-zero (got {})", a.gear),
            );
        }
        let (kp, kv) = match a.kind {
            ActuatorKind::Motor => (false, false),
            ActuatorKind::Position => (true, false),
            ActuatorKind::Velocity => (false, true),
        };
        let kind = match a.kind {
            ActuatorKind::Motor => "a motor",
            ActuatorKind::Position => "a position servo",
            ActuatorKind::Velocity => "a velocity servo",
        };
        // (key, value, required, allowed)
        let gains = [("kp", a.kp, kp, kp), ("kv", a.kv, kv, kp || kv)];
        for (key, value, required, allowed) in gains {
            match value {
                None if required => {
                    report.push(format!("{p}.{key}"), format!("{kind} needs {key}"));
                }
                Some(_) if !allowed => {
                    report.push(format!("{p}.{key}"), format!("{kind} takes no {key}"))
                }
                Some(g) if !(g.is_finite() && g >= 0.0) => report.push(
                    format!("{p}.{key}"),
                    format!("must be finite and >= 0 (got {g})"),
                ),
                _ => {}
            }
        }
        for (key, range) in [("ctrlrange", a.ctrlrange), ("forcerange", a.forcerange)] {
            if let Some([lo, hi]) = range {
                if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                    report.push(
                        format!("{p}.{key}"),
                        format!("must be [lo, hi] with finite lo < hi (got [{lo}, {hi}])"),
                    );
                }
            }
        }
    }
}
