//! `<equality>`: `connect` and `weld` as loop-closing joints, `joint` noted.

use std::collections::HashMap;

use super::lower::{Host, Outcome};
use super::model::{Equality, Model};
use crate::import::frame::Iso;
use crate::import::names::Namer;
use crate::math::{Mat3, Vec3};
use crate::spec::{JointKind, JointSpec, Problem, Spec};

/// `<equality>`: `connect` and `weld` become loop-closing spherical and fixed joints between
/// the two bodies' hosts, placed where the bodies are at `qpos0`; `joint` is noted.
#[allow(clippy::too_many_arguments)]
pub(super) fn equalities(
    m: &Model,
    joint_of: &HashMap<String, usize>,
    host: &[Host],
    world: &[Iso],
    spec: &mut Spec,
    out: &mut Outcome,
    problems: &mut Vec<Problem>,
) {
    let find = |name: &str| {
        m.bodies
            .iter()
            .position(|b| b.name.as_deref() == Some(name))
    };
    let mut names = Namer::new(
        &spec
            .joint
            .iter()
            .map(|j| j.name.as_str())
            .collect::<Vec<_>>(),
    );
    for (k, e) in m.equalities.iter().enumerate() {
        let (at, b1, b2, anchor, kind) = match e {
            Equality::Joint { joint1, joint2, .. } => {
                for n in std::iter::once(joint1).chain(joint2) {
                    if !joint_of.contains_key(n.as_str()) {
                        if let Equality::Joint { at, .. } = e {
                            problems.push(Problem::new(
                                at.clone(),
                                format!("joint \"{n}\" does not exist"),
                            ));
                        }
                    }
                }
                out.notes.push(format!(
                    "<equality joint joint1=\"{joint1}\"{}>: the coupling is not enforced (triad has no joint couplings yet): the joints are independent",
                    joint2.as_ref().map_or_else(String::new, |j| format!(" joint2=\"{j}\""))
                ));
                continue;
            }
            Equality::Connect {
                at,
                body1,
                body2,
                anchor,
            } => (at, body1, body2, *anchor, JointKind::Spherical),
            Equality::Weld { at, body1, body2 } => {
                (at, body1, body2, Vec3::zeros(), JointKind::Fixed)
            }
        };
        let i1 = find(b1);
        let i2 = match b2 {
            Some(n) => find(n),
            None => Some(0),
        };
        let (Some(i1), Some(i2)) = (i1, i2) else {
            let missing = if i1.is_none() {
                b1.clone()
            } else {
                b2.clone().unwrap_or_default()
            };
            problems.push(Problem::new(
                at.clone(),
                format!("body \"{missing}\" does not exist"),
            ));
            continue;
        };
        let (h1, h2) = (host[i1], host[i2]);
        if h1.body == h2.body {
            problems.push(Problem::new(
                at.clone(),
                "the two bodies are welded into one: the equality constrains nothing",
            ));
            continue;
        }
        // the constraint frame: at the anchor, oriented as body1, at qpos0
        let in1 = Iso {
            r: Mat3::identity(),
            p: anchor,
        };
        let w = world[i1].then(&in1);
        let in2 = world[i2].inverse().then(&w);
        let (parent, o1, child, o2) = match (h1.body, h2.body) {
            (Some(c), p) => (p, h2.place.then(&in2), c, h1.place.then(&in1)),
            (None, Some(c)) => (None, h1.place.then(&in1), c, h2.place.then(&in2)),
            (None, None) => continue,
        };
        let base = if kind == JointKind::Spherical {
            "connect"
        } else {
            "weld"
        };
        let id = names.name(&format!("{base}{}", k + 1));
        out.joints.push(at.clone());
        spec.joint.push(JointSpec {
            name: id,
            kind,
            parent: parent.map_or_else(|| "world".to_string(), |p| spec.body[p].name.clone()),
            child: spec.body[child].name.clone(),
            origin: o1.origin_spec(),
            child_origin: Some(o2.origin_spec()),
            axis: None,
            axis2: None,
            actuated: false,
            damping: 0.0,
            stiffness: 0.0,
            armature: 0.0,
            friction: 0.0,
            lower: None,
            upper: None,
            effort: None,
            stop_stiffness: None,
            stop_damping: None,
            initial: None,
            description: format!(
                "MJCF <equality {base}> of \"{b1}\" and \"{}\" (a loop-closing joint)",
                b2.as_deref().unwrap_or("world")
            ),
        });
    }
}
