//! A consistent copy of a spec whose only structure problems are a body's mass, inertia or
//! centre of mass, so that the later checks (loop closure, the mechanics' set-up) still run and
//! `check` reports their problems in the same run.

use super::super::error::Report;
use super::super::schema::Spec;
use super::super::values::InertiaSpec;

/// A copy of `spec` with placeholders for the values `report` finds unusable, and the indices
/// of the bodies that got one; `None` when another problem makes the spec unusable (an unknown
/// body, a bad joint). The caller checks that the copy is consistent. Placeholders: mass 1 kg, the inertia of
/// a uniform sphere of 0.1 m radius of the body's (placeholder) mass, the centre of mass at the
/// origin.
pub(super) fn salvage(spec: &Spec, report: &Report) -> Option<(Spec, Vec<usize>)> {
    let mut copy = spec.clone();
    let mut bodies = Vec::new();
    for p in &report.problems {
        let rest = p.path.strip_prefix("body[")?;
        let (index, field) = rest.split_once("].")?;
        let i: usize = index.parse().ok()?;
        let body = copy.body.get_mut(i)?;
        match field {
            "mass" => body.mass = 1.0,
            "com" => body.com = [0.0; 3],
            "inertia" => {}
            _ => return None,
        }
        if !bodies.contains(&i) {
            bodies.push(i);
        }
    }
    for &i in &bodies {
        let b = &mut copy.body[i];
        let bad_inertia = report
            .problems
            .iter()
            .any(|p| p.path == format!("body[{i}].inertia"));
        if bad_inertia {
            let j = 0.4 * b.mass * 0.01;
            b.inertia = InertiaSpec::Diagonal([j; 3]);
        }
    }
    Some((copy, bodies))
}
