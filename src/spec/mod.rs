//! The model spec (interface.md §2): serde structs read from TOML and JSON with one schema,
//! validation that reports every problem with file and path, and lowering to
//! [`ModelDef`].
//!
//! # Schema reference
//!
//! SI units, angles in radians, vectors `[x, y, z]`. Defaults in parentheses.
//!
//! | key | type | meaning |
//! |---|---|---|
//! | `name` | identifier | model identifier (FMU modelIdentifier), required |
//! | `description` | string | free text (`""`) |
//! | `gravity` | 3 numbers | world frame, m/s² (`[0, 0, -9.81]`) |
//! | `[experiment]` `start`, `stop`, `step` | numbers | default experiment, s (0, 10, 0.01) |
//! | `[solver]` `max_step`, `order`, `tolerance` | numbers | internal step (1e-3), 2 or 4 (2), Newton tolerance in (0, 1e-3) (1e-10) |
//! | `[[body]]` `name`, `mass`, `inertia` | required | identifier; kg > 0; about the COM, body axes: `[Ixx, Iyy, Izz]`, `[Ixx, Iyy, Izz, Ixy, Ixz, Iyz]` or 3×3 rows |
//! | `[[body]]` `com` | 3 numbers | centre of mass in the body frame (origin) |
//! | `[[body]]` `position`, `orientation`, `velocity`, `angular_velocity` | free bodies only | see below |
//! | `[[joint]]` `name`, `type`, `parent`, `child` | required | identifier; `revolute`, `prismatic`, `cylindrical`, `universal`, `spherical`, `planar`, `fixed`; a body or `world`; a body |
//! | `[[joint]]` `origin = { xyz, rpy }` | placement | joint frame in the parent frame, URDF style (identity) |
//! | `[[joint]]` `child_origin = { xyz, rpy }` | placement | loop-closing joints only: joint frame in the child frame |
//! | `[[joint]]` `axis`, `axis2` | 3 numbers | joint axis in the joint frame (normalised); `axis2` for universal joints, ⟂ `axis` |
//! | `[[joint]]` `actuated`, `damping`, `stiffness` | bool, numbers ≥ 0 | actuator inputs (false); viscous damping (0); spring about q = 0 (0) |
//! | `[[joint]]` `initial = { q, qd }` | number or list | tree joints: coordinates and rates (zeros); spherical: `{ rpy \| quat, w }` |
//! | `[[load]]` `body`, `torque`, `force` | name, bools | world-frame torque / force-at-COM inputs on a body |
//!
//! # Decisions beyond interface.md
//! - a joint is **loop-closing** exactly when it names `child_origin` (its frame in the child
//!   body frame); every other joint is a tree joint, and a body has at most one tree joint as
//!   child. Loop-closing joints take no `initial`; the initial pose must satisfy them;
//! - a **free body** (no joint at all) carries its initial state on the `[[body]]` entry itself:
//!   `position` (required, it is what makes the body free on purpose), `orientation`
//!   (quaternion `[w, x, y, z]` or 3×3 rows, default identity), `velocity` and `angular_velocity`
//!   (world frame, default zero); a jointed body must not have them;
//! - `axis` is required for revolute, prismatic, cylindrical, universal and planar joints and
//!   refused for spherical and fixed ones; it is normalised when lowered;
//! - planar coordinates `[x, y, angle]` are measured along the joint frame's x and y when `axis`
//!   is its z axis (the recommended form).

mod error;
mod kinematics;
mod load;
mod lower;
mod prune;
mod validate;
mod values;

use serde::{Deserialize, Serialize};
use std::path::Path;

pub use error::{Problem, SpecErrors};
pub use values::{Coords, InertiaSpec, OrientationSpec};

use crate::mechanics::{ModelDef, SolverSettings};

include!(concat!(env!("OUT_DIR"), "/bundled.rs"));

/// The shipped example models: (folder name under `modelDescription/`, `spec.toml` text).
#[must_use]
pub fn bundled() -> &'static [(&'static str, &'static str)] {
    BUNDLED
}

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
    #[serde(deserialize_with = "values::order")]
    pub order: u8,
    /// Newton tolerance on the scaled residual, in (0, 1e-3); default 1e-10, below which
    /// conservation is at round-off.
    pub tolerance: f64,
}

impl Default for SolverSpec {
    fn default() -> Self {
        let s = SolverSettings::default();
        Self {
            max_step: s.max_step,
            order: s.order,
            tolerance: s.tolerance,
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
    /// Initial coordinates and rates (tree joints only; default zero).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub initial: Option<InitialSpec>,
}

impl JointSpec {
    /// True when the joint closes a kinematic loop (it names `child_origin`).
    #[must_use]
    pub fn is_loop_closing(&self) -> bool {
        self.child_origin.is_some()
    }
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
    /// Reads and validates a spec file; the format follows the extension (`.toml`, `.json`).
    ///
    /// # Errors
    /// Every problem found, each with the file name and the location inside it.
    pub fn from_path(path: &Path) -> Result<Spec, SpecErrors> {
        let origin = path.display().to_string();
        let format = match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("toml") => Format::Toml,
            Some("json") => Format::Json,
            _ => {
                return Err(SpecErrors::single(
                    &origin,
                    "",
                    "unknown file type: a model spec ends in .toml or .json",
                ))
            }
        };
        let text = std::fs::read_to_string(path)
            .map_err(|e| SpecErrors::single(&origin, "", format!("cannot read the file: {e}")))?;
        Self::from_str(&text, format, &origin)
    }

    /// Parses and validates spec text; `origin` (a file name) prefixes every message.
    ///
    /// # Errors
    /// Every problem found: syntax (with line and column), structure, and model consistency.
    #[allow(clippy::should_implement_trait)]
    pub fn from_str(text: &str, format: Format, origin: &str) -> Result<Spec, SpecErrors> {
        let parsed = load::parse(text, format, origin)?;
        match parsed.spec {
            Some(spec) if parsed.problems.is_empty() => {
                validate::validate(&spec, origin)?;
                Ok(spec)
            }
            spec => {
                // shape problems first, then the consistency problems of what could be read
                let mut problems = parsed.problems;
                if let Some(spec) = spec {
                    let more = validate::structure(&spec).problems;
                    problems.extend(
                        more.into_iter()
                            .filter(|p| !parsed.pruned.iter().any(|q| prune::related(&p.path, q))),
                    );
                }
                Err(SpecErrors {
                    origin: origin.to_string(),
                    problems,
                })
            }
        }
    }

    /// Deterministic JSON of the whole spec (the FMU's `resources/model.json`, hashed into the
    /// GUID). `Spec::from_str(&s.canonical_json(), Format::Json, ..)` gives back an equal spec.
    #[must_use]
    pub fn canonical_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// Lowers to the mechanics' definition and solver settings (axes normalised, frames as
    /// matrices, tree joints first, then loop-closing ones).
    ///
    /// # Errors
    /// The structural problems of [`Spec::from_str`] validation, for a spec built in code.
    pub fn lower(&self) -> Result<(ModelDef, SolverSettings), SpecErrors> {
        lower::lower(self, &self.name)
    }

    /// Index in `self.joint` of the joint called `name`.
    #[must_use]
    pub fn joint_index(&self, name: &str) -> Option<usize> {
        self.joint.iter().position(|j| j.name == name)
    }
}
