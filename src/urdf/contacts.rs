//! `--contacts`: the links' `<collision>` elements as the spec's collision shapes, and a ground.
//!
//! - a `<collision>` sphere, box or cylinder becomes a `[[collision]]` shape of the same size on
//!   the body that carries its link, placed in that body's frame (a link merged by a fixed joint
//!   puts it where the link is, as for visuals):
//!   `T_body←shape = T_body←link ∘ origin_collision`;
//! - its name is the link's name made an identifier (`FR_foot`), with `_2`, `_3`, … for a
//!   link's further shapes (and for links whose identifiers collide), so that a foot merged
//!   into its calf is still `contact.FR_foot.*`;
//! - a cylinder touches the ground only (as a 12-sided prism; not other shapes): a note says so;
//! - a mesh is left out with a note: import never opens mesh files, and the bounding box of a
//!   rounded foot or a slanted leg is a poor contact surface (its corners touch first); the
//!   spec takes a sphere, capsule or box in its place;
//! - shapes of links welded to the world are left out with a note (the ground is the world's
//!   only contact surface), and so are shapes of zero size;
//! - a `[ground]` (the defaults: height 0, friction 0.8, stiffness 1e5 N/m, damping 1 s/m) is
//!   added when the spec has none.

use super::mass::{Iso, Placement};
use super::robot::{Geometry, Robot};
use crate::import::entries::collision_on;
use crate::import::names::Namer;
use crate::mechanics::ContactLaw;
use crate::spec::{BoxShape, GroundSpec, RoundShape, Spec, SphereShape};

/// How many links a note names before it says how many more.
const LISTED: usize = 6;

/// `'a' (line 3), 'b' (line 7)`, and past `LISTED` how many more.
fn listed(items: &[(String, usize)]) -> String {
    let mut s: Vec<String> = items
        .iter()
        .take(LISTED)
        .map(|(link, line)| format!("'{link}' (line {line})"))
        .collect();
    if items.len() > LISTED {
        s.push(format!("and {} more", items.len() - LISTED));
    }
    s.join(", ")
}

/// `1 <collision> mesh` / `3 <collision> meshes`.
fn count(n: usize, one: &str, many: &str) -> String {
    format!("{n} <collision> {}", if n == 1 { one } else { many })
}

/// What [`add`] tells besides the spec: notes, and where each shape came from (in the spec's
/// order).
#[derive(Debug, Default)]
pub(super) struct Added {
    pub notes: Vec<String>,
    pub sources: Vec<String>,
}

/// Adds the collision shapes of every link placed on a moving body (`host`, from the tree) to
/// `spec`, and a ground when it has none. `merged` lists each body's links, its own first.
pub(super) fn add(
    robot: &Robot,
    host: &[Option<Placement>],
    merged: &[(String, Vec<String>)],
    spec: &mut Spec,
) -> Added {
    let mut out = Added::default();
    let mut names = Namer::default();
    let (mut cylinders, mut meshes, mut welded, mut empty) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (l, link) in robot.links.iter().enumerate() {
        let Some(h) = host[l] else { continue };
        for shape in &link.collisions {
            let here = (link.name.clone(), shape.line);
            let (Some(b), Some(_)) = (h.body, h.cluster) else {
                welded.push(here);
                continue;
            };
            let mut c = collision_on(
                spec.body[b].name.clone(),
                h.frame
                    .then(&Iso::of(&shape.origin))
                    .origin(h.frame.is_identity().then_some(&shape.origin)),
            );
            let sizes_ok = match &shape.geometry {
                Geometry::Sphere(r) => {
                    c.sphere = Some(SphereShape { radius: *r });
                    *r > 0.0
                }
                Geometry::Box(size) => {
                    c.cuboid = Some(BoxShape { size: *size });
                    size.iter().all(|&x| x > 0.0)
                }
                Geometry::Cylinder([radius, length]) => {
                    c.cylinder = Some(RoundShape {
                        radius: *radius,
                        length: *length,
                    });
                    *radius > 0.0 && *length > 0.0
                }
                Geometry::Mesh(..) => {
                    meshes.push(here);
                    continue;
                }
            };
            if !sizes_ok {
                empty.push(here);
                continue;
            }
            if c.cylinder.is_some() {
                cylinders.push(here);
            }
            c.name = Some(names.name(&link.name));
            let merged = if merged[b].1.first() == Some(&link.name) {
                String::new()
            } else {
                format!(", merged into body {}", spec.body[b].name)
            };
            out.sources.push(format!(
                "URDF <collision> of link \"{}\" (line {}{merged})",
                link.name, shape.line
            ));
            spec.collision.push(c);
        }
    }
    if !cylinders.is_empty() {
        out.notes.push(format!(
            "{} ({}): cylinder shapes touch the ground (each rim as 12 points), not other shapes",
            count(cylinders.len(), "cylinder", "cylinders"),
            listed(&cylinders)
        ));
    }
    if !meshes.is_empty() {
        out.notes.push(format!(
            "{} left out ({}): triad has no mesh contact; give such a link a [[collision]] sphere, capsule or box in the spec",
            count(meshes.len(), "mesh", "meshes"),
            listed(&meshes)
        ));
    }
    if !welded.is_empty() {
        out.notes.push(format!(
            "{} of links welded to the world left out ({}): the ground is the world's only contact surface",
            count(welded.len(), "element", "elements"),
            listed(&welded)
        ));
    }
    if !empty.is_empty() {
        out.notes.push(format!(
            "{} of zero size left out ({})",
            count(empty.len(), "element", "elements"),
            listed(&empty)
        ));
    }
    if spec.collision.is_empty() {
        out.notes.push(
            "--contacts: no <collision> sphere, box or cylinder on a moving link, so nothing touches the ground; add [[collision]] shapes to the spec (triad import --contacts -o robot.toml)".into(),
        );
    }
    if spec.ground.is_none() {
        let law = ContactLaw::default();
        spec.ground = Some(GroundSpec {
            height: 0.0,
            friction: law.friction,
            stiffness: law.stiffness,
            damping: law.damping,
        });
    }
    out
}
