//! The model spec (interface.md §2): serde structs read from TOML and JSON with one schema,
//! validation that reports every problem with file and path, and lowering to
//! [`ModelDef`](crate::mechanics::ModelDef).
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
//! | `[[joint]]` `armature` | number ≥ 0 | rotor inertia in joint space, kg·m² or kg (0; not spherical, fixed or loop-closing) |
//! | `[[joint]]` `friction` | number ≥ 0 | Coulomb friction per coordinate, N·m or N; on a spherical joint a cone on its relative rotation, N·m (0; not fixed or loop-closing) |
//! | `[[joint]]` `lower`, `upper`, `effort` | numbers | revolute and prismatic: position limits (one-sided stops; none), actuator clamp ±effort (none) |
//! | `[[joint]]` `actuatorfrcrange` | `[lo, hi]`, lo < hi | revolute and prismatic: the sum of the `[[actuator]]`s' generalised forces on the joint clamped, N·m or N (none; MuJoCo's `actuatorfrcrange`) |
//! | `[[joint]]` `stop_stiffness`, `stop_damping` | numbers | the stops' spring (1e4 N·m/rad or N/m) and Hunt–Crossley damping (0) |
//! | `[[joint]]` `initial = { q, qd }` | number or list | tree joints: coordinates and rates (zeros); spherical: `{ rpy \| quat, w }` |
//! | `[[load]]` `body`, `torque`, `force` | name, bools | world-frame torque / force-at-COM inputs on a body |
//! | `[[actuator]]` `name`, `joint`, `kind` | identifier, a revolute or prismatic tree joint, `motor` \| `position` \| `velocity` | the input `actuator.A.ctrl`; the joint receives `gear · F`, `F = ctrl` (motor), `kp (ctrl − L) − kv L̇` (position), `kv (ctrl − L̇)` (velocity), `L = gear · q` (MuJoCo's laws); its work is in `system.work` |
//! | `[[actuator]]` `gear`, `kp`, `kv` | numbers | gear ≠ 0 (1); kp ≥ 0 (position, required); kv ≥ 0 (velocity: required; position: damping, 0) |
//! | `[[actuator]]` `ctrlrange`, `forcerange` | `[lo, hi]`, lo < hi | the control, the actuator force `F` clamped (none) |
//! | `[[site]]` `name`, `body`, `origin = { xyz, rpy }` | identifier, a body, placement | a frame fixed on the body: outputs `site.S.r`, `R`, `v`, `w` |
//! | `[[visual]]` `body`, `origin`, one of `box`, `cylinder`, `sphere`, `mesh` (+ `scale`), `rgba` | a body or `world`, placement, sizes in m | a shape for the 3-D viewer; no effect on the motion |
//! | `description` of a body, joint, site or actuator | text | appended to the descriptions of its variables (original URDF names) |
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
mod read;
mod schema;
mod shipped;
mod validate;
mod values;

pub use error::{did_you_mean, Problem, SpecErrors};
pub use schema::{
    ActuatorKind, ActuatorSpec, BodySpec, BoxShape, CollisionSpec, ContactPairSpec, CouplingSpec,
    Experiment, Format, GroundSpec, InitialSpec, JointKind, JointSpec, LoadSpec, OriginSpec,
    RoundShape, SiteSpec, SolverSpec, Spec, SphereShape, VisualSpec, ACTUATOR_KINDS, JOINT_TYPES,
};
pub use shipped::bundled;
pub use values::{Coords, InertiaSpec, OrientationSpec};
