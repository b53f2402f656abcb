//! Contact in the replay: the ground plane of a spec's `[ground]`, its `[[collision]]` shapes
//! (drawn on demand as wireframes, and as the body itself for a body without `[[visual]]`),
//! and the scale of the contact-force arrows.
//!
//! The page draws the arrow of shape C from its contact point along `contact.C.f` (the force
//! on C's body), `|f| / scale` long. The contact point is computed in the page from the pose:
//! for a shape in the ground, the centre of pressure of its ground points (those of the
//! mechanics: a sphere's centre, a capsule's two ends, a box's corners, a cylinder's 24 rim
//! points, each lowered by its radius) weighted by their depths (the elastic law is linear),
//! projected onto the ground; for a shape just clear of it (within 1 % of the model's size:
//! a force met between frames), its lowest point (a face's centre, an edge's middle or a
//! corner, blended over about a degree of tilt) projected onto the ground; for a shape
//! farther off (a force from another shape), its point farthest along `−f`.

use super::recording::Recording;
use super::shape::{Geometry, Shape};
use crate::math::{rpy_to_matrix, Mat3, Vec3};
use crate::spec::Spec;

/// The ground plane `normal · x = height`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GroundPlane {
    /// Unit normal, against gravity (`+z` without gravity).
    pub normal: Vec3,
    /// Height along the normal, m.
    pub height: f64,
}

/// A collision shape and the body it is fixed on.
#[derive(Clone, Debug, PartialEq)]
pub struct CollisionShape {
    /// The shape's name (`Spec::collision_names`).
    pub name: String,
    /// Index of its body in the spec (and in [`super::Scene::bodies`]).
    pub body: usize,
    /// The shape in its body's frame.
    pub shape: Shape,
}

/// How long the force arrows are drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForceScale {
    /// Newtons per metre of arrow.
    pub newtons_per_metre: f64,
    /// The force the scale was chosen from, N.
    pub reference: f64,
    /// What that force is.
    pub basis: ForceBasis,
}

impl Default for ForceScale {
    fn default() -> Self {
        Self {
            newtons_per_metre: 1.0,
            reference: 1.0,
            basis: ForceBasis::Unit,
        }
    }
}

/// What the arrows' scale was chosen from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ForceBasis {
    /// The model's weight, `Σ m |g|`.
    Weight,
    /// The largest contact force of the recording (without gravity).
    Largest,
    /// Nothing (no weight, no force): 1 N.
    Unit,
}

/// The arrow of the reference force is about this share of the model's size.
const REFERENCE_SHARE: f64 = 0.5;

/// The ground's unit normal for `gravity`: against it, or `+z` without gravity (as the
/// mechanics places it).
#[must_use]
pub fn ground_normal(gravity: [f64; 3]) -> Vec3 {
    let g = Vec3::from(gravity);
    let n = g.norm();
    if n > 0.0 && n.is_finite() {
        // (+ 0: no negative zeros in the page)
        -g / n + Vec3::zeros()
    } else {
        Vec3::z()
    }
}

/// The ground plane of `spec`, if it has `[ground]`, at the height the recording's gaps tell
/// (the run may have set the parameter `ground.height`), with a warning when that is not the
/// spec's.
#[must_use]
pub fn ground(
    spec: &Spec,
    recording: &Recording,
    shapes: &[CollisionShape],
) -> (Option<GroundPlane>, Option<String>) {
    let Some(g) = spec.ground else {
        return (None, None);
    };
    let normal = ground_normal(spec.gravity);
    let mut plane = GroundPlane {
        normal,
        height: g.height,
    };
    let Some(h) = recorded_height(normal, recording, shapes) else {
        return (Some(plane), None);
    };
    let tol = 1e-9 * (1.0 + g.height.abs() + h.abs());
    if (h - g.height).abs() <= tol {
        return (Some(plane), None);
    }
    plane.height = h;
    let shown = (h * 1e9).round() / 1e9;
    let warning = format!(
        "the ground is drawn at height {shown} m, where the result's contact gaps put it \
         (the spec says {} m: a run with ground.height set?)",
        g.height
    );
    (Some(plane), Some(warning))
}

/// The points of a shape that touch the ground, in its frame, each with its radius, as the
/// mechanics places them (a cylinder: 12 points on each rim).
fn ground_points(g: &Geometry) -> Vec<(Vec3, f64)> {
    match *g {
        Geometry::Sphere(r) => vec![(Vec3::zeros(), r)],
        Geometry::Capsule { radius, length } => [-0.5, 0.5]
            .iter()
            .map(|s| (Vec3::new(0.0, 0.0, s * length), radius))
            .collect(),
        Geometry::Cuboid(d) => (0..8)
            .map(|k| {
                let s = |bit: usize| if k & bit == 0 { -0.5 } else { 0.5 };
                (Vec3::new(s(1) * d[0], s(2) * d[1], s(4) * d[2]), 0.0)
            })
            .collect(),
        Geometry::Cylinder { radius, length } => (0..24)
            .map(|k| {
                #[allow(clippy::cast_precision_loss)]
                let a = std::f64::consts::TAU * (k % 12) as f64 / 12.0;
                let z = if k < 12 { -0.5 } else { 0.5 } * length;
                (Vec3::new(radius * a.cos(), radius * a.sin(), z), 0.0)
            })
            .collect(),
        Geometry::Mesh { .. } => Vec::new(),
    }
}

