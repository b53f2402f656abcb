//! Geoms as collision shapes (unless `--no-contacts`), a world `plane` as the ground.
//!
//! - the first `plane` geom of `<worldbody>` is the `[ground]`: its height along the normal
//!   against gravity, its friction; a plane whose normal is not against gravity is left out
//!   with a note;
//! - without a ground, only the shapes in pairs are kept;
//! - a sphere, capsule, box or cylinder geom on a moving body becomes a `[[collision]]` on the
//!   body that carries it, when MuJoCo would let it touch the plane (`contype & conaffinity`
//!   either way); pairs of such shapes on different bodies that MuJoCo lets collide (the bit
//!   test, not parent and child, not `<exclude>`d) become `[[contact_pair]]`s; cylinders touch
//!   the ground only (a note names those that would touch other shapes); ellipsoids and meshes
//!   are left out with a note;
//! - friction: the larger of the geom's and the plane's sliding coefficient (MuJoCo's default
//!   mixing);
//! - MuJoCo's soft contact (`solref`, `solimp`) mapped to triad's law `f = k x (1 + d ẋ)` at
//!   rest, as `tests/python/quadruped_mujoco.py` derives: with the impedance `i = dmax` at
//!   depth and the contact's inverse weight `w ≈ 1/m` (m: the mass of the tree the shape
//!   moves with, MuJoCo's `body_invweight0` approximated), MuJoCo's resting force is
//!   `f = x / (w tc² ζ² (1 − i))` for `solref = (tc, ζ)`, `f = S x / (w (1 − i))` for
//!   `solref = (−S, −B)`, so `k = m / (tc² ζ² (1 − i))` or `S m / (1 − i)`: the same resting
//!   depth under the tree's weight. MuJoCo's damper `2 m / (tc (1 − i))` (`B m / (1 − i)`)
//!   is matched by Hunt–Crossley's at that depth under the tree's weight `m g`:
//!   `d = 2 / (tc (1 − i) g)` (`B / ((1 − i) g)`). Approximate: MuJoCo's contact weight is not
//!   exactly `1/m` (a 4.2 kg sphere at the defaults rests 0.20 mm deep here, 0.29 mm in MuJoCo).

use std::collections::HashSet;

use super::inertia::Solid;
use super::lower::Host;
use super::model::{Geom, Model, Shape};
use crate::import::entries::collision_on;
use crate::import::names::Namer;
use crate::math::Vec3;
use crate::mechanics::ContactLaw;
use crate::spec::{BoxShape, ContactPairSpec, GroundSpec, RoundShape, Spec, SphereShape};

/// True when MuJoCo lets geoms `a` and `b` collide by their bits.
fn bits(a: &Geom, b: &Geom) -> bool {
    (a.contype & b.conaffinity) != 0 || (b.contype & a.conaffinity) != 0
}

/// The triad stiffness (N/m) and Hunt–Crossley damping (s/m) of `g` on a tree of mass `m`
/// under gravity `g_abs`.
fn law(g: &Geom, m: f64, g_abs: f64) -> (f64, Option<f64>) {
    let i = g.dmax.clamp(1e-4, 0.9999);
    let [a, b] = g.solref;
    let (k, d) = if a > 0.0 {
        let zeta = b.max(1e-6);
        (
            m / (a * a * zeta * zeta * (1.0 - i)),
            2.0 / (a * (1.0 - i) * g_abs),
        )
    } else {
        (-a * m / (1.0 - i), -b / ((1.0 - i) * g_abs))
    };
    (k, (g_abs > 0.0).then_some(d))
}

