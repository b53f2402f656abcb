//! The spec's schema: the serde structs read from TOML and JSON (one schema for both), as
//! documented in the table of the module `spec`.

use serde::{Deserialize, Serialize};

use super::values::{Coords, InertiaSpec, OrientationSpec};
use crate::mechanics::SolverSettings;

/// Text format of a spec.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// TOML (`.toml`).
    Toml,
    /// JSON (`.json`).
    Json,
}

fn default_gravity() -> [f64; 3] {
    [0.0, 0.0, -9.81]
}

/// A whole model spec. Field names are the spec's keys; see interface.md §2.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    /// Model identifier `[A-Za-z_][A-Za-z0-9_]*` (the FMU's modelIdentifier and `.so` name).
    pub name: String,
    /// Free text.
    #[serde(default)]
    pub description: String,
    /// Gravity, world frame, m/s² (default `[0, 0, -9.81]`).
    #[serde(default = "default_gravity")]
    pub gravity: [f64; 3],
    /// Default experiment.
    #[serde(default)]
    pub experiment: Experiment,
    /// Solver settings.
    #[serde(default)]
    pub solver: SolverSpec,
    /// Bodies (`[[body]]`).
    #[serde(default)]
    pub body: Vec<BodySpec>,
    /// Joints (`[[joint]]`).
    #[serde(default)]
    pub joint: Vec<JointSpec>,
    /// Body loads (`[[load]]`).
    #[serde(default)]
    pub load: Vec<LoadSpec>,
    /// Sites (`[[site]]`): named frames fixed on bodies, for reading poses.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub site: Vec<SiteSpec>,
    /// Shapes for the 3-D viewer (`[[visual]]`); no effect on the motion.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub visual: Vec<VisualSpec>,
    /// The ground plane (`[ground]`); none without this table.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ground: Option<GroundSpec>,
    /// Collision shapes fixed on bodies (`[[collision]]`); every shape touches the ground.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub collision: Vec<CollisionSpec>,
    /// Pairs of collision shapes that touch each other (`[[contact_pair]]`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub contact_pair: Vec<ContactPairSpec>,
    /// Every pair of shapes on different bodies touches, but for bodies joined by a joint.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub self_collision: bool,
    /// Joint couplings (`[[coupling]]`): joint `b` follows joint `a`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub coupling: Vec<CouplingSpec>,
    /// Joint actuators (`[[actuator]]`): each adds the input `actuator.A.ctrl`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub actuator: Vec<ActuatorSpec>,
}

/// `[[coupling]]`: joint `b` follows joint `a`, `q_b = ratio · q_a + offset` (two revolute or
/// two prismatic tree joints; URDF `<mimic>`, MJCF `<equality joint>` with a linear
/// `polycoef`), held exactly. The follower has no input of its own and its initial `q`, `qd`
/// follow from the leader's.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CouplingSpec {
    /// The leading joint.
    pub a: String,
    /// The following joint.
    pub b: String,
    /// `∂q_b/∂q_a` (finite, non-zero; default 1).
    #[serde(default = "one")]
    pub ratio: f64,
    /// `q_b` at `q_a = 0`, rad or m (default 0).
    #[serde(default)]
    pub offset: f64,
}

fn default_friction() -> f64 {
    crate::mechanics::ContactLaw::default().friction
}
/// Whether a number is 0 (fields written only when set).
#[allow(clippy::trivially_copy_pass_by_ref)]
fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

fn default_contact_stiffness() -> f64 {
    crate::mechanics::ContactLaw::default().stiffness
}
fn default_contact_damping() -> f64 {
    crate::mechanics::ContactLaw::default().damping
}

/// `[ground]`: a plane whose normal points against gravity.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroundSpec {
    /// Height along the normal, m (default 0).
    #[serde(default)]
    pub height: f64,
    /// Coulomb friction coefficient (default 0.8).
    #[serde(default = "default_friction")]
    pub friction: f64,
    /// Normal contact stiffness, N/m (default 1e5); also the friction bristle's.
    #[serde(default = "default_contact_stiffness")]
    pub stiffness: f64,
    /// Hunt–Crossley damping, s/m (default 1): normal force `k x (1 + damping ẋ)`.
    #[serde(default = "default_contact_damping")]
    pub damping: f64,
}

