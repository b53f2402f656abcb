//! `--on-ground`: the floating base starts where its lowest collision shape rests on the ground.
//!
//! A URDF places its base at the origin (or at its floating joint's origin), which for a legged
//! robot puts the feet inside a ground at height 0. Every shape hangs from the free base, so a
//! translation `δ n` of the base (`n` the ground normal, against gravity) changes every shape's
//! gap (`contact.C.gap`) by `δ`: with `δ = −min gap` the lowest shape touches (gap 0) and the
//! others are above. The gaps are the mechanics' own at the initial state (the joints' initial
//! values; a cylinder as its rims' points, as the contact sees it), so the FMU starts with the
//! lowest shape at gap 0 exactly (to round-off).

use super::lower::Outcome;
use super::options::{Base, ImportOptions};
use crate::mechanics::contact::ground_normal;
use crate::mechanics::{Model, State};
use crate::spec::{Problem, Spec};

/// Moves the floating base of `spec` so that its lowest collision shape rests on the ground,
/// and says so in `out` (a note, and the comment of the base's `position`). `--on-ground`
/// without a floating base or without `--contacts`, or with no collision shape, is a problem.
/// A spec that the mechanics cannot build is left as it is (its validation reports why).
pub(crate) fn place(
    spec: &mut Spec,
    opts: &ImportOptions,
    out: &mut Outcome,
    problems: &mut Vec<Problem>,
) {
    let base = spec
        .body
        .iter()
        .position(|b| b.position.is_some() && !spec.joint.iter().any(|j| j.child == b.name));
    if !opts.contacts {
        problems.push(Problem::new(
            "--on-ground",
            "rests the robot's collision shapes on the ground: it needs --contacts, which makes \
             the shapes and the ground",
        ));
    }
    let Some(base) = base else {
        let how = if opts.base == Base::Fixed {
            "drop --fixed-base"
        } else {
            "add --floating-base"
        };
        problems.push(Problem::new(
            "--on-ground",
            format!(
                "places a floating base, and this robot's base is welded to the world: {how} \
                 (or, for a welded robot, place the ground under it: [ground] height in the \
                 spec that `triad import` writes)"
            ),
        ));
        return;
    };
    if !opts.contacts {
        return;
    }
    if spec.collision.is_empty() {
        problems.push(Problem::new(
            "--on-ground",
            "the robot has no collision sphere, box or cylinder to rest on the ground (see the \
             note of --contacts)",
        ));
        return;
    }
    let Ok((def, settings)) = spec.lower() else {
        return;
    };
    let Ok(model) = Model::new(&def, settings) else {
        return;
    };
    let state = State::new(&model);
    let Some((lowest, gap)) = state
        .outputs()
        .contacts
        .iter()
        .enumerate()
        .map(|(k, c)| (k, c.gap))
        .min_by(|a, b| a.1.total_cmp(&b.1))
    else {
        return;
    };
    if !gap.is_finite() {
        return;
    }
    let n = ground_normal(&def.gravity);
    let b = &mut spec.body[base];
    let Some(position) = b.position.as_mut() else {
        return;
    };
    let before = *position;
    for (p, n) in position.iter_mut().zip(n.iter()) {
        *p -= gap * n;
    }
    let shape = &def.contact.shapes[lowest];
    let moved = if gap <= 0.0 { "raised" } else { "lowered" };
    let why = format!(
        "{moved} by {} m by --on-ground, so that the lowest collision shape at \
         the initial pose, '{}' on body '{}', rests on the ground (gap 0); the URDF puts the \
         base at [{}]",
        short(gap.abs()),
        shape.name,
        def.bodies[shape.body].name,
        list(&before)
    );
    let note = format!(
        "--on-ground: the floating base '{}' starts at position [{}], {why}",
        b.name,
        list(position)
    );
    out.placed = Some((b.name.clone(), why));
    out.notes.push(note);
}

/// A length to 0.1 µm, trailing zeros dropped.
fn short(x: f64) -> String {
    let s = format!("{x:.7}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// `x, y, z` in round-trip form.
fn list(v: &[f64; 3]) -> String {
    v.iter()
        .map(|x| format!("{x:?}"))
        .collect::<Vec<_>>()
        .join(", ")
}
