//! Layer 2, the step: one energy–momentum step of size `h` on a preallocated workspace.
//!
//! - `work`: the workspace (`Work`), the loads held over a step (`Held`) and the solver's
//!   memory;
//! - the scaled EM residual and its Jacobian: `newton` (rows and bodies, the multiplier form),
//!   `body_terms` (inertia and body loads), `joint_loads` (actuators, springs, dampers),
//!   `coupling` (the rows of joint couplings), `turn`
//!   (the exact discrete gradient of a joint angle), `contact` (ground and body–body contact
//!   forces, their work and the friction bristles; one ground point's law in `ground_law`),
//!   `increment` (the multiplier form's linear solve and update);
//! - `reduced`: Newton on the joint increments for trees (the discrete null-space method);
//! - `predictor` (the Newton start from the previous stages), `finish` (velocity update, work
//!   account, unwrapped angles), `momentum` (bodies in contact: the momenta exact at any
//!   tolerance), `identity` (the spurious roots a converged stage is refused for),
//!   `stage` (a robust stage, the order-4 composition), `tangent` (the step's exact tangent map,
//!   carried through a run; its columns in `tangent_state`, the ground contact's share in
//!   `contact_tangent`), `error`.
//!
//! Uses: `model`, `linalg` and `crate::math`; never `run`.

pub(crate) mod body_terms;
#[cfg(test)]
mod border_tests;
pub(crate) mod contact;
pub(crate) mod contact_tangent;
pub(crate) mod coupling;
pub(crate) mod error;
pub(crate) mod finish;
pub(crate) mod ground_law;
pub(crate) mod identity;
pub(crate) mod increment;
pub(crate) mod joint_loads;
pub(crate) mod momentum;
pub(crate) mod newton;
pub(crate) mod predictor;
pub(crate) mod reduced;
pub(crate) mod stage;
pub(crate) mod tangent;
pub(crate) mod tangent_state;
pub(crate) mod turn;
pub(crate) mod work;