/// `{ radius = … }`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SphereShape {
    /// Radius, m.
    pub radius: f64,
}

/// `{ radius = …, length = … }` (along the shape's z axis).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoundShape {
    /// Radius, m.
    pub radius: f64,
    /// Length along z, m (a capsule's without its caps).
    pub length: f64,
}

/// `{ size = [x, y, z] }`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxShape {
    /// Full edge lengths, m.
    pub size: [f64; 3],
}

/// `[[collision]]`: a shape fixed on a body that touches the ground (and the shapes of the
/// pairs it is in); exactly one of `sphere`, `capsule`, `box`, `cylinder`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CollisionSpec {
    /// Identifier, unique among shapes (default: the body's name and the shape's number on
    /// it, `foot_1`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// The body it is fixed on.
    pub body: String,
    /// The shape's frame in the body frame.
    #[serde(default)]
    pub origin: OriginSpec,
    /// A sphere about the origin.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sphere: Option<SphereShape>,
    /// A capsule along z, centred.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub capsule: Option<RoundShape>,
    /// A box centred on the origin.
    #[serde(rename = "box", default, skip_serializing_if = "Option::is_none")]
    pub cuboid: Option<BoxShape>,
    /// A cylinder along z, centred (it touches the ground only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cylinder: Option<RoundShape>,
    /// Its own friction coefficient (default: the ground's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction: Option<f64>,
    /// Its own contact stiffness, N/m (default: the ground's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
    /// Its own Hunt–Crossley damping, s/m (default: the ground's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<f64>,
}

/// `[[contact_pair]]`: two collision shapes (on different bodies) that touch each other.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactPairSpec {
    /// One shape's name.
    pub a: String,
    /// The other's.
    pub b: String,
}

/// `[experiment]`: the FMU's DefaultExperiment and `triad simulate`'s defaults.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Experiment {
    /// Start time, s (default 0).
    pub start: f64,
    /// Stop time, s (default 10).
    pub stop: f64,
    /// Communication step, s (default 0.01: one output row per 10 ms).
    pub step: f64,
}

impl Default for Experiment {
    fn default() -> Self {
        Self {
            start: 0.0,
            stop: 10.0,
            step: 1e-2,
        }
    }
}

/// `[solver]`: integrator settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SolverSpec {
    /// Largest internal step, s (default 1e-3).
    pub max_step: f64,
    /// 2 (energy–momentum midpoint scheme) or 4 (its triple-jump composition); default 2.
    #[serde(deserialize_with = "super::values::order")]
    pub order: u8,
    /// Newton tolerance on the scaled residual, in (0, 1e-3); default 1e-10, below which
    /// conservation is at round-off.
    pub tolerance: f64,
    /// Most internal sub-steps one communication step may take (default 100 000): a step that
    /// needs more stops there (`fmi2Discard` with the progress made).
    pub max_substeps: u32,
    /// Stages of the order-4 composition: 3 (triple jump, default) or 5 (Suzuki's).
    pub stages: u8,
    /// Relative tolerance of error-controlled internal steps; 0 (default): fixed steps.
    pub rtol: f64,
    /// Absolute tolerance of error-controlled internal steps (default 0).
    pub atol: f64,
    /// Floor of an error-controlled internal step, s (default 1e-8).
    pub min_step: f64,
}

impl Default for SolverSpec {
    fn default() -> Self {
        let s = SolverSettings::default();
        Self {
            max_step: s.max_step,
            order: s.order,
            tolerance: s.tolerance,
            max_substeps: s.max_substeps,
            stages: s.stages,
            rtol: s.rtol,
            atol: s.atol,
            min_step: s.min_step,
        }
    }
}

