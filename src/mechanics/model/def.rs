//! Plain description of a multibody system: what `Model::new` consumes.
//!
//! Everything here is in SI units. A body's *frame* is the user's frame (URDF link frame); its
//! origin need not be the centre of mass. The world frame is fixed; gravity is given in it.

use crate::math::{Mat3, Vec3};

/// Index of a body in [`ModelDef::bodies`].
pub type BodyIndex = usize;

/// A rigid body.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyDef {
    /// Identifier, unique among bodies.
    pub name: String,
    /// Mass, kg, > 0.
    pub mass: f64,
    /// Centre of mass in the body frame, m.
    pub com: Vec3,
    /// Inertia tensor about the centre of mass in body axes, kg·m² (symmetric positive definite,
    /// principal moments satisfying the triangle inequalities).
    pub inertia: Mat3,
}

/// The lower kinematic pairs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum JointType {
    /// 1 rotation about `axis`; q = `[angle]`.
    Revolute,
    /// 1 translation along `axis`; q = `[slide]`.
    Prismatic,
    /// Translation along and rotation about `axis`; q = `[slide, angle]`.
    Cylindrical,
    /// Rotations about `axis` (fixed in the parent) then `axis2` (fixed in the child); q = `[α, β]`.
    Universal,
    /// 3 rotations; coordinates are a quaternion (w, x, y, z) and a relative angular velocity.
    Spherical,
    /// Motion in the plane normal to `axis`; q = `[x, y, angle]` in the joint frame.
    Planar,
    /// No relative motion.
    Fixed,
}

impl JointType {
    /// Number of scalar joint coordinates q (spherical: 4, the quaternion).
    #[must_use]
    pub fn nq(self) -> usize {
        match self {
            Self::Revolute | Self::Prismatic => 1,
            Self::Cylindrical | Self::Universal => 2,
            Self::Spherical => 4,
            Self::Planar => 3,
            Self::Fixed => 0,
        }
    }

    /// Number of degrees of freedom (= number of rates qd).
    #[must_use]
    pub fn dof(self) -> usize {
        match self {
            Self::Revolute | Self::Prismatic => 1,
            Self::Cylindrical | Self::Universal => 2,
            Self::Spherical | Self::Planar => 3,
            Self::Fixed => 0,
        }
    }

    /// Lower-case name as written in a spec.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Revolute => "revolute",
            Self::Prismatic => "prismatic",
            Self::Cylindrical => "cylindrical",
            Self::Universal => "universal",
            Self::Spherical => "spherical",
            Self::Planar => "planar",
            Self::Fixed => "fixed",
        }
    }
}

/// A rigid placement: rotation then translation, `x_parent = rotation · x_local + translation`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Origin of the local frame in the parent frame, m.
    pub translation: Vec3,
    /// Rotation parent ← local (columns are the local axes in parent coordinates).
    pub rotation: Mat3,
}

impl Frame {
    /// The identity placement.
    #[must_use]
    pub fn identity() -> Self {
        Self {
            translation: Vec3::zeros(),
            rotation: Mat3::identity(),
        }
    }
}

impl Default for Frame {
    fn default() -> Self {
        Self::identity()
    }
}

/// Initial joint state of a tree joint (ignored for loop-closing joints, whose state follows
/// from the tree).
#[derive(Clone, Debug, PartialEq)]
pub enum JointInitial {
    /// Coordinates and rates in the order of [`JointType::nq`] / [`JointType::dof`]
    /// (rad, m, rad/s, m/s). Empty vectors mean zeros.
    Coords {
        /// Joint coordinates.
        q: Vec<f64>,
        /// Joint rates.
        qd: Vec<f64>,
    },
    /// Spherical joints: child frame relative to the joint frame as a unit quaternion
    /// `[w, x, y, z]`, and the relative angular velocity in the child frame, rad/s.
    Spherical {
        /// Relative orientation.
        quat: [f64; 4],
        /// Relative angular velocity, child frame.
        w: Vec3,
    },
}

impl Default for JointInitial {
    fn default() -> Self {
        Self::Coords {
            q: Vec::new(),
            qd: Vec::new(),
        }
    }
}

