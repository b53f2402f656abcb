//! Contact in the replay: the ground plane of a spec's `[ground]`, its `[[collision]]` shapes
//! (drawn on demand as wireframes, and as the body itself for a body without `[[visual]]`),
//! and the scale of the contact-force arrows.
//!
//! The page draws the arrow of shape C from its contact point along `contact.C.f` (the force
//! on C's body), `|f| / scale` long. The contact point is computed in the page from the pose:
//! for a shape on or in the ground, its lowest point along the ground's normal (a face's
//! centre, an edge's middle or a corner, blended over about a degree of tilt so that the
//! arrow does not jump between corners of a box lying flat) projected onto the ground; for a
//! shape clear of the ground (a force from another shape), its point farthest along `−f`.

use super::recording::Recording;
use super::shape::{Geometry, Shape};
use crate::math::{rpy_to_matrix, Vec3};
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

/// The ground plane of `spec`, if it has `[ground]`.
#[must_use]
pub fn ground(spec: &Spec) -> Option<GroundPlane> {
    spec.ground.map(|g| GroundPlane {
        normal: ground_normal(spec.gravity),
        height: g.height,
    })
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
    use super::*;

    #[test]
    fn normal_against_gravity() {
        assert_eq!(ground_normal([0.0, 0.0, -9.81]), Vec3::z());
        assert_eq!(ground_normal([0.0, 0.0, 0.0]), Vec3::z());
        assert_eq!(ground_normal([3.0, 0.0, 0.0]), -Vec3::x());
    }

    #[test]
    fn nice_numbers() {
        assert_eq!(nice(9.81), 10.0);
        assert_eq!(nice(0.0042), 0.005);
        assert!((nice(260.0) - 200.0).abs() < 1e-9);
        assert_eq!(nice(1.0), 1.0);
    }
}