/// `[[body]]`: a rigid body.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// Identifier, unique among bodies (`world` is reserved).
    pub name: String,
    /// Mass, kg (> 0).
    pub mass: f64,
    /// Centre of mass in the body frame, m (default origin).
    #[serde(default)]
    pub com: [f64; 3],
    /// Inertia about the centre of mass, body axes, kg·m².
    pub inertia: InertiaSpec,
    /// Free bodies only: initial body-frame origin, world frame, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub position: Option<[f64; 3]>,
    /// Free bodies only: initial orientation world ← body (default identity).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orientation: Option<OrientationSpec>,
    /// Free bodies only: initial velocity of the body-frame origin, world frame, m/s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<[f64; 3]>,
    /// Free bodies only: initial angular velocity, world frame, rad/s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angular_velocity: Option<[f64; 3]>,
    /// Free text appended to the descriptions of the body's variables (URDF import: the
    /// link's original name when it is not an identifier).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub description: String,
}

/// Joint type as written in a spec (`type = "revolute"`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum JointKind {
    /// One rotation about `axis`.
    Revolute,
    /// One translation along `axis`.
    Prismatic,
    /// Slide along and rotation about `axis`: q = [slide, angle].
    Cylindrical,
    /// Rotations about `axis` then `axis2`.
    Universal,
    /// Three rotations (ball joint).
    Spherical,
    /// Motion in the plane normal to `axis`: q = [x, y, angle].
    Planar,
    /// Rigid connection.
    Fixed,
}

/// The joint type names accepted in a spec.
pub const JOINT_TYPES: [&str; 7] = [
    "revolute",
    "prismatic",
    "cylindrical",
    "universal",
    "spherical",
    "planar",
    "fixed",
];

/// A placement `{ xyz, rpy }` (URDF origin): translation, m, and fixed-axis roll-pitch-yaw, rad.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OriginSpec {
    /// Translation, m.
    pub xyz: [f64; 3],
    /// Roll, pitch, yaw about the fixed x, y, z axes, rad.
    pub rpy: [f64; 3],
}

/// `initial = { ... }` of a tree joint.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InitialSpec {
    /// Coordinates (not spherical): a number for one-coordinate joints, else a list.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub q: Option<Coords>,
    /// Rates (not spherical), like `q`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub qd: Option<Coords>,
    /// Spherical: child frame relative to the joint frame as roll, pitch, yaw, rad.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rpy: Option<[f64; 3]>,
    /// Spherical: the same as a unit quaternion `[w, x, y, z]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub quat: Option<[f64; 4]>,
    /// Spherical: relative angular velocity in the child frame, rad/s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub w: Option<[f64; 3]>,
}

