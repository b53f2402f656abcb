//! The shapes drawn for a body without `[[visual]]` entries, from the model itself: a capsule
//! from the body's origin (its joint) to each of its child joints, loop joints and sites, a
//! ball at its origin, and the box with the body's mass and inertia about its centre of mass
//! (sides `a² = 6 (I₂ + I₃ − I₁) / m` along the principal axes), so that a spin about any axis
//! shows. The box's sides are kept between 2.5 capsule radii and twice the body's reach (its
//! farthest joint, site or centre of mass from its origin): some URDFs carry placeholder
//! inertias much larger than the link. A body with collision shapes is drawn with those
//! instead of its box.

use crate::math::{Mat3, Vec3};
use crate::spec::Spec;

use super::recording::Recording;
use super::shape::{Geometry, Shape};

/// Capsule radius as a share of the model's size.
const CAPSULE_SHARE: f64 = 0.02;

/// The model's size, m (see [`super::Scene::length`]).
pub(super) fn model_length(spec: &Spec, recording: &Recording) -> f64 {
    let mut lo = Vec3::repeat(f64::INFINITY);
    let mut hi = Vec3::repeat(f64::NEG_INFINITY);
    let mut add = |p: Vec3| {
        lo = lo.inf(&p);
        hi = hi.sup(&p);
    };
    for (b, track) in recording.bodies.iter().enumerate() {
        track.r.iter().for_each(|&r| add(r));
        let (Some(&r), Some(&rot)) = (track.r.first(), track.rot.first()) else {
            continue;
        };
        if let Some(body) = spec.body.get(b) {
            add(r + rot * Vec3::from(body.com));
        }
        for j in spec.joint.iter().filter(|j| j.parent == track.name) {
            add(r + rot * Vec3::from(j.origin.xyz));
        }
        for s in spec.site.iter().filter(|s| s.body == track.name) {
            add(r + rot * Vec3::from(s.origin.xyz));
        }
    }
    for j in spec.joint.iter().filter(|j| j.parent == "world") {
        add(Vec3::from(j.origin.xyz));
    }
    let diagonal = (hi - lo).norm();
    if diagonal.is_finite() && diagonal > 0.1 {
        return diagonal;
    }
    // a single free body: its own box sets the size
    spec.body
        .iter()
        .filter_map(|b| inertia_box(b.mass, &b.inertia.matrix()).map(|(s, _)| s.max() * 1.5))
        .fold(0.1, f64::max)
}

/// Sides (full lengths along the principal axes, m) and axes (columns, a rotation) of the box
/// with mass `m` and inertia `inertia` about its centre; `None` without mass.
fn inertia_box(m: f64, inertia: &Mat3) -> Option<(Vec3, Mat3)> {
    if m.is_nan() || m <= 0.0 {
        return None;
    }
    let sym = (inertia + inertia.transpose()) * 0.5;
    let eig = sym.symmetric_eigen();
    let i = eig.eigenvalues;
    let side = |a: usize, b: usize, c: usize| (6.0 * (i[b] + i[c] - i[a]) / m).max(0.0).sqrt();
    let sides = Vec3::new(side(0, 1, 2), side(1, 2, 0), side(2, 0, 1));
    let mut axes = eig.eigenvectors;
    if axes.determinant() < 0.0 {
        axes.column_mut(2).neg_mut();
    }
    sides.iter().all(|s| s.is_finite()).then_some((sides, axes))
}

/// A capsule from `a` to `b` (body frame) of radius `radius`.
fn capsule(a: Vec3, b: Vec3, radius: f64) -> Option<Shape> {
    let d = b - a;
    let length = d.norm();
    if length.is_nan() || length <= 1e-9 {
        return None;
    }
    // rotation taking z to d
    let z = d / length;
    let helper = if z.x.abs() < 0.9 {
        Vec3::x()
    } else {
        Vec3::y()
    };
    let x = helper.cross(&z).normalize();
    let y = z.cross(&x);
    Some(Shape {
        geometry: Geometry::Capsule { radius, length },
        xyz: (a + b) * 0.5,
        rot: Mat3::from_columns(&[x, y, z]),
        rgba: None,
        default: true,
        faceted: false,
    })
}

