//! Joint checks: references, axes, per-type fields, initial values, and the tree/loop structure
//! (every body posed exactly once: by one tree joint, or as a free body).

use std::collections::HashMap;

use super::common::{check_finite, normalized};
use crate::mechanics::ranges;
use crate::spec::error::{did_you_mean, Report};
use crate::spec::schema::{JointKind, JointSpec, Spec};

pub(super) fn kind_name(k: JointKind) -> &'static str {
    crate::spec::lower::joint_type(k).name()
}

fn needs_axis(k: JointKind) -> bool {
    !matches!(k, JointKind::Spherical | JointKind::Fixed)
}

/// Checks one joint's own fields.
fn fields(report: &mut Report, p: &str, j: &JointSpec) {
    let kind = kind_name(j.kind);
    check_finite(
        report,
        &format!("{p}.origin"),
        &[j.origin.xyz, j.origin.rpy].concat(),
    );
    if let Some(c) = &j.child_origin {
        check_finite(
            report,
            &format!("{p}.child_origin"),
            &[c.xyz, c.rpy].concat(),
        );
    }
    match (needs_axis(j.kind), j.axis) {
        (true, None) => report.push(
            p,
            format!("a {kind} joint needs axis = [x, y, z] (in the joint frame)"),
        ),
        (false, Some(_)) => {
            report.push(format!("{p}.axis"), format!("a {kind} joint takes no axis"))
        }
        (true, Some(a)) => {
            if a.iter().any(|x| !x.is_finite()) {
                check_finite(report, &format!("{p}.axis"), &a);
            } else if normalized(a).is_none() {
                report.push(format!("{p}.axis"), "zero length");
            }
        }
        (false, None) => {}
    }
    match (j.kind == JointKind::Universal, j.axis2) {
        (true, None) => report.push(
            p,
            "a universal joint needs axis2 = [x, y, z], perpendicular to axis",
        ),
        (false, Some(_)) => report.push(
            format!("{p}.axis2"),
            format!("only universal joints take axis2, not a {kind} joint"),
        ),
        (true, Some(b)) => {
            if b.iter().any(|x| !x.is_finite()) {
                check_finite(report, &format!("{p}.axis2"), &b);
            } else if let Some(b) = normalized(b) {
                if let Some(a) = j.axis.and_then(normalized) {
                    let c = a.dot(&b);
                    if c.abs() > 1e-9 {
                        report.push(
                            format!("{p}.axis2"),
                            format!("must be perpendicular to axis (cos angle = {c:.3e})"),
                        );
                    }
                }
            } else {
                report.push(format!("{p}.axis2"), "zero length");
            }
        }
        (false, None) => {}
    }
    if j.actuated && matches!(j.kind, JointKind::Planar | JointKind::Fixed) {
        report.push(
            format!("{p}.actuated"),
            format!("{kind} joints cannot be actuated; use a [[load]] on the child body instead"),
        );
    }
    for (field, v) in [("damping", j.damping), ("stiffness", j.stiffness)] {
        if let Err(e) = ranges::non_negative(v) {
            report.push(format!("{p}.{field}"), e);
        } else if v > 0.0 && j.kind == JointKind::Fixed {
            report.push(
                format!("{p}.{field}"),
                "a fixed joint has no motion to damp or spring",
            );
        }
    }
    for (field, v, what) in [
        ("armature", j.armature, "armature (rotor inertia acts"),
        ("friction", j.friction, "friction (joint friction acts"),
    ] {
        if let Err(e) = ranges::non_negative(v) {
            report.push(format!("{p}.{field}"), e);
        } else if v > 0.0 && j.is_loop_closing() {
            report.push(
                format!("{p}.{field}"),
                format!("a loop-closing joint takes no {field} (its coordinate is not free: put it on a tree joint of the loop)"),
            );
        } else if v > 0.0
            && (j.kind == JointKind::Fixed
                || (j.kind == JointKind::Spherical && field == "armature"))
        {
            report.push(
                format!("{p}.{field}"),
                format!(
                    "{} joints take no {what} on a joint coordinate: revolute, prismatic, cylindrical, universal or planar{})",
                    kind_name(j.kind),
                    if field == "friction" { "; on a spherical joint, on its relative rotation" } else { "" }
                ),
            );
        }
    }
    if j.stiffness != 0.0 && j.kind == JointKind::Spherical {
        report.push(
            format!("{p}.stiffness"),
            "spherical joints take no stiffness (there is no single angle to spring)",
        );
    }
    limits(report, p, j);
    initial(report, p, j);
}