/// A joint between a parent (a body or the world) and a child body.
///
/// Frames follow URDF: the joint frame is placed in the parent frame by `parent_frame`; at
/// q = 0 the child's joint frame (`child_frame`, given in the child body frame) coincides with
/// it. For tree joints `child_frame` is the identity (the child body frame *is* the joint frame
/// at q = 0).
#[derive(Clone, Debug, PartialEq)]
pub struct JointDef {
    /// Identifier, unique among joints.
    pub name: String,
    /// Pair type.
    pub kind: JointType,
    /// Parent body, `None` for the world.
    pub parent: Option<BodyIndex>,
    /// Child body.
    pub child: BodyIndex,
    /// Joint frame in the parent body frame (or the world frame).
    pub parent_frame: Frame,
    /// Joint frame in the child body frame.
    pub child_frame: Frame,
    /// Unit axis in the joint frame: rotation/slide axis, or the plane normal (planar).
    pub axis: Vec3,
    /// Second unit axis of a universal joint, in the joint frame, perpendicular to `axis`.
    pub axis2: Vec3,
    /// Whether the joint carries actuator inputs (not for planar or fixed joints).
    pub actuated: bool,
    /// Viscous damping on each coordinate, N·m·s/rad or N·s/m (≥ 0; tunable at run time).
    pub damping: f64,
    /// Linear stiffness about q = 0 on each coordinate, N·m/rad or N/m (≥ 0; tunable).
    pub stiffness: f64,
    /// Rotor inertia in joint space on each coordinate, kg·m² or kg (≥ 0): adds `a q̇²/2` of
    /// kinetic energy per coordinate, as MuJoCo's `armature` and Pinocchio's `model.armature`
    /// (not for spherical or fixed joints).
    pub armature: f64,
    /// Coulomb friction on each coordinate, N·m or N (≥ 0): a bristle that sticks below
    /// breakaway (`model::joint_friction`), its loss counted in the work (not for spherical,
    /// fixed or loop-closing joints).
    pub friction: f64,
    /// Position stops and actuator effort limit (revolute and prismatic joints).
    pub limits: JointLimits,
    /// True for a joint that closes a kinematic loop (its child already has a tree parent).
    pub loop_closing: bool,
    /// Initial coordinates and rates (tree joints only).
    pub initial: JointInitial,
}

/// Default stiffness of a joint stop, N·m/rad or N/m.
pub const STOP_STIFFNESS: f64 = 1.0e4;

/// Limits of a revolute or prismatic joint's coordinate (rad or m) and actuator (N·m or N).
/// The stops are one-sided springs with a Hunt–Crossley damper beyond each limit
/// (`model::stops`); the actuator input is clamped to `±effort`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointLimits {
    /// Lower position limit (−∞: none).
    pub lower: f64,
    /// Upper position limit (+∞: none).
    pub upper: f64,
    /// Largest actuator input magnitude (+∞: none).
    pub effort: f64,
    /// Stop stiffness, N·m/rad or N/m (> 0).
    pub stop_stiffness: f64,
    /// Stop damping (Hunt–Crossley: force `c·penetration·rate`), N·m·s/rad² or N·s/m² (≥ 0).
    pub stop_damping: f64,
    /// The sum of the generalised forces of the `[[actuator]]`s driving the coordinate is
    /// clamped to `[lo, hi]`, N·m or N (MuJoCo's joint `actuatorfrcrange`; none: unclamped).
    /// The joint's own input (`joint.J.tau`, `joint.J.f`) is not part of that sum.
    pub actuator_force: Option<[f64; 2]>,
}

impl Default for JointLimits {
    fn default() -> Self {
        Self {
            lower: f64::NEG_INFINITY,
            upper: f64::INFINITY,
            effort: f64::INFINITY,
            stop_stiffness: STOP_STIFFNESS,
            stop_damping: 0.0,
            actuator_force: None,
        }
    }
}

impl JointLimits {
    /// True when a position limit is set.
    #[must_use]
    pub fn has_stops(&self) -> bool {
        self.lower.is_finite() || self.upper.is_finite()
    }
}

/// Declared body loads: inputs applied to `body`.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyLoadDef {
    /// Loaded body.
    pub body: BodyIndex,
    /// Adds a world-frame torque input (3 components), N·m.
    pub torque: bool,
    /// Adds a world-frame force input at the centre of mass (3 components), N.
    pub force: bool,
}

/// Initial state of a body that no joint attaches to anything (a free body).
#[derive(Clone, Debug, PartialEq)]
pub struct FreeBodyInitial {
    /// The free body.
    pub body: BodyIndex,
    /// Body frame origin, world frame, m.
    pub position: Vec3,
    /// Rotation world ← body.
    pub orientation: Mat3,
    /// Velocity of the body frame origin, world frame, m/s.
    pub velocity: Vec3,
    /// Angular velocity, world frame, rad/s.
    pub angular_velocity: Vec3,
}

