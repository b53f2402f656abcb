//! Consistency checks of a parsed spec. Every check runs and every problem is reported; the
//! mechanics is asked to build the model only when the spec itself is consistent.

use std::collections::HashMap;

use crate::mechanics::{ranges, Model, ModelError};

use super::error::{did_you_mean, Report, SpecErrors};
use super::schema::{BodySpec, Spec};
use super::values::{rows_to_matrix, OrientationSpec};
use super::{kinematics, lower};
use common::check_finite;

mod actuators;
mod common;
mod contact;
mod couplings;
mod joints;
mod salvage;

/// Largest loop-closure violation accepted at the initial pose, m or 1: the mechanics' own
/// tolerance, so that the spec check and `Model::new` agree.
const LOOP_TOLERANCE: f64 = crate::mechanics::loops::LOOP_TOLERANCE;

pub(crate) use common::is_identifier;

fn check_name(report: &mut Report, path: &str, name: &str) {
    if !is_identifier(name) {
        report.push(path, format!("\"{name}\" is not an identifier: use letters, digits and _ and do not start with a digit"));
    }
}

/// Checks names for being identifiers and unique; returns name → first index.
fn check_names<'a>(
    report: &mut Report,
    what: &str,
    names: impl Iterator<Item = &'a str>,
) -> HashMap<&'a str, usize> {
    let mut seen: HashMap<&str, usize> = HashMap::new();
    for (i, name) in names.enumerate() {
        let path = format!("{what}[{i}].name");
        check_name(report, &path, name);
        if let Some(first) = seen.get(name) {
            report.push(
                path,
                format!("duplicate {what} name \"{name}\" (also {what}[{first}])"),
            );
        } else {
            seen.insert(name, i);
        }
    }
    seen
}

fn top_level(spec: &Spec, report: &mut Report) {
    check_name(report, "name", &spec.name);
    check_finite(report, "gravity", &spec.gravity);
    let e = &spec.experiment;
    check_finite(report, "experiment", &[e.start, e.stop, e.step]);
    if e.start.is_finite() && e.stop.is_finite() && e.stop <= e.start {
        report.push(
            "experiment.stop",
            format!(
                "must be greater than experiment.start ({} <= {})",
                e.stop, e.start
            ),
        );
    }
    if e.step.is_nan() || e.step <= 0.0 {
        report.push(
            "experiment.step",
            format!("must be positive (got {})", e.step),
        );
    }
    let s = &spec.solver;
    let checks = [
        ("solver.max_step", ranges::max_step(s.max_step)),
        ("solver.order", ranges::order(f64::from(s.order)).map(drop)),
        ("solver.tolerance", ranges::tolerance(s.tolerance)),
        (
            "solver.max_substeps",
            ranges::max_substeps(f64::from(s.max_substeps)).map(drop),
        ),
        (
            "solver.stages",
            ranges::stages(f64::from(s.stages)).map(drop),
        ),
        ("solver.rtol", ranges::rtol(s.rtol)),
        ("solver.atol", ranges::atol(s.atol)),
        ("solver.min_step", ranges::min_step(s.min_step)),
    ];
    for (path, check) in checks {
        if let Err(e) = check {
            report.push(path, e);
        }
    }
}

fn bodies(spec: &Spec, report: &mut Report) {
    for (i, b) in spec.body.iter().enumerate() {
        let p = format!("body[{i}]");
        if b.name == "world" {
            report.push(
                format!("{p}.name"),
                "\"world\" is reserved for the fixed world frame",
            );
        }
        if let Err(e) = ranges::non_negative(b.mass) {
            report.push(format!("{p}.mass"), e);
        }
        check_finite(report, &format!("{p}.com"), &b.com);
        inertia(report, &format!("{p}.inertia"), b);
        for (field, v) in [
            ("position", b.position),
            ("velocity", b.velocity),
            ("angular_velocity", b.angular_velocity),
        ] {
            if let Some(v) = v {
                check_finite(report, &format!("{p}.{field}"), &v);
            }
        }
        match &b.orientation {
            Some(o) if o.numbers().iter().any(|x| !x.is_finite()) => {
                check_finite(report, &format!("{p}.orientation"), &o.numbers())
            }
            Some(OrientationSpec::Quat(q))
                if q.iter().map(|x| x * x).sum::<f64>().sqrt() < 1e-9 =>
            {
                report.push(format!("{p}.orientation"), "quaternion has zero length");
            }
            Some(OrientationSpec::Matrix(m)) => {
                let r = rows_to_matrix(m);
                let err = (r.transpose() * r - crate::math::Mat3::identity()).amax();
                let at = format!("{p}.orientation");
                if err > 1e-9 {
                    report.push(at, format!("is not a rotation matrix: its rows are not orthonormal (largest entry of RᵀR − I is {err:.1e})"));
                } else if r.determinant() < 0.0 {
                    report.push(at, "is a reflection (determinant −1), not a rotation");
                }
            }
            _ => {}
        }
    }
}

