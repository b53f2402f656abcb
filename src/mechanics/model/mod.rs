//! Layer 1, the model: what a multibody system *is*, built once and immutable during a run.
//!
//! - the input definition (`def`) and its error (`error`);
//! - bodies and their mass data (`body`), the coordinate layout and the one constraint
//!   primitive (`constraint`: nodes `[φ, d1, d2, d3]`, `LinVec`, `DotRow`), rows in sparse form
//!   (`sparse_row`);
//! - joints as rows of that primitive (`joint`), the initial configuration (`kinematics`),
//!   loop closures (`loops`), joint couplings (`coupling`), redundant loop rows (`redundancy`) and whether bodies without
//!   mass leave the motion determined (`determinacy`);
//! - the runtime [`runtime::Model`] and its set-up (`assemble`);
//! - the director kernels shared by the step and the projection (`kernels`: reciprocal basis,
//!   rotation increment, projected blocks), where the model's rows land in the linear system
//!   (`sink`), and the M-orthogonal projection of velocities onto the admissible ones
//!   (`projection`; it makes the initial rates consistent and the reported rates exact);
//! - the one-sided spring written once (`one_sided`); joint stops as an exact discrete gradient
//!   (`stops`); joint friction as a sticking bristle (`joint_friction`); joint actuators' laws
//!   (`joint_actuator`); contact with the ground and between bodies: geometry (`contact`) and laws
//!   (`contact_law`);
//! - the valid range of every parameter and solver setting (`ranges`), shared by the spec
//!   check and the FMU;
//! - the continuous-time dynamics of trees in minimal coordinates, generic over the scalar
//!   (`tree_dynamics`), its exact linear models by analytic derivatives (`tree_dynamics`'s
//!   `tree_partials`, in spatial vectors: `spatial`; mass-matrix solves by the articulated-body
//!   recursion: `articulated`) or dual numbers (`linear`), and the tangents between its
//!   coordinates and the nodal ones (`minimal`);
//! - test models shared by several layers' unit tests (`fixtures`).
//!
//! Uses: `linalg` and `crate::math`; never `step` or `run`.

pub(crate) mod articulated;
pub(crate) mod assemble;
pub mod body;
pub mod constraint;
pub mod contact;
pub(crate) mod contact_law;
pub(crate) mod coupling;
pub mod def;
pub(crate) mod determinacy;
pub(crate) mod error;
#[cfg(test)]
pub(crate) mod fixtures;
pub mod joint;
pub(crate) mod joint_actuator;
pub(crate) mod joint_friction;
pub(crate) mod kernels;
pub mod kinematics;
pub mod linear;
pub mod loop_closure;
pub mod loop_linear;
pub mod loops;
pub mod minimal;
pub mod motion;
pub(crate) mod one_sided;
pub(crate) mod projection;
pub mod ranges;
pub(crate) mod redundancy;
pub(crate) mod runtime;
pub mod scalar;
pub(crate) mod sink;
pub(crate) mod sparse_row;
pub(crate) mod spatial;
pub mod sticking;
pub(crate) mod sticking_at;
pub(crate) mod stops;
pub mod tree_dynamics;
pub mod unsupported;