/// `[[joint]]`: a joint between a parent (a body or `world`) and a child body.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointSpec {
    /// Identifier, unique among joints.
    pub name: String,
    /// Joint type.
    #[serde(rename = "type")]
    pub kind: JointKind,
    /// Parent body name, or `world`.
    pub parent: String,
    /// Child body name.
    pub child: String,
    /// Joint frame in the parent frame.
    #[serde(default)]
    pub origin: OriginSpec,
    /// Loop-closing joints only: the joint frame in the child body frame. Naming it is what
    /// makes the joint loop-closing.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub child_origin: Option<OriginSpec>,
    /// Axis in the joint frame (rotation/slide axis, plane normal), normalised when lowered.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axis: Option<[f64; 3]>,
    /// Universal joints: second axis, perpendicular to `axis`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axis2: Option<[f64; 3]>,
    /// Adds actuator inputs (not for planar or fixed joints).
    #[serde(default)]
    pub actuated: bool,
    /// Viscous damping per coordinate, N·m·s/rad or N·s/m (≥ 0).
    #[serde(default)]
    pub damping: f64,
    /// Linear stiffness about q = 0 per coordinate, N·m/rad or N/m (≥ 0; not spherical).
    #[serde(default)]
    pub stiffness: f64,
    /// Rotor inertia in joint space per coordinate, kg·m² or kg (≥ 0; not spherical or
    /// fixed): adds `armature·q̇²/2` of kinetic energy, as MuJoCo and Pinocchio define it.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub armature: f64,
    /// Coulomb friction per coordinate, N·m or N; on a spherical joint a cone `|τ| ≤ C` on its
    /// relative rotation (≥ 0; not fixed or loop-closing):
    /// sticks below breakaway, slides at it, its loss counted in `system.work`.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub friction: f64,
    /// Revolute and prismatic joints: lower position limit, rad or m (a one-sided stop).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lower: Option<f64>,
    /// Revolute and prismatic joints: upper position limit, rad or m (a one-sided stop).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub upper: Option<f64>,
    /// Revolute and prismatic joints: the actuator input is clamped to ±effort, N·m or N (> 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub effort: Option<f64>,
    /// Revolute and prismatic joints: the sum of the generalised forces of the
    /// `[[actuator]]`s driving the joint is clamped to `[lo, hi]`, N·m or N (lo < hi; none:
    /// unclamped), as MuJoCo's joint `actuatorfrcrange`. The joint's own input is not in it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub actuatorfrcrange: Option<[f64; 2]>,
    /// Stiffness of the stops, N·m/rad or N/m (> 0; default 1e4).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stop_stiffness: Option<f64>,
    /// Hunt–Crossley damping of the stops (force c·penetration·rate), N·m·s/rad² or N·s/m²
    /// (≥ 0; default 0: elastic stops).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stop_damping: Option<f64>,
    /// Initial coordinates and rates (tree joints only; default zero).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub initial: Option<InitialSpec>,
    /// Free text appended to the descriptions of the joint's variables (URDF import: the
    /// joint's original name when it is not an identifier).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub description: String,
}

impl JointSpec {
    /// True when the joint closes a kinematic loop (it names `child_origin`).
    #[must_use]
    pub fn is_loop_closing(&self) -> bool {
        self.child_origin.is_some()
    }
}

/// `[[site]]`: a named frame fixed on a body (a tool centre point, a sensor); adds the outputs
/// `site.S.r[i]`, `site.S.R[i,j]`, `site.S.v[i]`, `site.S.w[i]` (world frame).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SiteSpec {
    /// Identifier, unique among sites.
    pub name: String,
    /// The body it is fixed on.
    pub body: String,
    /// The site frame in the body frame.
    #[serde(default)]
    pub origin: OriginSpec,
    /// Free text appended to the descriptions of the site's variables (URDF import: the
    /// link's original name when it is not an identifier).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub description: String,
}

/// `[[visual]]`: a shape drawn by the 3-D viewer, fixed on a body (or the world); exactly one of
/// `box`, `cylinder`, `sphere`, `mesh`. It has no mass and no effect on the motion.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VisualSpec {
    /// The body it is fixed on, or `world`.
    pub body: String,
    /// The shape's frame in the body frame.
    #[serde(default)]
    pub origin: OriginSpec,
    /// A box centred on the origin: full side lengths along x, y, z, m.
    #[serde(rename = "box", default, skip_serializing_if = "Option::is_none")]
    pub cuboid: Option<[f64; 3]>,
    /// A cylinder along z centred on the origin: `[radius, length]`, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cylinder: Option<[f64; 2]>,
    /// A sphere centred on the origin: radius, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sphere: Option<f64>,
    /// A mesh file (`package://…`, relative to the model file, or absolute), as written.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mesh: Option<String>,
    /// Scale of a mesh along x, y, z (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale: Option<[f64; 3]>,
    /// Colour, red, green, blue, alpha in [0, 1].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rgba: Option<[f64; 4]>,
}

/// The law of an `[[actuator]]` (MuJoCo's `<motor>`, `<position>`, `<velocity>`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ActuatorKind {
    /// `F = ctrl`.
    Motor,
    /// `F = kp (ctrl − L) − kv L̇`, `L = gear · q`.
    Position,
    /// `F = kv (ctrl − L̇)`.
    Velocity,
}

