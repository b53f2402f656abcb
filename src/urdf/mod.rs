//! URDF import (interface.md §1–§3): a robot description becomes a model spec, which every
//! command then treats like a spec file (`triad check|describe|simulate|build robot.urdf`), and
//! which `triad import` writes out as editable TOML.
//!
//! Semantics chosen (docs/guide/bring-your-robot.md):
//! - the root link: a root named `world` is the world (a `fixed` joint below it welds the base,
//!   a `floating` joint frees it); any other root is the base, welded to the world by default
//!   (as Pinocchio and MuJoCo do). `--floating-base` frees the base, `--fixed-base` welds a base
//!   the URDF declares floating;
//! - fixed joints merge the child's inertial into its parent's body (mass, centre of mass,
//!   rotated inertia with the parallel-axis term) and make the child's frame a site
//!   (`site.S.r`, `R`, `v`, `w`); `--keep-fixed` keeps such links as bodies on `fixed` joints;
//!   a link welded to the world carries nothing; `<dynamics>` of a fixed joint is ignored with a
//!   note;
//! - one inertial rule in both modes (`mass`): a link whose own inertia is impossible is
//!   accepted with a note when the rigid cluster it is welded into is possible; an impossible
//!   cluster is refused, naming its impossible links at their `<inertia>` lines;
//! - `<inertial>` `origin xyz rpy`: the centre of mass and the axes of the inertia tensor in the
//!   link frame (the tensor is rotated into the link axes); a link without `<inertial>` is
//!   massless;
//! - revolute and continuous joints become actuated `revolute` joints (input `joint.J.tau`),
//!   prismatic ones actuated `prismatic` joints (`joint.J.f`), planar ones `planar` joints;
//!   `<axis>` defaults to `1 0 0`; `<dynamics damping>` is the joint's damping;
//! - `<limit lower upper>` of revolute and prismatic joints become joint stops and `effort`
//!   clamps the actuator input (`--no-limits`: neither); placeholders (`lower = upper`,
//!   `effort = 0`) are left out with a note;
//! - `<visual>` shapes (or a link's `<collision>` shapes when it has no visual) become
//!   `[[visual]]` entries on the host body for the viewer; mesh files are never opened; one
//!   that cannot be read is dropped with a warning (`Outcome::warnings`, with its line): only
//!   what the dynamics needs can refuse a robot;
//! - `--contacts` (`contacts`): `<collision>` spheres, boxes and cylinders become
//!   `[[collision]]` shapes named after their links, on their host bodies, and a `[ground]` is
//!   added; meshes and shapes of links welded to the world are left out with a note;
//! - `--on-ground` (`on_ground`, with a floating base and `--contacts`): the base's initial
//!   `position` is moved against gravity so that the lowest collision shape at the initial pose
//!   rests on the ground (`on_ground`), with a note and a comment in the written TOML;
//! - `<dynamics friction>` becomes the joint's Coulomb `friction` (`--no-friction`,
//!   `no_friction`: left out);
//! - not modelled, reported as a note: `<mimic>` (the joints are independent; a `<mimic>` of a
//!   joint that does not exist is an error);
//! - names that are not identifiers are made identifiers deterministically (`names`), the
//!   original name kept in the description of the element's variables.
//!
//! Errors name the file, the line and the element (`robot.urdf: line 57: joint "elbow": child
//! link "forearm" does not exist`; a cycle names its joints and their lines), all at once.

mod contacts;
mod lower;
mod mass;
mod on_ground;
mod options;
mod robot;
mod write;

pub use lower::Outcome;
pub use options::{Base, ImportOptions};
pub use write::{in_urdf_terms, to_toml};

use crate::import::xml;
use crate::spec::{Problem, Spec, SpecErrors};

/// Reads URDF text into a spec. `origin` (the file name) prefixes every message and goes into
/// the spec's description. The spec is not validated here when the URDF has no problem
/// (`Spec::validate` does that); when it has some, the checks after them still run on what can
/// be salvaged (a link's missing `<inertia>` replaced by a placeholder, the spec's own
/// validation in the URDF's terms), so that one run reports every problem; a stage that cannot
/// run is named in a note of the errors.
///
/// # Errors
/// Every problem found, each with its line and element.
pub fn import(
    text: &str,
    origin: &str,
    opts: &ImportOptions,
) -> Result<(Spec, Outcome), SpecErrors> {
    let fail = |problems: Vec<Problem>| SpecErrors {
        origin: origin.to_string(),
        problems,
        notes: Vec::new(),
    };
    let root = xml::parse(text)
        .map_err(|(line, msg)| fail(vec![Problem::new(format!("line {line}"), msg)]))?;
    let mut problems = Vec::new();
    let mut warnings = Vec::new();
    let robot = robot::robot(&root, &mut problems, &mut warnings);
    if !robot.dropped.is_empty() {
        return Err(fail(problems).noting(format!(
            "further checks skipped: {} could not be read ({}), so the tree of links and \
             joints is not known; fix the problems above, then check again",
            if robot.dropped.len() == 1 {
                "an element"
            } else {
                "elements"
            },
            robot.dropped.join(", ")
        )));
    }
    let name = std::path::Path::new(origin)
        .file_name()
        .map_or_else(|| origin.to_string(), |f| f.to_string_lossy().into_owned());
    let (mut spec, mut outcome) = lower::spec(&robot, opts, &name, &mut problems);
    outcome.warnings = warnings;
    if let Some(why) = &outcome.skipped {
        return Err(fail(problems).noting(format!(
            "further checks skipped: {why}; fix the problems above, then check again"
        )));
    }
    if opts.on_ground && problems.is_empty() {
        on_ground::place(&mut spec, opts, &mut outcome, &mut problems);
    }
    if problems.is_empty() {
        return Ok((spec, outcome));
    }
    // the later stages on the salvaged spec: what they find of elements that already have a
    // problem follows from it (a placeholder, a repeated value) and is left out
    let mut errors = fail(problems);
    if let Err(later) = spec.validate(origin) {
        let later = in_urdf_terms(later, &spec, &outcome);
        let named: Vec<String> = errors
            .problems
            .iter()
            .filter_map(|p| element(&p.path))
            .collect();
        errors.problems.extend(
            later
                .problems
                .into_iter()
                .filter(|p| element(&p.path).is_none_or(|e| !named.contains(&e))),
        );
        errors.notes.extend(later.notes);
    }
    Err(errors)
}

/// The URDF element a problem's path names: `link "arm"` of `line 7: link "arm" (body[1])`.
fn element(path: &str) -> Option<String> {
    let at = path.find("link \"").or_else(|| path.find("joint \""))?;
    let rest = &path[at..];
    let open = rest.find('"')?;
    let close = rest[open + 1..].find('"')? + open + 1;
    Some(rest[..=close].to_string())
}
