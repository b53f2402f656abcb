//! MJCF import (MuJoCo's XML; interface.md §1, §2 "MJCF"): a MuJoCo model becomes a model spec,
//! which every command then treats like a spec file (`triad check|simulate|build model.xml`),
//! and which `triad import` writes out as editable TOML.
//!
//! The files: `xml` (the element tree with file and line, `<include>` expanded), `defaults`
//! (`<default>` classes, `class`, `childclass`), `frames` (`<compiler angle eulerseq>` and the
//! orientation forms), `inertia` (geom mass properties), `model` (the typed document), `read`
//! with `reader`, `bodies` and `sections` (reading it, every problem with file, line and
//! element), `lower` (→ `Spec`: frames so that `joint.J.q` is MuJoCo's `qpos`, inertials,
//! sites), `actuators` with `actuator_law` (MuJoCo's actuator parameters → a motor, position or
//! velocity servo), `keyframe` (the initial state), `equality` (loop-closing joints),
//! `contacts` (geoms as collision shapes, the world plane as the ground), `write` (commented
//! TOML), `options`.
//!
//! Semantics chosen (docs/guide/bring-your-robot.md, "MJCF"):
//! - `hinge` → revolute, `slide` → prismatic, `ball` → spherical, `free`/`<freejoint>` → a free
//!   body (a floating base); a body without joints is merged into its parent (its frame a
//!   site); several joints in one body are chained through massless bodies;
//! - `ref` is exact (the joint frame is turned or shifted by it), so `q` = `qpos`; a hinge's or
//!   slide's `armature` and `frictionloss` are the joint's `armature` and Coulomb `friction`
//!   (a ball's `frictionloss` its friction cone); `springref`, a ball joint's armature and
//!   `<equality joint>` are imported with a note saying what is not reproduced;
//! - `<motor>`, `<position>`, `<velocity>` (and `<general>` equal to one of them) on a hinge or
//!   slide are `[[actuator]]`s with MuJoCo's law, gear and clamps: the input `actuator.A.ctrl`;
//!   a hinge's or slide's `actuatorfrcrange` (limited by `actuatorfrclimited`, or given with
//!   `autolimits`) is the joint's `actuatorfrcrange`, the clamp of its actuators' summed force;
//! - `<equality connect>` → a loop-closing spherical joint, `weld` → a loop-closing fixed joint,
//!   both at the bodies' places at `qpos0`;
//! - tendons, muscles, flex, composites and plugins are refused; lights, cameras, materials,
//!   textures, sensors and visual settings are ignored.

mod actuator_law;
mod actuators;
mod bodies;
mod body_inertials;
mod contacts;
mod defaults;
mod equality;
mod frames;
mod inertia;
mod joint_spec;
mod keyframe;
mod lower;
mod model;
mod options;
mod read;
mod reader;
mod sections;
mod write;
mod xml;

pub use lower::Outcome;
pub use options::ImportOptions;
pub use write::{in_mjcf_terms, to_toml};

use std::path::Path;

use crate::spec::{Spec, SpecErrors};

/// Reads the MJCF text `text` of the file `path` (includes are read relative to it) into a
/// spec. `path` prefixes every message and goes into the spec's description. The spec is not
/// validated here (`Spec::validate` does that).
///
/// # Errors
/// Every problem found, each with its file, line and element.
pub fn import(
    text: &str,
    path: &Path,
    opts: &ImportOptions,
) -> Result<(Spec, Outcome), SpecErrors> {
    let origin = path.to_string_lossy().into_owned();
    let fail = |problems| SpecErrors {
        origin: origin.clone(),
        problems,
        notes: Vec::new(),
    };
    let root = xml::read(text, path).map_err(fail)?;
    let model = read::model(&root).map_err(fail)?;
    let name = path
        .file_name()
        .map_or_else(|| origin.clone(), |f| f.to_string_lossy().into_owned());
    let mut problems = Vec::new();
    let lower::Lowered {
        mut spec,
        mut outcome,
        host,
        slots,
        joint_of,
    } = lower::spec(&model, &name, &mut problems);
    actuators::actuators(&model, &joint_of, &mut spec, &mut outcome, &mut problems);
    keyframe::initial_state(&model, opts, &slots, &mut spec, &mut problems);
    let world = lower::world_frames(&model);
    equality::equalities(
        &model,
        &joint_of,
        &host,
        &world,
        &mut spec,
        &mut outcome,
        &mut problems,
    );
    if !opts.no_contacts && problems.is_empty() {
        let (sources, notes) = contacts::add(&model, &host, &mut spec);
        outcome.collisions = sources;
        outcome.notes.extend(notes);
    }
    if problems.is_empty() {
        Ok((spec, outcome))
    } else {
        Err(fail(problems))
    }
}

#[cfg(test)]
mod actuator_tests;
#[cfg(test)]
mod tests;