/// A site: a named frame fixed on a body, whose pose and twist are outputs.
#[derive(Clone, Debug, PartialEq)]
pub struct SiteDef {
    /// Identifier, unique among sites.
    pub name: String,
    /// The body it is fixed on.
    pub body: BodyIndex,
    /// The site frame in the body frame.
    pub frame: Frame,
}

/// Settings of the time integrator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolverSettings {
    /// Largest internal step, s (> 0).
    pub max_step: f64,
    /// 2: energy–momentum midpoint scheme; 4: a symmetric composition of it.
    pub order: u8,
    /// Stages of the order-4 composition: 3 (the triple jump, default) or 5 (Suzuki's, whose
    /// error is about 1/64 of the triple jump's at the same step); unused at order 2.
    pub stages: u8,
    /// Newton tolerance on the scaled update/residual (default 1e-10, the level below which
    /// conservation is at round-off, theory.md §6 item 8).
    pub tolerance: f64,
    /// Newton iteration limit per step (default 20).
    pub max_iterations: usize,
    /// Most internal sub-steps one communication step may take (default 100 000); a step that
    /// needs more stops there and reports how far it got. Not used by the step itself.
    pub max_substeps: u32,
    /// Relative tolerance of the error-controlled internal step (1); 0 (default): fixed steps
    /// of at most `max_step`. See `crate::mechanics::run::control`.
    pub rtol: f64,
    /// Absolute tolerance of the error-controlled internal step (1), added to `rtol` times the
    /// size of each body's coordinates.
    pub atol: f64,
    /// Floor of the error-controlled internal step, s (default 1e-8): a step the error
    /// estimate wants shorter is taken at this size and accepted.
    pub min_step: f64,
}

impl Default for SolverSettings {
    fn default() -> Self {
        Self {
            max_step: 1e-3,
            order: 2,
            tolerance: 1e-10,
            max_iterations: 20,
            max_substeps: 100_000,
            stages: 3,
            rtol: 0.0,
            atol: 0.0,
            min_step: 1e-8,
        }
    }
}

/// A complete multibody system, as lowered from a spec.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelDef {
    /// Gravity, world frame, m/s².
    pub gravity: Vec3,
    /// Bodies.
    pub bodies: Vec<BodyDef>,
    /// Joints; tree joints first in any order, loop-closing joints flagged.
    pub joints: Vec<JointDef>,
    /// Declared body loads.
    pub loads: Vec<BodyLoadDef>,
    /// Initial states of free bodies (those with no joint).
    pub free_bodies: Vec<FreeBodyInitial>,
    /// Sites (outputs only; they carry no mass and change no motion).
    pub sites: Vec<SiteDef>,
    /// The ground, collision shapes and the pairs of shapes that touch (none by default).
    pub contact: ContactDef,
    /// Joint couplings `q_b = ratio · q_a + offset` (none by default).
    pub couplings: Vec<CouplingDef>,
    /// Joint actuators: one control input each, after the joint and body inputs.
    pub actuators: Vec<ActuatorDef>,
}

/// The law of a joint actuator: the actuator force `F` from the control `u` and the actuator
/// length `L = gear·q` and rate `L̇ = gear·q̇` (MuJoCo's motor and servos).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ActuatorLaw {
    /// `F = u`.
    Motor,
    /// A position servo: `F = kp (u − L) − kv L̇` (kp ≥ 0 in N·m/rad or N/m per unit of gear,
    /// kv ≥ 0 in N·m·s/rad or N·s/m).
    Position {
        /// Position gain.
        kp: f64,
        /// Damping gain.
        kv: f64,
    },
    /// A velocity servo: `F = kv (u − L̇)` (kv ≥ 0, N·m·s/rad or N·s/m).
    Velocity {
        /// Velocity gain.
        kv: f64,
    },
}

impl ActuatorLaw {
    /// The gains `[kp, kv]` (N·m/rad or N/m, N·m·s/rad or N·s/m per unit of gear): 0 where
    /// the law has none (a motor has neither, a velocity servo no `kp`).
    #[must_use]
    pub fn gains(&self) -> [f64; 2] {
        match *self {
            Self::Motor => [0.0, 0.0],
            Self::Position { kp, kv } => [kp, kv],
            Self::Velocity { kv } => [0.0, kv],
        }
    }

    /// The same law with the gains `[kp, kv]` (those it has no use for ignored).
    #[must_use]
    pub fn with_gains(self, [kp, kv]: [f64; 2]) -> Self {
        match self {
            Self::Motor => Self::Motor,
            Self::Position { .. } => Self::Position { kp, kv },
            Self::Velocity { .. } => Self::Velocity { kv },
        }
    }
}

