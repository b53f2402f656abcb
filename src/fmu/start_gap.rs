//! The warning an instance logs at `fmi2ExitInitializationMode` when collision shapes start
//! below the ground (the first `fmi2DoStep` then meets contact springs compressed by the whole
//! depth, and may return `fmi2Discard`).

use crate::sim::Simulation;

/// The message for the shapes below the ground at `sim`'s state, or `None`.
#[must_use]
pub fn below_ground(sim: &Simulation) -> Option<String> {
    let below = sim.below_ground();
    let deepest = below.first()?.depth;
    let def = sim.model().def();
    let named: Vec<String> = below
        .iter()
        .take(5)
        .map(|b| {
            let s = &def.contact.shapes[b.shape];
            format!(
                "'{}' on body '{}' by {:.3e} m",
                s.name, def.bodies[s.body].name, b.depth
            )
        })
        .collect();
    let more = below.len().saturating_sub(named.len());
    Some(format!(
        "{} collision shape{} start{} below the ground: {}{}; the first step meets contact \
         forces of stiffness × depth and may be discarded. Lower the parameter ground.height \
         by at least {deepest:.3e} m, or start the model higher (the floating base's initial \
         position in the spec, `triad import --on-ground` for a URDF)",
        below.len(),
        if below.len() == 1 { "" } else { "s" },
        if below.len() == 1 { "s" } else { "" },
        named.join(", "),
        if more > 0 {
            format!(" and {more} more")
        } else {
            String::new()
        }
    ))
}
