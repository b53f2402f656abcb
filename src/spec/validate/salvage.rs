//! A consistent copy of a spec whose only structure problems are unusable values with an
//! obvious stand-in (a body's mass, inertia or centre of mass, a joint's zero or non-finite
//! axis), so that the later checks (loop closure, the mechanics' set-up) still run and `check`
//! reports their problems in the same run.

use super::super::error::Report;
use super::super::schema::Spec;
use super::super::values::InertiaSpec;

/// A copy of `spec` with placeholders for the values `report` finds unusable, and the elements
/// that got one (`body[0]`, `joint[2]`); `None` when another problem makes the spec unusable
/// (an unknown body, a bad joint type). The caller checks that the copy is consistent.
/// Placeholders: mass 1 kg, the inertia of a uniform sphere of 0.1 m radius of the body's
/// (placeholder) mass, the centre of mass at the origin, the axis `z`.
pub(super) fn salvage(spec: &Spec, report: &Report) -> Option<(Spec, Vec<String>)> {
    let mut copy = spec.clone();
    let mut elements: Vec<String> = Vec::new();
    let mut inertias = Vec::new();
    for p in &report.problems {
        let (element, field) = p.path.split_once('.')?;
        let (kind, index) = element.strip_suffix(']')?.split_once('[')?;
        let i: usize = index.parse().ok()?;
        match (kind, field) {
            ("body", "mass") => copy.body.get_mut(i)?.mass = 1.0,
            ("body", "com") => copy.body.get_mut(i)?.com = [0.0; 3],
            ("body", "inertia") => inertias.push(i),
            ("joint", "axis") if p.message == "zero length" || p.message.contains("finite") => {
                copy.joint.get_mut(i)?.axis = Some([0.0, 0.0, 1.0]);
            }
            _ => return None,
        }
        if !elements.iter().any(|e| e == element) {
            elements.push(element.to_string());
        }
    }
    for i in inertias {
        let b = copy.body.get_mut(i)?;
        let j = 0.4 * b.mass * 0.01;
        b.inertia = InertiaSpec::Diagonal([j; 3]);
    }
    Some((copy, elements))
}
