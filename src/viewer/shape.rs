//! A shape drawn on a body: its geometry and its placement in the body frame.

use crate::math::{Mat3, Vec3};

/// The geometry of a shape, in its own frame, m.
#[derive(Clone, Debug, PartialEq)]
pub enum Geometry {
    /// A box centred on the origin: full side lengths along x, y, z.
    Cuboid([f64; 3]),
    /// A cylinder along z centred on the origin.
    Cylinder {
        /// Radius.
        radius: f64,
        /// Length along z.
        length: f64,
    },
    /// A sphere centred on the origin.
    Sphere(f64),
    /// A capsule along z centred on the origin: a cylinder of `length` with half-sphere ends.
    Capsule {
        /// Radius.
        radius: f64,
        /// Length of the cylindrical part along z.
        length: f64,
    },
    /// Mesh `index` of [`super::Scene::meshes`], scaled along its x, y, z.
    Mesh {
        /// Index in [`super::Scene::meshes`].
        index: usize,
        /// Scale factors.
        scale: [f64; 3],
    },
}

/// A shape placed in a body frame (or the world frame).
#[derive(Clone, Debug, PartialEq)]
pub struct Shape {
    /// The geometry.
    pub geometry: Geometry,
    /// Origin of the shape frame, in the body frame, m.
    pub xyz: Vec3,
    /// Rotation body ← shape.
    pub rot: Mat3,
    /// Colour (red, green, blue, alpha in [0, 1]); `None`: the body's colour (or the mesh's own).
    pub rgba: Option<[f64; 4]>,
    /// True for a default shape drawn from the model's mass data and joints.
    pub default: bool,
    /// Drawn with coarse flat facets, so that a turn about an axis of symmetry shows (a
    /// collision shape standing in for the look of a body without `[[visual]]`).
    pub faceted: bool,
}
