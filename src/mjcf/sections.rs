//! The `<actuator>` and `<equality>` sections.

use super::actuator_law::{law, Element, ACTUATOR_KINDS};
use super::defaults::Attrs;
use super::model::{Actuator, Equality};
use super::reader::{limited, refused, Reader};
use super::xml::Node;
use crate::math::Vec3;
use crate::spec::Problem;

/// Reads the `<actuator>` section.
pub(super) fn actuators(r: &mut Reader, node: &Node, out: &mut Vec<Actuator>) {
    for act in &node.children {
        if let Some(p) = refused(act) {
            r.problems.push(p);
            continue;
        }
        if !ACTUATOR_KINDS.contains(&act.name.as_str()) {
            r.problems.push(act.problem(format!(
                "actuator <{}> is not supported (motor, position, velocity, and general with their laws, on a joint are)",
                act.name
            )));
            continue;
        }
        // an actuator's class is its own `class`, else main (bodies' childclass does not reach it)
        let Some(class) = r.ok(r.classes.of(act, 0)) else {
            continue;
        };
        let a = Attrs::with_chain(act, r.classes.defaults_of(class, &ACTUATOR_KINDS));
        let element = Element {
            node: act,
            all: a.chain().to_vec(),
            same: r.classes.defaults_of(class, &[act.name.as_str()]),
            general: r.classes.defaults_of(class, &["general"]),
        };
        let Some(joint) = a.text("joint") else {
            r.problems.push(act.problem(
                "only actuators on a joint (joint=\"...\") are supported: tendon, site and body transmissions are not",
            ));
            continue;
        };
        let autolimits = r.compiler.autolimits;
        let read = || -> Result<Actuator, Problem> {
            let ctrl = a.numbers("ctrlrange", 2, 2)?;
            let force = a.numbers("forcerange", 2, 2)?;
            let ctrl_on = limited(&a, "ctrllimited", ctrl.is_some(), autolimits)?;
            let force_on = limited(&a, "forcelimited", force.is_some(), autolimits)?;
            Ok(Actuator {
                name: act.attr("name").map(str::to_string),
                at: act.at(),
                law: law(&element)?,
                joint: joint.to_string(),
                gear: a.numbers("gear", 1, 6)?.map_or(1.0, |g| g[0]),
                ctrlrange: ctrl.filter(|_| ctrl_on).map(|v| [v[0], v[1]]),
                forcerange: force.filter(|_| force_on).map(|v| [v[0], v[1]]),
            })
        };
        if let Some(x) = r.ok(read()) {
            out.push(x);
        }
    }
}

/// Reads the `<equality>` section.
pub(super) fn equalities(r: &mut Reader, node: &Node, out: &mut Vec<Equality>) {
    for e in &node.children {
        let Some(class) = r.ok(r.classes.of(e, 0)) else {
            continue;
        };
        let a = r.classes.attrs(e, class);
        let need = |key: &str| {
            a.text(key)
                .map(str::to_string)
                .ok_or_else(|| e.problem(format!("<{}> needs {key}", e.name)))
        };
        let read = || -> Result<Equality, Problem> {
            Ok(match e.name.as_str() {
                "connect" => {
                    if a.text("site1").is_some() {
                        return Err(e.problem(
                            "<connect site1 site2> is not supported: use body1, body2 and anchor",
                        ));
                    }
                    Equality::Connect {
                        at: e.at(),
                        body1: need("body1")?,
                        body2: a.text("body2").map(str::to_string),
                        anchor: Vec3::from(a.array("anchor", [0.0; 3])?),
                    }
                }
                "weld" => {
                    if a.text("site1").is_some() {
                        return Err(
                            e.problem("<weld site1 site2> is not supported: use body1 and body2")
                        );
                    }
                    if a.text("relpose").is_some() {
                        return Err(e.problem("<weld relpose> is not supported: the bodies are welded where they are at the model's pose"));
                    }
                    Equality::Weld {
                        at: e.at(),
                        body1: need("body1")?,
                        body2: a.text("body2").map(str::to_string),
                    }
                }
                "joint" => {
                    let mut polycoef = [0.0, 1.0, 0.0, 0.0, 0.0];
                    if let Some(v) = a.numbers("polycoef", 1, 5)? {
                        polycoef[..v.len()].copy_from_slice(&v);
                    }
                    Equality::Joint {
                        at: e.at(),
                        joint1: need("joint1")?,
                        joint2: a.text("joint2").map(str::to_string),
                        polycoef,
                    }
                }
                other => {
                    return Err(e.problem(format!(
                        "<equality><{other}> is not supported (connect, weld, joint are)"
                    )))
                }
            })
        };
        if let Some(x) = r.ok(read()) {
            out.push(x);
        }
    }
}