/// Checks the position limits, the effort limit and the stop parameters.
fn limits(report: &mut Report, p: &str, j: &JointSpec) {
    let fields = [
        ("lower", j.lower),
        ("upper", j.upper),
        ("effort", j.effort),
        ("stop_stiffness", j.stop_stiffness),
        ("stop_damping", j.stop_damping),
    ];
    let limited = matches!(j.kind, JointKind::Revolute | JointKind::Prismatic);
    for (field, v) in fields {
        let Some(v) = v else { continue };
        if !limited {
            report.push(
                format!("{p}.{field}"),
                format!(
                    "only revolute and prismatic joints take limits, not a {} joint",
                    kind_name(j.kind)
                ),
            );
        } else {
            // the FMU's fmi2SetReal applies the same rules to these parameters
            let check = match field {
                "stop_damping" => ranges::non_negative(v),
                "effort" | "stop_stiffness" => ranges::positive(v),
                _ => ranges::any_finite(v),
            };
            if let Err(e) = check {
                report.push(format!("{p}.{field}"), e);
            }
        }
    }
    if let (Some(lo), Some(hi)) = (j.lower, j.upper) {
        if limited && lo >= hi {
            report.push(
                format!("{p}.upper"),
                format!("must be greater than lower ({hi} <= {lo})"),
            );
        }
    }
    if let Some([lo, hi]) = j.actuatorfrcrange {
        let field = format!("{p}.actuatorfrcrange");
        if !limited {
            report.push(
                field,
                format!(
                    "only revolute and prismatic joints take actuators, not a {} joint",
                    kind_name(j.kind)
                ),
            );
        } else if !(lo.is_finite() && hi.is_finite() && lo < hi) {
            report.push(
                field,
                format!("must be [lo, hi] with finite lo < hi (got [{lo}, {hi}])"),
            );
        }
    }
    if limited && j.lower.is_none() && j.upper.is_none() {
        for (field, v) in &fields[3..] {
            if v.is_some() {
                report.push(
                    format!("{p}.{field}"),
                    "the joint has no stops: set lower and/or upper",
                );
            }
        }
    }
}

/// Checks `initial` against the joint type.
fn initial(report: &mut Report, p: &str, j: &JointSpec) {
    let Some(init) = &j.initial else { return };
    let p = format!("{p}.initial");
    let kind = kind_name(j.kind);
    if j.is_loop_closing() {
        report.push(
            p,
            "a loop-closing joint takes no initial values: its state follows from the tree joints",
        );
        return;
    }
    if j.kind == JointKind::Fixed {
        report.push(p, "a fixed joint has no coordinates");
        return;
    }
    if j.kind == JointKind::Spherical {
        for (field, present) in [("q", init.q.is_some()), ("qd", init.qd.is_some())] {
            if present {
                report.push(
                    format!("{p}.{field}"),
                    "a spherical joint takes rpy or quat, and w",
                );
            }
        }
        if init.rpy.is_some() && init.quat.is_some() {
            report.push(p.clone(), "give rpy or quat, not both");
        }
        if let Some(r) = init.rpy {
            check_finite(report, &format!("{p}.rpy"), &r);
        }
        if let Some(q) = init.quat {
            check_finite(report, &format!("{p}.quat"), &q);
            if q.iter().all(|x| x.is_finite()) && q.iter().map(|x| x * x).sum::<f64>().sqrt() < 1e-9
            {
                report.push(format!("{p}.quat"), "quaternion has zero length");
            }
        }
        if let Some(w) = init.w {
            check_finite(report, &format!("{p}.w"), &w);
        }
        return;
    }
    for (field, present) in [
        ("rpy", init.rpy.is_some()),
        ("quat", init.quat.is_some()),
        ("w", init.w.is_some()),
    ] {
        if present {
            report.push(
                format!("{p}.{field}"),
                format!("only spherical joints take {field}; a {kind} joint takes q and qd"),
            );
        }
    }
    let nq = crate::spec::lower::joint_type(j.kind).nq();
    for (field, c) in [("q", &init.q), ("qd", &init.qd)] {
        let Some(c) = c else { continue };
        let v = c.values();
        let path = format!("{p}.{field}");
        if v.len() != nq {
            let want = if nq == 1 {
                "1 number".to_string()
            } else {
                format!("{nq} numbers")
            };
            let coords = if nq == 1 { "coordinate" } else { "coordinates" };
            report.push(
                path,
                format!(
                    "a {kind} joint has {nq} {coords}: expected {want}, found {}",
                    v.len()
                ),
            );
        } else {
            check_finite(report, &path, &v);
        }
    }
}