fn inertia(report: &mut Report, path: &str, b: &BodySpec) {
    let numbers = b.inertia.numbers();
    if numbers.iter().any(|x| !x.is_finite()) {
        check_finite(report, path, &numbers);
    } else if let Err(e) = ranges::inertia(&b.inertia.matrix()) {
        report.push(path, e);
    }
}

fn loads(spec: &Spec, report: &mut Report, body_index: &HashMap<&str, usize>) {
    let mut seen: HashMap<&str, usize> = HashMap::new();
    for (i, l) in spec.load.iter().enumerate() {
        let p = format!("load[{i}]");
        if !body_index.contains_key(l.body.as_str()) {
            let hint = did_you_mean(&l.body, body_index.keys().copied());
            report.push(
                format!("{p}.body"),
                format!("no body named \"{}\"{hint}", l.body),
            );
        }
        if !l.torque && !l.force {
            report.push(
                p.clone(),
                "adds no inputs: set torque = true and/or force = true",
            );
        }
        if let Some(first) = seen.insert(l.body.as_str(), i) {
            report.push(
                format!("{p}.body"),
                format!(
                    "body \"{}\" already has a load (load[{first}]); merge them",
                    l.body
                ),
            );
        }
    }
}

fn sites(spec: &Spec, report: &mut Report, body_index: &HashMap<&str, usize>) {
    for (i, s) in spec.site.iter().enumerate() {
        let p = format!("site[{i}]");
        if !body_index.contains_key(s.body.as_str()) {
            let why = if s.body == "world" {
                "a site must be fixed on a body: a frame fixed in the world does not move".into()
            } else {
                let hint = did_you_mean(&s.body, body_index.keys().copied());
                format!("no body named \"{}\"{hint}", s.body)
            };
            report.push(format!("{p}.body"), why);
        }
        check_finite(
            report,
            &format!("{p}.origin"),
            &[s.origin.xyz, s.origin.rpy].concat(),
        );
    }
}

fn visuals(spec: &Spec, report: &mut Report, body_index: &HashMap<&str, usize>) {
    for (i, v) in spec.visual.iter().enumerate() {
        let p = format!("visual[{i}]");
        if v.body != "world" && !body_index.contains_key(v.body.as_str()) {
            let hint = did_you_mean(&v.body, body_index.keys().copied());
            report.push(
                format!("{p}.body"),
                format!("no body named \"{}\"{hint}", v.body),
            );
        }
        check_finite(
            report,
            &format!("{p}.origin"),
            &[v.origin.xyz, v.origin.rpy].concat(),
        );
        let sizes: Vec<(&str, Vec<f64>)> = [
            ("box", v.cuboid.map(|b| b.to_vec())),
            ("cylinder", v.cylinder.map(|c| c.to_vec())),
            ("sphere", v.sphere.map(|s| vec![s])),
            ("mesh", v.mesh.as_ref().map(|_| Vec::new())),
        ]
        .into_iter()
        .filter_map(|(k, s)| s.map(|s| (k, s)))
        .collect();
        if sizes.len() != 1 {
            report.push(p.clone(), "give exactly one of box, cylinder, sphere, mesh");
        }
        for (k, s) in &sizes {
            if s.iter().any(|x| !(x.is_finite() && *x >= 0.0)) {
                report.push(format!("{p}.{k}"), "sizes must be finite and >= 0");
            }
        }
        if v.scale.is_some() && v.mesh.is_none() {
            report.push(format!("{p}.scale"), "only a mesh takes a scale");
        }
        for (k, x) in [
            ("scale", v.scale.map(|s| s.to_vec())),
            ("rgba", v.rgba.map(|c| c.to_vec())),
        ] {
            if let Some(x) = x {
                check_finite(report, &format!("{p}.{k}"), &x);
            }
        }
    }
}

