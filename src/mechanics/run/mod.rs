//! Layer 3, a run: the mutable [`state::State`] of one simulation (time, coordinates, inputs,
//! tunable parameters, the step's workspace and memory), the outputs read off it (`outputs`,
//! with the reported rates projected onto the admissible velocities), and the entry points
//! that advance it (`advance`: `step`, `step_state`, `controlled_step`), the step-size control
//! (`control`), the joint-stop crossings that error-controlled steps end on (`events`), and
//! the operating point of a linear model read off a state (`operating`), and the
//! discrete-time linear model of a communication step (`step_map`).
//!
//! Uses: `step`, `model`, `linalg` and `crate::math`.

pub(crate) mod advance;
pub(crate) mod control;
pub(crate) mod events;
pub(crate) mod operating;
pub(crate) mod outputs;
pub(crate) mod state;
pub(crate) mod step_map;