/// The actuator kinds as written in a spec.
pub const ACTUATOR_KINDS: &[&str] = &["motor", "position", "velocity"];

fn one() -> f64 {
    1.0
}
#[allow(clippy::trivially_copy_pass_by_ref, clippy::float_cmp)]
fn is_one(x: &f64) -> bool {
    *x == 1.0
}

/// `[[actuator]]`: a control input `actuator.A.ctrl` driving the coordinate `q` of a revolute
/// or prismatic tree joint through a gear: the joint receives `gear · F`, `F` the actuator force
/// of its `kind` at `L = gear · q`, `L̇ = gear · q̇` (MuJoCo's law), its work counted in
/// `system.work`. It adds to the joint's own `joint.J.tau`/`joint.J.f` input, if any.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ActuatorSpec {
    /// Identifier, unique among actuators.
    pub name: String,
    /// The driven joint.
    pub joint: String,
    /// The law.
    pub kind: ActuatorKind,
    /// Transmission ratio (default 1; finite, ≠ 0).
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub gear: f64,
    /// Position servos: the position gain, N·m/rad or N/m per unit of `L` (≥ 0; required).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kp: Option<f64>,
    /// Velocity servos: the velocity gain (required); position servos: the damping gain
    /// (default 0); N·m·s/rad or N·s/m (≥ 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kv: Option<f64>,
    /// The control is clamped to `[lo, hi]` (lo < hi; none: unclamped).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ctrlrange: Option<[f64; 2]>,
    /// The actuator force `F` is clamped to `[lo, hi]` (lo < hi; none: unclamped).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub forcerange: Option<[f64; 2]>,
    /// Free text appended to the description of its input (MJCF import: the original name).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub description: String,
}

/// `[[load]]`: external inputs on a body (world frame; the force acts at the centre of mass).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadSpec {
    /// Loaded body.
    pub body: String,
    /// Adds `body.B.torque[1..3]`, N·m.
    #[serde(default)]
    pub torque: bool,
    /// Adds `body.B.force[1..3]`, N.
    #[serde(default)]
    pub force: bool,
}

impl Spec {
    /// The name of every collision shape: its own, else the body's name and its number among
    /// that body's shapes (`foot_1`, `foot_2`).
    #[must_use]
    pub fn collision_names(&self) -> Vec<String> {
        let mut count: std::collections::HashMap<&str, usize> = std::collections::HashMap::new();
        self.collision
            .iter()
            .map(|c| {
                let n = count.entry(c.body.as_str()).or_insert(0);
                *n += 1;
                c.name
                    .clone()
                    .unwrap_or_else(|| format!("{}_{}", c.body, n))
            })
            .collect()
    }

    /// Deterministic JSON of the whole spec (the FMU's `resources/model.json`, hashed into the
    /// GUID). `Spec::from_str(&s.canonical_json(), Format::Json, ..)` gives back an equal spec.
    #[must_use]
    pub fn canonical_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// `(prefix, text)` for every body, joint and site with a `description`: the prefix of its
    /// variable names (`body.B`, `joint.J`, `site.S`) and the text to append to their
    /// descriptions.
    #[must_use]
    pub fn labels(&self) -> Vec<(String, String)> {
        let bodies = self.body.iter().map(|b| ("body", &b.name, &b.description));
        let joints = self
            .joint
            .iter()
            .map(|j| ("joint", &j.name, &j.description));
        let sites = self.site.iter().map(|s| ("site", &s.name, &s.description));
        let actuators = self
            .actuator
            .iter()
            .map(|a| ("actuator", &a.name, &a.description));
        bodies
            .chain(joints)
            .chain(sites)
            .chain(actuators)
            .filter(|(_, _, d)| !d.is_empty())
            .map(|(kind, name, d)| (format!("{kind}.{name}"), d.clone()))
            .collect()
    }

    /// Index in `self.joint` of the joint called `name`.
    #[must_use]
    pub fn joint_index(&self, name: &str) -> Option<usize> {
        self.joint.iter().position(|j| j.name == name)
    }
}