/// A joint actuator: a control input acting on the coordinate of a revolute or prismatic tree
/// joint through a gear; the joint receives the generalised force `gear · F`
/// (`model::joint_actuator`).
#[derive(Clone, Debug, PartialEq)]
pub struct ActuatorDef {
    /// Identifier, unique among actuators.
    pub name: String,
    /// The driven joint (index into [`ModelDef::joints`]).
    pub joint: usize,
    /// Its law.
    pub law: ActuatorLaw,
    /// Transmission ratio: `L = gear · q`, generalised force `gear · F` (finite, ≠ 0).
    pub gear: f64,
    /// The control is clamped to `[lo, hi]` (none: unclamped).
    pub ctrlrange: Option<[f64; 2]>,
    /// The actuator force `F` is clamped to `[lo, hi]` (none: unclamped).
    pub forcerange: Option<[f64; 2]>,
}

/// A coupling of two joints of the same kind with one coordinate each (revolute or prismatic
/// tree joints): joint `b` follows joint `a`, `q_b = ratio · q_a + offset` (rad or m), held as
/// an exact constraint on the joint coordinates (`step::coupling`).
#[derive(Clone, Debug, PartialEq)]
pub struct CouplingDef {
    /// The leading joint (index in [`ModelDef::joints`]).
    pub a: usize,
    /// The following joint.
    pub b: usize,
    /// `∂q_b/∂q_a` (dimensionless, finite, non-zero).
    pub ratio: f64,
    /// `q_b` at `q_a = 0`, rad or m.
    pub offset: f64,
}

/// The laws of a contact (see `model::contact_law`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactLaw {
    /// Coulomb friction coefficient μ ≥ 0.
    pub friction: f64,
    /// Normal stiffness k, N/m (also the friction bristle's), > 0.
    pub stiffness: f64,
    /// Hunt–Crossley damping d, s/m ≥ 0 (normal force `k x (1 + d ẋ)`; the bristle's damper
    /// `k d x`).
    pub damping: f64,
}

impl Default for ContactLaw {
    /// μ = 0.8, k = 1e5 N/m, d = 1 s/m: a 10–50 kg robot on four feet sinks 0.25–1.2 mm and
    /// its contacts ring at ≲ 600 rad/s, resolved by steps of 1 ms.
    fn default() -> Self {
        Self {
            friction: 0.8,
            stiffness: 1e5,
            damping: 1.0,
        }
    }
}

/// A plane under the model: its normal points against gravity (up, `+z`, without gravity).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GroundDef {
    /// Height of the plane along its normal, m.
    pub height: f64,
    /// Its contact laws (the default of every shape that sets none of its own).
    pub law: ContactLaw,
}

/// The geometry of a collision shape, in the shape's frame (m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ShapeKind {
    /// A sphere about the frame's origin.
    Sphere {
        /// Radius.
        radius: f64,
    },
    /// A capsule along the frame's z axis, centred: a segment of `length` swept by `radius`.
    Capsule {
        /// Radius.
        radius: f64,
        /// Length of the segment (without the caps).
        length: f64,
    },
    /// A box centred on the frame's origin, edges along its axes.
    Cuboid {
        /// Edge lengths along x, y, z.
        size: Vec3,
    },
    /// A cylinder along the frame's z axis, centred.
    Cylinder {
        /// Radius.
        radius: f64,
        /// Length.
        length: f64,
    },
}

/// A collision shape fixed on a body.
#[derive(Clone, Debug, PartialEq)]
pub struct ShapeDef {
    /// Identifier, unique among shapes.
    pub name: String,
    /// The body it is fixed on.
    pub body: BodyIndex,
    /// Its geometry.
    pub kind: ShapeKind,
    /// The shape's frame in the body frame.
    pub frame: Frame,
    /// Its own laws (those of the ground where `None`).
    pub law: Option<ContactLaw>,
}

/// Contact: the ground, the shapes and which pairs of shapes touch.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContactDef {
    /// The ground plane, if any.
    pub ground: Option<GroundDef>,
    /// Collision shapes; every shape touches the ground.
    pub shapes: Vec<ShapeDef>,
    /// Pairs of shapes (indices into `shapes`, on different bodies) that touch each other.
    pub pairs: Vec<(usize, usize)>,
}

impl ContactDef {
    /// The laws of shape `s`: its own, else the ground's, else the defaults.
    #[must_use]
    pub fn law(&self, s: usize) -> ContactLaw {
        self.shapes[s]
            .law
            .or(self.ground.map(|g| g.law))
            .unwrap_or_default()
    }
}
