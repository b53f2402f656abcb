//! The MJCF document as typed data, `<default>` classes applied: compiler and option settings,
//! the bodies in MuJoCo's order (depth first, the world first) with their joints, geoms, sites
//! and inertials, keyframes, actuators, equalities and contact exclusions (read by `read`).

use super::frames::Angles;
use super::inertia::Solid;
use crate::import::frame::Iso;
use crate::math::{Mat3, Vec3};

/// `<compiler inertiafromgeom>`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum FromGeom {
    /// Never: a body without `<inertial>` is massless.
    Never,
    /// Always, even over an `<inertial>`.
    Always,
    /// For bodies without `<inertial>` (MuJoCo's default).
    Auto,
}

/// The `<compiler>` settings that change the model.
#[derive(Clone, Copy, Debug)]
pub(super) struct Compiler {
    pub angles: Angles,
    pub autolimits: bool,
    pub from_geom: FromGeom,
    pub boundmass: f64,
    pub boundinertia: f64,
    pub settotalmass: Option<f64>,
}

/// MuJoCo joint types.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum JointType {
    Hinge,
    Slide,
    Ball,
    Free,
}

/// `<joint>` (or `<freejoint>`), in the body frame; angles in radians.
#[derive(Clone, Debug)]
pub(super) struct Joint {
    pub name: Option<String>,
    pub at: String,
    pub kind: JointType,
    pub pos: Vec3,
    /// Unit axis.
    pub axis: Vec3,
    /// The stops, when limited.
    pub range: Option<[f64; 2]>,
    pub damping: f64,
    pub stiffness: f64,
    pub springref: f64,
    pub reference: f64,
    pub armature: f64,
    pub frictionloss: f64,
    /// The clamp of the summed actuator force on the joint (N·m or N), when limited.
    pub actuatorfrcrange: Option<[f64; 2]>,
}

/// What a geom is.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Shape {
    Solid(Solid),
    Plane,
    /// Mesh, height field, signed distance field: the type's name.
    Other(String),
}

/// `<geom>`, in the body frame.
#[derive(Clone, Debug)]
pub(super) struct Geom {
    pub name: Option<String>,
    pub at: String,
    pub shape: Shape,
    pub frame: Iso,
    pub mass: Option<f64>,
    pub density: f64,
    pub contype: u32,
    pub conaffinity: u32,
    /// The sliding friction (the first of `friction`).
    pub friction: f64,
    pub solref: [f64; 2],
    /// `solimp`'s dmax (the impedance at depth).
    pub dmax: f64,
}

/// `<site>`, in the body frame.
#[derive(Clone, Debug)]
pub(super) struct Site {
    pub name: Option<String>,
    pub frame: Iso,
}

/// `<inertial>`: mass, centre of mass and inertia about it in the body frame.
#[derive(Clone, Copy, Debug)]
pub(super) struct Inertial {
    pub mass: f64,
    pub com: Vec3,
    pub inertia: Mat3,
}

/// `<body>` (index 0: `<worldbody>`).
#[derive(Clone, Debug)]
pub(super) struct Body {
    pub name: Option<String>,
    pub at: String,
    pub parent: usize,
    /// The body frame in the parent's frame at `qpos0` (`<frame>`s composed).
    pub frame: Iso,
    pub joints: Vec<Joint>,
    pub geoms: Vec<Geom>,
    pub sites: Vec<Site>,
    pub inertial: Option<Inertial>,
}

/// `<key>`.
#[derive(Clone, Debug)]
pub(super) struct Key {
    pub name: String,
    pub at: String,
    pub qpos: Option<Vec<f64>>,
    pub qvel: Option<Vec<f64>>,
}

/// An actuator on a joint (`ctrlrange`, `forcerange`: given and limited).
#[derive(Clone, Debug)]
pub(super) struct Actuator {
    pub name: Option<String>,
    pub at: String,
    pub law: crate::mechanics::ActuatorLaw,
    pub joint: String,
    pub gear: f64,
    pub ctrlrange: Option<[f64; 2]>,
    pub forcerange: Option<[f64; 2]>,
}

/// `<equality>` elements.
#[derive(Clone, Debug)]
pub(super) enum Equality {
    /// `connect body1 body2 anchor` (anchor in body1's frame).
    Connect {
        at: String,
        body1: String,
        body2: Option<String>,
        anchor: Vec3,
    },
    /// `weld body1 body2`.
    Weld {
        at: String,
        body1: String,
        body2: Option<String>,
    },
    /// `joint joint1 joint2 polycoef`: `q₁ − q₁,₀ = Σₖ cₖ (q₂ − q₂,₀)ᵏ` (`qpos0`).
    Joint {
        at: String,
        joint1: String,
        joint2: Option<String>,
        polycoef: [f64; 5],
    },
}

/// The document.
#[derive(Clone, Debug)]
pub(super) struct Model {
    pub name: String,
    pub compiler: Compiler,
    pub gravity: Option<[f64; 3]>,
    pub timestep: Option<f64>,
    pub bodies: Vec<Body>,
    pub keys: Vec<Key>,
    pub actuators: Vec<Actuator>,
    pub equalities: Vec<Equality>,
    /// `<contact><exclude body1 body2>`.
    pub excludes: Vec<(String, String)>,
    /// What was ignored or is not modelled, for the notes.
    pub notes: Vec<String>,
}