/// The height along `normal` of the lowest point of `shape` on a body at `(r, rot)`, m.
fn lowest(normal: Vec3, shape: &Shape, r: Vec3, rot: &Mat3) -> Option<f64> {
    ground_points(&shape.geometry)
        .into_iter()
        .map(|(p, radius)| normal.dot(&(r + rot * (shape.xyz + shape.rot * p))) - radius)
        .reduce(f64::min)
}

/// The ground's height in the run, from the first recorded gap of every shape
/// (`n·lowest point − gap`), if the shapes agree on it.
fn recorded_height(normal: Vec3, recording: &Recording, shapes: &[CollisionShape]) -> Option<f64> {
    let heights: Vec<f64> = recording
        .contacts
        .iter()
        .filter_map(|t| {
            let gap = *t.gap.as_ref()?.first()?;
            let c = shapes.iter().find(|c| c.name == t.name)?;
            let body = recording.bodies.get(c.body)?;
            let low = lowest(normal, &c.shape, *body.r.first()?, body.rot.first()?)?;
            Some(low - gap).filter(|h| h.is_finite())
        })
        .collect();
    let (&first, rest) = heights.split_first()?;
    let tol = 1e-9 * (1.0 + first.abs());
    rest.iter()
        .all(|h| (h - first).abs() <= tol)
        .then_some(first)
}

/// The collision shapes of `spec` on its bodies, in the spec's order (a shape on a body the
/// spec does not have is left out).
#[must_use]
pub fn collision_shapes(spec: &Spec) -> Vec<CollisionShape> {
    spec.collision
        .iter()
        .zip(spec.collision_names())
        .filter_map(|(c, name)| {
            // (the spec's `CollisionSpec` is not exported: its fields are read here)
            let geometry = if let Some(s) = c.sphere {
                Geometry::Sphere(s.radius)
            } else if let Some(s) = c.capsule {
                Geometry::Capsule {
                    radius: s.radius,
                    length: s.length,
                }
            } else if let Some(b) = c.cuboid {
                Geometry::Cuboid(b.size)
            } else {
                let s = c.cylinder?;
                Geometry::Cylinder {
                    radius: s.radius,
                    length: s.length,
                }
            };
            Some(CollisionShape {
                name,
                body: spec.body.iter().position(|b| b.name == c.body)?,
                shape: Shape {
                    geometry,
                    xyz: Vec3::from(c.origin.xyz),
                    rot: rpy_to_matrix(&Vec3::from(c.origin.rpy)),
                    rgba: None,
                    default: false,
                    faceted: false,
                },
            })
        })
        .collect()
}

/// `x` rounded to the nearest of 1, 2, 5 × 10^k (in ratio).
fn nice(x: f64) -> f64 {
    let e = 10f64.powf(x.log10().floor());
    let m = x / e;
    let m = if m < 1.4 {
        1.0
    } else if m < 3.2 {
        2.0
    } else if m < 7.1 {
        5.0
    } else {
        10.0
    };
    m * e
}

/// The arrows' scale for `recording` of `spec` in a model of size `length` (m): the model's
/// weight (else, without gravity, the largest recorded contact force) is drawn about half the
/// model's size long, rounded to 1, 2 or 5 N/m times a power of ten.
#[must_use]
pub fn force_scale(spec: &Spec, recording: &Recording, length: f64) -> ForceScale {
    let g = Vec3::from(spec.gravity).norm();
    let weight: f64 = spec.body.iter().map(|b| b.mass.max(0.0)).sum::<f64>() * g;
    let largest = recording
        .contacts
        .iter()
        .flat_map(|c| c.f.iter().map(Vec3::norm))
        .filter(|f| f.is_finite())
        .fold(0.0, f64::max);
    let (reference, basis) = if weight > 0.0 && weight.is_finite() {
        (weight, ForceBasis::Weight)
    } else if largest > 0.0 {
        (largest, ForceBasis::Largest)
    } else {
        (1.0, ForceBasis::Unit)
    };
    ForceScale {
        newtons_per_metre: nice(reference / (REFERENCE_SHARE * length.max(1e-3))),
        reference,
        basis,
    }
}

#[cfg(test)]
mod tests {
    use super::super::recording::{BodyTrack, ContactTrack};
    use super::*;

