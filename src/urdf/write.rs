//! The imported spec as editable TOML: the spec's own serialisation (numbers in their shortest
//! round-trip form, `1e-10` rather than `0.0000000001`, so reading it back gives the same spec and
//! the same FMU), with a header (the notes, and a `# warning:` line for every `<visual>` or
//! `<collision>` dropped) and a comment before every body, joint, site and collision shape
//! naming the URDF elements it came from (and one before the ground saying what it holds).

use super::lower::Outcome;
use crate::import::toml_text::shortest_numbers;
use crate::spec::Spec;

/// TOML text of `spec` with the import's comments and notes.
///
/// # Errors
/// A message if the spec cannot be serialised (not for specs made by the importer).
pub fn to_toml(spec: &Spec, outcome: &Outcome) -> Result<String, String> {
    let body = toml::to_string(spec).map_err(|e| e.to_string())?;
    let mut out = String::new();
    out.push_str(&format!("# {}\n", spec.description));
    out.push_str(
        "# Written by `triad import`; edit freely: `triad build` on this file and on the URDF\n",
    );
    out.push_str("# give the same FMU as long as nothing is changed.\n");
    for n in &outcome.notes {
        out.push_str(&format!("# note: {n}\n"));
    }
    for w in &outcome.warnings {
        out.push_str(&format!("# warning: {w}\n"));
    }
    out.push('\n');
    let (mut b, mut j, mut k, mut c) = (0, 0, 0, 0);
    for line in body.lines() {
        match line.trim() {
            "[ground]" => out.push_str(
                "\n# The ground (--contacts): a plane at `height` along the normal against gravity;\n\
                 # Coulomb `friction`, normal `stiffness` (N/m) and Hunt-Crossley `damping` (s/m,\n\
                 # normal force k x (1 + damping x')); also the FMU parameters ground.*\n",
            ),
            "[[collision]]" => {
                if let Some(source) = outcome.collisions.get(c) {
                    if c == 0 {
                        out.push_str(
                            "\n# Collision shapes (--contacts), in their bodies' frames: every shape touches the\n\
                             # ground; outputs contact.NAME.f[1..3] (N, world frame) and contact.NAME.gap (m)\n",
                        );
                    }
                    out.push_str(&format!("\n# {source}\n"));
                }
                c += 1;
            }
            // the importer declares no loads; an empty list says nothing
            "load = []" => continue,
            "[[site]]" => {
                if let Some(s) = spec.site.get(k) {
                    let original = s.description.strip_prefix("URDF link ");
                    out.push_str(&format!(
                        "\n# URDF link {} (welded to {} by a fixed joint: a site)\n",
                        original.map_or_else(|| format!("\"{}\"", s.name), str::to_string),
                        s.body
                    ));
                }
                k += 1;
            }
            "[[body]]" => {
                if let Some((_, links)) = outcome.merged.get(b) {
                    out.push('\n');
                    match links.as_slice() {
                        [one] => out.push_str(&format!("# URDF link \"{one}\"\n")),
                        [first, rest @ ..] => out.push_str(&format!(
                            "# URDF link \"{first}\" with the links merged into it by fixed joints: {}\n",
                            rest.iter().map(|l| format!("\"{l}\"")).collect::<Vec<_>>().join(", ")
                        )),
                        [] => {}
                    }
                }
                if let Some((name, why)) = &outcome.placed {
                    if spec.body.get(b).is_some_and(|body| body.name == *name) {
                        out.push_str(&format!("# position: {why}\n"));
                    }
                }
                b += 1;
            }
            "[[joint]]" => {
                if let Some(s) = spec.joint.get(j) {
                    out.push('\n');
                    let original = outcome
                        .renamed
                        .iter()
                        .find(|(kind, id, _)| *kind == "joint" && *id == s.name)
                        .map_or(s.name.as_str(), |(_, _, o)| o.as_str());
                    out.push_str(&format!("# URDF joint \"{original}\"\n"));
                }
                j += 1;
            }
            _ => {}
        }
        out.push_str(&shortest_numbers(line));
        out.push('\n');
    }
    Ok(out)
}

/// Problems of an imported spec (validated after import) told in the URDF's terms: the path
/// `body[i]…` becomes `line L: link "<URDF name>" (body[i]…)`, `joint[i]…` becomes
/// `line L: joint "<URDF name>" (joint[i]…)`.
#[must_use]
pub fn in_urdf_terms(
    mut errors: crate::spec::SpecErrors,
    spec: &Spec,
    outcome: &Outcome,
) -> crate::spec::SpecErrors {
    for p in &mut errors.problems {
        let Some((kind, rest)) = p.path.split_once('[') else {
            continue;
        };
        let Some((index, _)) = rest.split_once(']') else {
            continue;
        };
        let Ok(i) = index.parse::<usize>() else {
            continue;
        };
        let is_body = kind == "body";
        let original = match kind {
            "body" => outcome
                .merged
                .get(i)
                .and_then(|(_, links)| links.first().cloned()),
            "joint" => spec.joint.get(i).map(|j| {
                outcome
                    .renamed
                    .iter()
                    .find(|(k, id, _)| *k == "joint" && *id == j.name)
                    .map_or_else(|| j.name.clone(), |(_, _, o)| o.clone())
            }),
            _ => None,
        };
        if let Some(name) = original {
            let (what, lines) = if kind == "body" {
                ("link", &outcome.body_lines)
            } else {
                ("joint", &outcome.joint_lines)
            };
            let line = lines
                .get(i)
                .map_or_else(String::new, |l| format!("line {l}: "));
            p.path = format!("{line}{what} \"{name}\" ({})", p.path);
        }
        // a free body is welded by the import's options, not by a joint of the URDF
        let body = is_body.then(|| spec.body.get(i)).flatten();
        if let Some(how) = body.and_then(|b| {
            outcome
                .free_bases
                .iter()
                .find(|(n, _)| *n == b.name)
                .map(|(_, how)| how)
        }) {
            p.message = p.message.replace("(a fixed joint)", &format!("({how})"));
        }
    }
    errors
}
