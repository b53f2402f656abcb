//! The warning of `check`, `build` and `simulate` for collision shapes that start below the
//! ground: which shapes, on which bodies, how deep, and what moves them out (`[ground] height`,
//! the initial `position` of the free body they hang from, `--on-ground` for a URDF).
//!
//! A warning, not a problem: a model may start in contact on purpose (feet pressed in by their
//! static load `m g / k`, a state saved from a run), and the FMU accepts it. What it does is
//! said: the contact springs push with `k · depth` at the first step, which a deep start turns
//! into a step that fails.

use triad::mechanics::ModelDef;
use triad::sim::Simulation;
use triad::urdf::ImportOptions;

/// The warning for the shapes below the ground at the simulation's current (initial) state, or
/// `None` when every shape is on or above it. `urdf`: the import options when MODEL is a URDF
/// (the advice then names `--on-ground` and `triad import`).
pub fn below_ground_warning(sim: &Simulation, urdf: Option<&ImportOptions>) -> Option<String> {
    let below = sim.below_ground();
    let deepest = below.first()?.depth;
    let def = sim.model().def();
    let shapes = &def.contact.shapes;
    let height = def.contact.ground.map_or(0.0, |g| g.height);
    let mut text = format!(
        "warning: {} start{} below the ground (gap < 0 at the initial state; deepest {} m): \
         at the first step the contact springs push {} out with a force of stiffness × depth, \
         and a step that cannot resolve that fails (fmi2Discard in an FMU). Deepest first:",
        count(below.len()),
        if below.len() == 1 { "s" } else { "" },
        metres(deepest),
        if below.len() == 1 { "it" } else { "them" },
    );
    for b in &below {
        let s = &shapes[b.shape];
        text.push_str(&format!(
            "\n  '{}' on body '{}': {} m below",
            s.name,
            def.bodies[s.body].name,
            metres(b.depth)
        ));
    }
    // per free root (a floating base or a loose body), the depth of its deepest shape
    let mut free: Vec<(usize, f64)> = Vec::new();
    let mut welded = false;
    for b in &below {
        match root(def, shapes[b.shape].body) {
            Some(r) => match free.iter_mut().find(|(f, _)| *f == r) {
                Some(entry) => entry.1 = entry.1.max(b.depth),
                None => free.push((r, b.depth)),
            },
            None => welded = true,
        }
    }
    let mut fixes = Vec::new();
    if urdf.is_some_and(|o| !o.on_ground) && !free.is_empty() {
        fixes.push(
            "import with --on-ground (the floating base placed so that its lowest shape rests \
             on the ground)"
                .to_string(),
        );
    }
    let mut edits = vec![format!(
        "lower [ground] height by at least {} m (to {} m or below)",
        metres(deepest),
        metres_signed(height - deepest)
    )];
    for (r, depth) in &free {
        edits.push(format!(
            "raise the initial `position` of free body '{}' by {} m (against gravity)",
            def.bodies[*r].name,
            metres(*depth)
        ));
    }
    if welded {
        edits.push(
            "choose the joints' initial `q` so that the shapes of bodies welded to the world \
             clear the ground"
                .to_string(),
        );
    }
    let edits = edits.join("; or ");
    if urdf.is_some() {
        fixes.push(format!("in the spec that `triad import` writes, {edits}"));
    } else {
        fixes.push(edits);
    }
    text.push_str(&format!(
        "\n  To start on the ground: {}",
        fixes.join("; or ")
    ));
    Some(text)
}

/// The free body at the root of `body`'s tree, or `None` for a tree welded to the world.
fn root(def: &ModelDef, body: usize) -> Option<usize> {
    let mut b = body;
    // a tree has at most as many joints as bodies: the walk ends
    for _ in 0..=def.bodies.len() {
        match def.joints.iter().find(|j| !j.loop_closing && j.child == b) {
            None => return Some(b),
            Some(j) => match j.parent {
                None => return None,
                Some(p) => b = p,
            },
        }
    }
    None
}

/// "1 collision shape", "3 collision shapes".
fn count(n: usize) -> String {
    format!("{n} collision shape{}", if n == 1 { "" } else { "s" })
}

/// A positive length for a message: 4 decimals above a millimetre (trailing zeros dropped),
/// else 3 significant digits.
fn metres(x: f64) -> String {
    if x >= 1e-3 {
        let s = format!("{x:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{x:.2e}")
    }
}

/// [`metres`] for a length of either sign.
fn metres_signed(x: f64) -> String {
    if x < 0.0 {
        format!("-{}", metres(-x))
    } else if x == 0.0 {
        "0".into()
    } else {
        metres(x)
    }
}

/// The warning for `sim` ([`below_ground_warning`]) of a model read as `urdf` asks.
pub fn for_model(
    sim: &Simulation,
    model: &str,
    urdf: &super::import_args::ImportArgs,
) -> Option<String> {
    let opts = super::load::is_urdf(std::path::Path::new(model)).then(|| urdf.options());
    below_ground_warning(sim, opts.as_ref())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lengths() {
        assert_eq!(metres(0.1), "0.1");
        assert_eq!(metres(0.62832), "0.6283");
        assert_eq!(metres(2.0), "2");
        assert_eq!(metres(2e-6), "2.00e-6");
        assert_eq!(metres_signed(-0.25), "-0.25");
        assert_eq!(metres_signed(0.0), "0");
    }
}