/// The default shapes of body `b` of `spec` in a model of size `length`; `inertia`: with the
/// box of its mass and inertia (a body with collision shapes is drawn with those instead).
pub(super) fn shapes(spec: &Spec, b: usize, length: f64, inertia: bool) -> Vec<Shape> {
    let body = &spec.body[b];
    let radius = (CAPSULE_SHARE * length).max(1e-3);
    let mut points: Vec<Vec3> = spec
        .joint
        .iter()
        .filter(|j| j.parent == body.name)
        .map(|j| Vec3::from(j.origin.xyz))
        .collect();
    points.extend(
        spec.joint
            .iter()
            .filter(|j| j.child == body.name)
            .filter_map(|j| j.child_origin.map(|o| Vec3::from(o.xyz))),
    );
    points.extend(
        spec.site
            .iter()
            .filter(|s| s.body == body.name)
            .map(|s| Vec3::from(s.origin.xyz)),
    );
    let com = Vec3::from(body.com);
    if points.is_empty() {
        points.push(com);
    }
    let mut out: Vec<Shape> = points
        .iter()
        .filter_map(|&p| capsule(Vec3::zeros(), p, radius))
        .collect();
    out.push(Shape {
        geometry: Geometry::Sphere(radius * 1.6),
        xyz: Vec3::zeros(),
        rot: Mat3::identity(),
        rgba: None,
        default: true,
        faceted: false,
    });
    // a body's joints and sites bound its box (some URDFs carry placeholder inertias far
    // larger than the link)
    let span = points.iter().map(Vec3::norm).fold(com.norm(), f64::max);
    let cap = if spec.joint.iter().any(|j| j.child == body.name) || span > 0.0 {
        (2.0 * span).max(4.0 * radius)
    } else {
        f64::INFINITY
    };
    if !inertia {
        return out;
    }
    if let Some((sides, axes)) = inertia_box(body.mass, &body.inertia.matrix()) {
        let sides = sides.map(|s| s.clamp(2.5 * radius, cap.max(2.5 * radius)));
        out.push(Shape {
            geometry: Geometry::Cuboid([sides.x, sides.y, sides.z]),
            xyz: com,
            rot: axes,
            rgba: None,
            default: true,
            faceted: false,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_of_a_box() {
        // a 2 × 1 × 0.5 box of 3 kg
        let (a, b, c, m) = (2.0, 1.0, 0.5, 3.0);
        let i = Mat3::from_diagonal(&Vec3::new(b * b + c * c, a * a + c * c, a * a + b * b))
            * (m / 12.0);
        let (sides, axes) = inertia_box(m, &i).unwrap();
        let mut got: Vec<f64> = sides.iter().copied().collect();
        got.sort_by(f64::total_cmp);
        for (g, w) in got.iter().zip([0.5, 1.0, 2.0]) {
            assert!((g - w).abs() < 1e-12, "{got:?}");
        }
        assert!((axes.determinant() - 1.0).abs() < 1e-12);
        assert!(inertia_box(0.0, &i).is_none());
    }

    #[test]
    fn capsule_points_from_a_to_b() {
        let s = capsule(Vec3::zeros(), Vec3::new(0.0, 0.0, -1.0), 0.1).unwrap();
        assert!((s.xyz - Vec3::new(0.0, 0.0, -0.5)).norm() < 1e-15);
        assert!((s.rot * Vec3::z() - Vec3::new(0.0, 0.0, -1.0)).norm() < 1e-15);
        assert!(capsule(Vec3::zeros(), Vec3::zeros(), 0.1).is_none());
    }
}
