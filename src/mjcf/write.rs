//! The imported spec as editable TOML: the spec's own serialisation (shortest numbers), a
//! header with the notes, and a comment before every body, joint, collision shape and actuator naming
//! the MJCF element it came from.

use super::lower::Outcome;
use crate::import::toml_text::shortest_numbers;
use crate::spec::{Spec, SpecErrors};

/// TOML text of `spec` with the import's comments and notes.
///
/// # Errors
/// A message if the spec cannot be serialised (not for specs made by the importer).
pub fn to_toml(spec: &Spec, outcome: &Outcome) -> Result<String, String> {
    let body = toml::to_string(spec).map_err(|e| e.to_string())?;
    let mut out = format!(
        "# {}\n# Written by `triad import`; edit freely: `triad build` on this file and on the MJCF\n# give the same FMU as long as nothing is changed.\n",
        spec.description
    );
    for n in &outcome.notes {
        out.push_str(&format!("# note: {n}\n"));
    }
    out.push('\n');
    let (mut b, mut j, mut c, mut a) = (0, 0, 0, 0);
    for line in body.lines() {
        let source = match line.trim() {
            "[[body]]" => {
                b += 1;
                outcome.bodies.get(b - 1)
            }
            "[[joint]]" => {
                j += 1;
                outcome.joints.get(j - 1)
            }
            "[[collision]]" => {
                c += 1;
                outcome.collisions.get(c - 1)
            }
            "[[actuator]]" => {
                a += 1;
                outcome.actuators.get(a - 1)
            }
            "load = []" => continue,
            _ => None,
        };
        if let Some(s) = source {
            out.push_str(&format!("\n# MJCF {s}\n"));
        }
        out.push_str(&shortest_numbers(line));
        out.push('\n');
    }
    Ok(out)
}

/// Problems of an imported spec (validated after import) told in the MJCF's terms: the path
/// `body[i]…` becomes `<MJCF element> (body[i]…)`, and so for joints, shapes and actuators.
#[must_use]
pub fn in_mjcf_terms(mut errors: SpecErrors, outcome: &Outcome) -> SpecErrors {
    for p in &mut errors.problems {
        let Some((kind, rest)) = p.path.split_once('[') else {
            continue;
        };
        let Some(i) = rest
            .split_once(']')
            .and_then(|(i, _)| i.parse::<usize>().ok())
        else {
            continue;
        };
        let source = match kind {
            "body" => outcome.bodies.get(i),
            "joint" => outcome.joints.get(i),
            "collision" => outcome.collisions.get(i),
            "actuator" => outcome.actuators.get(i),
            _ => None,
        };
        if let Some(s) = source {
            p.path = format!("{s} ({})", p.path);
        }
    }
    errors
}
