//! The rotationless multibody core: director bodies, quadratic joint constraints, consistent
//! torques and the energy–momentum time step (theory.md). It knows nothing of FMI, XML, zip or
//! serde.
//!
//! Coordinate conventions: body `b` has `q_b = [φ, d1, d2, d3] ∈ R¹²` — its centre of mass and
//! the three directors (the columns of the rotation world ← body), world frame — stored at
//! `q[12b..12b+12]`; `v` likewise. The mass matrix `diag(m I, E ⊗ I)` with the Euler tensor
//! `E = ½ tr(J) I − J` is constant.
//!
//! Use: `Model::new(&def, settings)` once (validates, orders the tree, finds redundant loop
//! constraints, computes the initial state), `State::new(&model)`, then `step(&model, &mut state, h)`
//! as often as needed; `state.outputs()` holds every output after each step. `step_state` is the
//! integrator step alone (outputs refreshed on demand by `State::refresh_outputs`), for runs that
//! read outputs once per communication step.

mod assemble;
pub mod body;
mod body_terms;
mod border;
pub mod constraint;
pub mod def;
mod dense;
mod error;
mod finish;
mod increment;
pub mod joint;
mod joint_loads;
mod kernels;
pub mod kinematics;
pub mod loops;
mod model;
mod newton;
mod outputs;
mod predictor;
mod projection;
mod reduced;
mod redundancy;
mod small_mat;
mod solver;
mod sparse_row;
mod state;
mod step;
mod turn;
mod work;

pub use def::{
    BodyDef, BodyIndex, BodyLoadDef, Frame, FreeBodyInitial, JointDef, JointInitial, JointType,
    ModelDef, SolverSettings,
};
pub use error::{ModelError, StepError};
pub use model::{InputSlot, Model};
pub use outputs::{BodyOutput, JointOutput, Outputs};
pub use state::State;
pub use step::{gamma1, step, step_state, StepStats};