    #[test]
    fn normal_against_gravity() {
        assert_eq!(ground_normal([0.0, 0.0, -9.81]), Vec3::z());
        assert_eq!(ground_normal([0.0, 0.0, 0.0]), Vec3::z());
        assert_eq!(ground_normal([3.0, 0.0, 0.0]), -Vec3::x());
    }

    /// A tilted box on a free body, with a ground at `height` and gravity `gravity`.
    fn tilted_box(height: f64, gravity: &str) -> Spec {
        let text = format!(
            r#"
            name = "Box"
            gravity = {gravity}
            [ground]
            height = {height}
            [[body]]
            name = "b"
            mass = 2.0
            inertia = [0.1, 0.1, 0.1]
            position = [0.1, 0.2, 1.0]
            orientation = [0.9238795325112867, 0.3826834323650898, 0.0, 0.0]
            [[collision]]
            body = "b"
            box = {{ size = [0.4, 0.2, 0.1] }}
            origin = {{ xyz = [0.0, 0.0, 0.05], rpy = [0.0, 0.3, 0.0] }}
            "#
        );
        Spec::from_str(&text, crate::spec::Format::Toml, "box.toml").unwrap()
    }

    #[test]
    fn the_ground_height_from_the_gaps() {
        let spec = tilted_box(0.0, "[0.0, 0.0, -9.81]");
        let shapes = collision_shapes(&spec);
        assert_eq!(shapes.len(), 1);
        assert_eq!(shapes[0].name, "b_1");
        assert_eq!(shapes[0].shape.geometry, Geometry::Cuboid([0.4, 0.2, 0.1]));
        // the body's pose and the shape's gap to a ground at 0.4, as the mechanics has them
        let r = Vec3::new(0.1, 0.2, 1.0);
        let rot = crate::math::quat_to_matrix(&[
            0.923_879_532_511_286_7,
            0.382_683_432_365_089_8,
            0.0,
            0.0,
        ]);
        let corners = ground_points(&shapes[0].shape.geometry);
        assert_eq!(corners.len(), 8);
        let low = corners
            .iter()
            .map(|(p, _)| (r + rot * (shapes[0].shape.xyz + shapes[0].shape.rot * p)).z)
            .fold(f64::INFINITY, f64::min);
        let recording = Recording {
            time: vec![0.0],
            bodies: vec![BodyTrack {
                name: "b".into(),
                r: vec![r],
                rot: vec![rot],
            }],
            contacts: vec![ContactTrack {
                name: "b_1".into(),
                shape: 0,
                f: vec![Vec3::zeros()],
                gap: Some(vec![low - 0.4]),
            }],
            ..Recording::default()
        };
        let (plane, warning) = ground(&spec, &recording, &shapes);
        let plane = plane.unwrap();
        assert!((plane.height - 0.4).abs() < 1e-12, "{plane:?}");
        assert!(warning.unwrap().contains("drawn at height 0.4 m"));
        // the spec's own height: no warning
        let spec = tilted_box(0.4, "[0.0, 0.0, -9.81]");
        let (plane, warning) = ground(&spec, &recording, &shapes);
        assert_eq!(plane.unwrap().height, 0.4);
        assert!(warning.is_none());
        // without gaps, the spec's height
        let mut without = recording.clone();
        without.contacts[0].gap = None;
        assert_eq!(ground(&spec, &without, &shapes).0.unwrap().height, 0.4);
    }

    #[test]
    fn the_scale_from_the_weight_or_the_largest_force() {
        let spec = tilted_box(0.0, "[0.0, 0.0, -9.81]");
        let mut recording = Recording {
            contacts: vec![ContactTrack {
                name: "b_1".into(),
                shape: 0,
                f: vec![Vec3::new(0.0, 0.0, 300.0), Vec3::repeat(f64::NAN)],
                gap: None,
            }],
            ..Recording::default()
        };
        // 2 kg: 19.62 N half of 1 m long, 39.24 N/m: 50
        let s = force_scale(&spec, &recording, 1.0);
        assert_eq!(s.basis, ForceBasis::Weight);
        assert_eq!(s.newtons_per_metre, 50.0);
        // without gravity, the largest force (NaN left out)
        let spec = tilted_box(0.0, "[0.0, 0.0, 0.0]");
        let s = force_scale(&spec, &recording, 1.0);
        assert_eq!(
            (s.basis, s.reference, s.newtons_per_metre),
            (ForceBasis::Largest, 300.0, 500.0)
        );
        recording.contacts.clear();
        assert_eq!(force_scale(&spec, &recording, 1.0).basis, ForceBasis::Unit);
    }

    #[test]
    fn nice_numbers() {
        assert_eq!(nice(9.81), 10.0);
        assert_eq!(nice(0.0042), 0.005);
        assert!((nice(260.0) - 200.0).abs() < 1e-9);
        assert_eq!(nice(1.0), 1.0);
    }
}
