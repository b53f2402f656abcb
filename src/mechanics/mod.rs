//! The rotationless multibody core: director bodies, quadratic joint constraints, consistent
//! torques and the energy–momentum time step (theory.md). It knows nothing of FMI, XML, zip or
//! serde.
//!
//! Coordinate conventions: body `b` has `q_b = [φ, d1, d2, d3] ∈ R¹²` — its centre of mass and
//! the three directors (the columns of the rotation world ← body), world frame — stored at
//! `q[12b..12b+12]`; `v` likewise. The mass matrix `diag(m I, E ⊗ I)` with the Euler tensor
//! `E = ½ tr(J) I − J` is constant.
//!
//! Layers, lowest first; each uses only the ones below it (checked by `tests/import_cycles.rs`):
//!
//! | layer | holds |
//! |---|---|
//! | `linalg` | fixed-size blocks, dense LU, the tree block factorisation, the bordered solve |
//! | `model` | definitions, bodies, joints and their rows, kinematics, loops, the runtime `Model`, the velocity projection |
//! | `step` | residual and Jacobian, loads, turn coordinates, predictor, Newton (both forms), finish, the order-4 composition |
//! | `run` | the `State`, the outputs, `step` / `step_state` |
//!
//! This file only names the public API.
//!
//! Use: `Model::new(&def, settings)` once (validates, orders the tree, finds redundant loop
//! constraints, computes the initial state), `State::new(&model)`, then `step(&model, &mut state, h)`
//! as often as needed; `state.outputs()` holds every output after each step. `step_state` is the
//! integrator step alone (outputs refreshed on demand by `State::refresh_outputs`), for runs that
//! read outputs once per communication step.

mod linalg;
mod model;
mod run;
mod step;

pub use model::def::{
    ActuatorDef, ActuatorLaw, BodyDef, BodyIndex, BodyLoadDef, ContactDef, ContactLaw, CouplingDef,
    Frame, FreeBodyInitial, GroundDef, JointDef, JointInitial, JointLimits, JointType, ModelDef,
    ShapeDef, ShapeKind, SiteDef, SolverSettings, STOP_STIFFNESS,
};
pub use model::error::ModelError;
pub use model::linear::{Linear, Quantity};
pub use model::loop_closure::{Closure, Independent};
pub use model::minimal::NodalColumns;
pub use model::runtime::{InputSlot, Model};
pub use model::sticking::Sticking;
pub use model::tree_dynamics::{linearizable, supported, Coord, TreeDynamics, Unsupported};
pub use model::{body, constraint, contact, def, joint, kinematics, loops, ranges};
pub use run::advance::{controlled_step, step, step_state};
pub use run::control::{above_floor, Control, Verdict};
pub use run::events::{crossing_within, first_event, penetration, Event, LANDED};
pub use run::operating::Operating;
pub use run::outputs::{BodyOutput, JointOutput, Outputs};
pub use run::state::State;
pub use run::step_map::{begin_step_map, finish_step_map, StepMap};
pub use step::error::StepError;
pub use step::stage::{gamma1, StepStats};
