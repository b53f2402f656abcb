//! `<equality>`: `connect` and `weld` as loop-closing joints, `joint` with a linear
//! `polycoef` as a `[[coupling]]`.

use std::collections::HashMap;

use super::lower::{Host, Outcome};
use super::model::{Equality, Model};
use crate::import::frame::Iso;
use crate::import::names::Namer;
use crate::math::{Mat3, Vec3};
use crate::spec::{CouplingSpec, JointKind, JointSpec, Problem, Spec};

/// `<equality>`: `connect` and `weld` become loop-closing spherical and fixed joints between
/// the two bodies' hosts, placed where the bodies are at `qpos0`; `joint` becomes a coupling
/// (`coupling`).
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
            Equality::Joint {
                at,
                joint1,
                joint2,
                polycoef,
            } => {
                if let Some(c) = coupling(
                    m,
                    joint_of,
                    spec,
                    at,
                    joint1,
                    joint2.as_deref(),
                    polycoef,
                    problems,
                ) {
                    // the follower has no input, and its initial state follows the leader's
                    if let Some(js) = spec.joint.iter_mut().find(|j| j.name == c.b) {
                        js.actuated = false;
                        js.initial = None;
                    }
                    spec.coupling.push(c);
                }
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
            actuatorfrcrange: None,
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

/// `<equality joint>` as the coupling `q₁ = c₁ q₂ + (c₀ + q₁,₀ − c₁ q₂,₀)` (`q = qpos`, so
/// `qpos0` is each joint's `ref`): two hinges or two slides with a linear `polycoef`; a lock
/// (no `joint2`), a polynomial of higher degree, `c₁ = 0` or other joint kinds are refused on
/// the element's line.
#[allow(clippy::too_many_arguments)]
fn coupling(
    m: &Model,
    joint_of: &HashMap<String, usize>,
    spec: &Spec,
    at: &str,
    joint1: &str,
    joint2: Option<&str>,
    c: &[f64; 5],
    problems: &mut Vec<Problem>,
) -> Option<CouplingSpec> {
    let mut bad = |why: String| {
        problems.push(Problem::new(at.to_string(), why));
        None
    };
    let Some(joint2) = joint2 else {
        return bad(format!("<equality joint joint1=\"{joint1}\"> without joint2 locks the joint: not supported (a coupling needs two joints)"));
    };
    let (Some(&b), Some(&a)) = (joint_of.get(joint1), joint_of.get(joint2)) else {
        for n in [joint1, joint2] {
            if !joint_of.contains_key(n) {
                problems.push(Problem::new(
                    at.to_string(),
                    format!("joint \"{n}\" does not exist"),
                ));
            }
        }
        return None;
    };
    if c[2..].iter().any(|&x| x != 0.0) || c[1] == 0.0 {
        return bad(format!(
            "polycoef {c:?}: only a linear coupling (c2 = c3 = c4 = 0, c1 ≠ 0) is supported"
        ));
    }
    let (ja, jb) = (&spec.joint[a], &spec.joint[b]);
    let one = matches!(ja.kind, JointKind::Revolute | JointKind::Prismatic);
    if ja.kind != jb.kind || !one {
        return bad(format!(
            "joints \"{joint1}\" and \"{joint2}\" must both be hinges or both slides to be coupled"
        ));
    }
    let reference = |name: &str| {
        m.bodies
            .iter()
            .flat_map(|body| &body.joints)
            .find(|j| j.name.as_deref() == Some(name))
            .map_or(0.0, |j| j.reference)
    };
    let (r1, r2) = (reference(joint1), reference(joint2));
    Some(CouplingSpec {
        a: ja.name.clone(),
        b: jb.name.clone(),
        ratio: c[1],
        offset: c[0] + r1 - c[1] * r2,
    })
}