/// References and the tree/loop structure.
pub(super) fn check(spec: &Spec, report: &mut Report, body_index: &HashMap<&str, usize>) {
    let n = spec.body.len();
    let mut tree_parent: Vec<Option<usize>> = vec![None; n];
    let mut touched = vec![false; n];
    for (i, j) in spec.joint.iter().enumerate() {
        let p = format!("joint[{i}]");
        fields(report, &p, j);
        let parent = if j.parent == "world" {
            Some(None)
        } else {
            body_index.get(j.parent.as_str()).map(|b| Some(*b))
        };
        if parent.is_none() {
            let hint = did_you_mean(&j.parent, body_index.keys().copied().chain(["world"]));
            report.push(
                format!("{p}.parent"),
                format!(
                    "no body named \"{}\" (use a [[body]] name or \"world\"){hint}",
                    j.parent
                ),
            );
        }
        let child = body_index.get(j.child.as_str()).copied();
        if j.child == "world" {
            report.push(
                format!("{p}.child"),
                "the world cannot be a child: swap parent and child",
            );
        } else if child.is_none() {
            let hint = did_you_mean(&j.child, body_index.keys().copied());
            report.push(
                format!("{p}.child"),
                format!("no body named \"{}\"{hint}", j.child),
            );
        }
        if j.parent == j.child {
            report.push(
                format!("{p}.child"),
                "a joint cannot connect a body to itself",
            );
            continue;
        }
        for b in [parent.flatten(), child].into_iter().flatten() {
            touched[b] = true;
        }
        let Some(c) = child else { continue };
        if j.is_loop_closing() {
            continue;
        }
        match tree_parent[c] {
            Some(first) => report.push(
                format!("{p}.child"),
                format!(
                    "body \"{}\" already has a tree parent (joint[{first}] \"{}\"); if this joint closes a loop, give it child_origin = {{ xyz = [...], rpy = [...] }} (its frame in the child)",
                    j.child, spec.joint[first].name
                ),
            ),
            None => tree_parent[c] = Some(i),
        }
    }
    // poses: every body is a tree child, or free (no joint at all, with a position); a
    // misspelt child or a duplicate name already explains a missing pose
    let unresolved = spec
        .joint
        .iter()
        .any(|j| j.child != "world" && !body_index.contains_key(j.child.as_str()));
    let duplicate = |b: usize| body_index.get(spec.body[b].name.as_str()) != Some(&b);
    for (b, body) in spec.body.iter().enumerate() {
        let p = format!("body[{b}]");
        let free_fields = [
            ("position", body.position.is_some()),
            ("orientation", body.orientation.is_some()),
            ("velocity", body.velocity.is_some()),
            ("angular_velocity", body.angular_velocity.is_some()),
        ];
        if let Some(ji) = tree_parent[b] {
            for (field, present) in free_fields {
                if present {
                    report.push(format!("{p}.{field}"), format!("body \"{}\" is placed by joint \"{}\"; only free bodies and floating bases (bodies that are no tree joint's child) take {field}: set the joint's initial values instead", body.name, spec.joint[ji].name));
                }
            }
        } else if touched[b] && body.position.is_none() {
            report.push(p, format!("body \"{}\" has no tree joint to the world (it is only a parent or a loop-closing child): attach it with a joint without child_origin, or make it a floating base by giving position = [x, y, z] (and optionally orientation, velocity, angular_velocity)", body.name));
        } else if body.position.is_none() && !unresolved && !duplicate(b) {
            report.push(p, format!("body \"{}\" has no pose: attach it with a [[joint]], or make it a free body by giving position = [x, y, z] (and optionally orientation, velocity, angular_velocity)", body.name));
        }
    }
    // cycles among tree joints: a chain of tree parents that returns to where it started
    // (reported once, from the cycle's lowest body index)
    for start in 0..n {
        let mut b = start;
        let mut path = Vec::new();
        for _ in 0..=n {
            let Some(ji) = tree_parent[b] else { break };
            path.push(ji);
            match body_index.get(spec.joint[ji].parent.as_str()) {
                Some(&parent) if parent == start => {
                    let lowest = path.iter().all(|&j| {
                        body_index
                            .get(spec.joint[j].child.as_str())
                            .is_none_or(|&c| c >= start)
                    });
                    if lowest {
                        let names: Vec<&str> =
                            path.iter().map(|&j| spec.joint[j].name.as_str()).collect();
                        report.push(
                            format!("joint[{ji}]"),
                            format!("tree joints {} form a cycle that never reaches the world; mark the joint that closes it as loop-closing by giving it child_origin", names.join(", ")),
                        );
                    }
                    break;
                }
                Some(&parent) => b = parent,
                None => break,
            }
        }
    }
}