/// Adds the ground, the collision shapes and their pairs to `spec`; returns the sources of the
/// shapes and the notes.
pub(super) fn add(m: &Model, host: &[Host], spec: &mut Spec) -> (Vec<String>, Vec<String>) {
    let mut notes = Vec::new();
    let mut sources = Vec::new();
    let gravity = Vec3::from(spec.gravity);
    let g_abs = gravity.norm();
    let up = if g_abs > 0.0 {
        -gravity / g_abs
    } else {
        Vec3::z()
    };
    let planes: Vec<&Geom> = m.bodies[0]
        .geoms
        .iter()
        .filter(|g| g.shape == Shape::Plane)
        .collect();
    let mut plane = None;
    for p in &planes {
        let normal = p.frame.r * Vec3::z();
        if plane.is_none() && normal.dot(&up) > 1.0 - 1e-9 {
            plane = Some(*p);
        } else {
            notes.push(format!(
                "{}: only one plane, with its normal against gravity, can be the ground: left out",
                p.at
            ));
        }
    }
    let others = m.bodies[0]
        .geoms
        .iter()
        .filter(|g| g.shape != Shape::Plane)
        .count();
    if others > 0 {
        notes.push(format!("{others} geom(s) of <worldbody> other than the ground plane left out: the ground is the world's only contact surface"));
    }
    if let Some(p) = plane {
        let law = ContactLaw::default();
        spec.ground = Some(GroundSpec {
            height: p.frame.p.dot(&up),
            friction: p.friction,
            stiffness: law.stiffness,
            damping: law.damping,
        });
    }
    // the mass of the tree of each spec body (tree joints come parent first)
    let mut root: Vec<usize> = (0..spec.body.len()).collect();
    for j in spec.joint.iter().filter(|j| !j.is_loop_closing()) {
        let (Some(c), Some(p)) = (
            spec.body.iter().position(|b| b.name == j.child),
            spec.body.iter().position(|b| b.name == j.parent),
        ) else {
            continue;
        };
        root[c] = root[p];
    }
    let tree_mass = |b: usize| -> f64 {
        (0..spec.body.len())
            .filter(|&k| root[k] == root[b])
            .map(|k| spec.body[k].mass)
            .sum()
    };
    let mut names = Namer::default();
    let mut shapes: Vec<(usize, usize, &Geom)> = Vec::new();
    let (mut skipped, mut cylinders_paired) = (Vec::new(), Vec::new());
    for (i, body) in m.bodies.iter().enumerate().skip(1) {
        let Some(b) = host[i].body else {
            if !body.geoms.is_empty() {
                notes.push(format!("the geoms of body '{}' (welded to the world) are left out: the ground is the world's only contact surface", body.name.as_deref().unwrap_or("")));
            }
            continue;
        };
        for g in &body.geoms {
            if g.contype == 0 && g.conaffinity == 0 {
                continue;
            }
            let touches_ground = plane.is_none_or(|p| bits(g, p));
            if !touches_ground {
                continue;
            }
            let mut c = collision_on(
                spec.body[b].name.clone(),
                host[i].place.then(&g.frame).origin_spec(),
            );
            match g.shape {
                Shape::Solid(Solid::Sphere(r)) => c.sphere = Some(SphereShape { radius: r }),
                Shape::Solid(Solid::Capsule(r, h)) => {
                    c.capsule = Some(RoundShape {
                        radius: r,
                        length: 2.0 * h,
                    })
                }
                Shape::Solid(Solid::Cylinder(r, h)) => {
                    c.cylinder = Some(RoundShape {
                        radius: r,
                        length: 2.0 * h,
                    })
                }
                Shape::Solid(Solid::Box(s)) => {
                    c.cuboid = Some(BoxShape {
                        size: [2.0 * s[0], 2.0 * s[1], 2.0 * s[2]],
                    })
                }
                _ => {
                    skipped.push(g.at.clone());
                    continue;
                }
            }
            let friction = plane.map_or(g.friction, |p| g.friction.max(p.friction));
            if spec.ground.is_none_or(|gr| gr.friction != friction) {
                c.friction = Some(friction);
            }
            let (k, d) = law(g, tree_mass(b), g_abs);
            c.stiffness = Some(k);
            c.damping = d;
            let n = g.name.clone().unwrap_or_else(|| spec.body[b].name.clone());
            c.name = Some(names.name(&n));
            sources.push(g.at.clone());
            spec.collision.push(c);
            shapes.push((i, b, g));
        }
    }
    if !skipped.is_empty() {
        notes.push(format!("{} geom(s) left out as collision shapes (ellipsoids, meshes, height fields: triad has spheres, capsules, boxes, cylinders): {}", skipped.len(), skipped.join(", ")));
    }
    let excluded: HashSet<(usize, usize)> = m
        .excludes
        .iter()
        .filter_map(|(a, b)| {
            let f = |n: &str| m.bodies.iter().position(|x| x.name.as_deref() == Some(n));
            Some((f(a)?, f(b)?))
        })
        .flat_map(|(a, b)| [(a, b), (b, a)])
        .collect();
    let names_all = spec.collision_names();
    for x in 0..shapes.len() {
        for y in x + 1..shapes.len() {
            let ((i, b, g), (k, c, h)) = (shapes[x], shapes[y]);
            let family = m.bodies[i].parent == k || m.bodies[k].parent == i;
            if b == c || family || excluded.contains(&(i, k)) || !bits(g, h) {
                continue;
            }
            if spec.collision[x].cylinder.is_some() || spec.collision[y].cylinder.is_some() {
                cylinders_paired.push(format!("{} / {}", names_all[x], names_all[y]));
                continue;
            }
            spec.contact_pair.push(ContactPairSpec {
                a: names_all[x].clone(),
                b: names_all[y].clone(),
            });
        }
    }
    // without a ground, a shape touches only the shapes of its pairs
    if plane.is_none() {
        let paired: HashSet<&str> = spec
            .contact_pair
            .iter()
            .flat_map(|p| [p.a.as_str(), p.b.as_str()])
            .collect();
        let keep: Vec<bool> = names_all
            .iter()
            .map(|n| paired.contains(n.as_str()))
            .collect();
        let mut k = keep.iter();
        spec.collision.retain(|_| *k.next().unwrap_or(&false));
        let mut k = keep.iter();
        sources.retain(|_| *k.next().unwrap_or(&false));
    }
    if !cylinders_paired.is_empty() {
        notes.push(format!(
            "cylinders touch the ground only: {} pair(s) MuJoCo would collide are left out ({})",
            cylinders_paired.len(),
            cylinders_paired.join(", ")
        ));
    }
    if !spec.collision.is_empty() {
        notes.push("contact stiffness and damping come from each geom's solref/solimp at the weight of its tree (see the MJCF chapter of the guide); contacts are not MuJoCo's soft constraints".into());
    }
    if g_abs == 0.0 && !spec.collision.is_empty() {
        notes.push("without gravity the contact damping is triad's default (MuJoCo's is matched under the tree's weight)".into());
    }
    (sources, notes)
}