/// Every check that needs only the spec (no mechanics).
pub(crate) fn structure(spec: &Spec) -> Report {
    let mut report = Report::default();
    top_level(spec, &mut report);
    let body_index = check_names(
        &mut report,
        "body",
        spec.body.iter().map(|b| b.name.as_str()),
    );
    let joint_index = check_names(
        &mut report,
        "joint",
        spec.joint.iter().map(|j| j.name.as_str()),
    );
    bodies(spec, &mut report);
    joints::check(spec, &mut report, &body_index);
    loads(spec, &mut report, &body_index);
    check_names(
        &mut report,
        "site",
        spec.site.iter().map(|s| s.name.as_str()),
    );
    sites(spec, &mut report, &body_index);
    visuals(spec, &mut report, &body_index);
    contact::check(spec, &mut report, &body_index);
    couplings::check(spec, &mut report);
    actuators::check(spec, &mut report, &joint_index);
    if spec.body.is_empty() {
        report.push("body", "the model has no bodies: add at least one [[body]]");
    }
    report
}

/// The note of a spec that could not be read whole (syntax or shape problems).
pub(crate) const SKIPPED_UNREAD: &str = "further checks skipped: the initial pose (loop \
    closure) and the mechanics' checks (determinacy of bodies without mass) need the whole \
    spec read; fix the problems above, then check again";

/// Full validation: structure, loop closure at the initial pose, and the mechanics' own set-up.
/// When the structure has problems, the later checks run on a salvaged copy (`salvage`: a
/// body's unusable mass, inertia or centre of mass, a joint's zero axis replaced by a
/// placeholder) if one can be made, leaving out what they say of the elements given
/// placeholders; otherwise they are skipped with a note.
pub(super) fn validate(spec: &Spec, origin: &str) -> Result<(), SpecErrors> {
    let mut report = structure(spec);
    if report.is_empty() {
        mechanics(spec, &mut report);
        return report.finish(origin);
    }
    match salvage::salvage(spec, &report).filter(|(copy, _)| structure(copy).is_empty()) {
        Some((salvaged, elements)) => {
            let mut more = Report::default();
            mechanics(&salvaged, &mut more);
            let placeholder = |path: &str| {
                elements
                    .iter()
                    .any(|e| path == e || path.starts_with(&format!("{e}.")))
            };
            report
                .problems
                .extend(more.problems.into_iter().filter(|p| !placeholder(&p.path)));
            report.notes.extend(more.notes);
        }
        None => report.notes.push(
            "further checks skipped: the initial pose (loop closure) and the mechanics' checks \
             (determinacy of bodies without mass) need a consistent spec; fix the problems \
             above, then check again"
                .into(),
        ),
    }
    report.finish(origin)
}

/// The checks on a consistent spec: loop closure at the initial pose, then the mechanics' own
/// set-up (`Model::new`: determinacy of bodies without mass, redundant loops).
fn mechanics(spec: &Spec, report: &mut Report) {
    let (def, settings) = lower::build(spec);
    for (k, residual) in kinematics::loop_residuals(&def) {
        if residual.is_nan() || residual > LOOP_TOLERANCE {
            let name = &def.joints[k].name;
            let i = spec.joint_index(name).unwrap_or(k);
            report.push(
                format!("joint[{i}]"),
                format!("loop-closing joint \"{name}\" is violated by the initial pose by {residual:.3e} (tolerance {LOOP_TOLERANCE:e}): choose the tree joints' initial q so that the loop closes (child_origin must meet origin)"),
            );
        }
    }
    if !report.is_empty() {
        report.notes.push(
            "further checks skipped: the mechanics' checks (determinacy of bodies without mass) \
             need the loops closed at the initial pose"
                .into(),
        );
        return;
    }
    if let Err(e) = Model::new(&def, settings) {
        match &e {
            ModelError::LoopNotClosed { joint, residual } => {
                let i = spec
                    .joint_index(joint)
                    .map_or(String::from("joint"), |i| format!("joint[{i}]"));
                report.push(i, format!("loop-closing joint \"{joint}\" is violated by the initial pose by {residual:.3e}: choose the tree joints' initial q so that the loop closes"));
            }
            ModelError::Undetermined { body, why } => {
                let i = spec
                    .body
                    .iter()
                    .position(|b| b.name == *body)
                    .map_or(String::from("body"), |i| format!("body[{i}]"));
                report.push(i, format!("body \"{body}\" {why}"));
            }
            other => report.push("", format!("the mechanics rejected the model: {other}")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identifiers() {
        assert!(is_identifier("link_1") && is_identifier("_a"));
        assert!(
            !is_identifier("1a")
                && !is_identifier("a-b")
                && !is_identifier("")
                && !is_identifier("a.b")
        );
    }
}
