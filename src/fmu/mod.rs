//! Safe FMI 2.0 Co-Simulation semantics: the instance state machine, get/set by value reference,
//! communication steps, FMU-state snapshots and the GUID. No `unsafe`, no C types: `ffi` converts
//! C arguments and calls [`Instance`] methods.
//!
//! Design (FMI 2.0.4 §4.2.4):
//! - **State machine as data**: [`Mode`] per instance, one [`allowed`] table for every [`Op`].
//! - **Two kinds of `fmi2Error`**: a *rejected* call (illegal call sequence, unknown value
//!   reference, forbidden set, non-finite value, wrong communication point) changes nothing and
//!   leaves the mode as it was, so the instance keeps working; a *failure* (the model cannot be
//!   built, a corrupt FMU state) moves it to [`Mode::Error`], from which only `fmi2Reset`,
//!   `fmi2SetFMUstate`, the getters and `fmi2FreeInstance` lead out. A panic moves it to
//!   [`Mode::Fatal`] (poisoned): every later call except `fmi2FreeInstance` returns `fmi2Error`.
//! - **When the simulation exists**: it is built at `fmi2EnterInitializationMode` (so outputs are
//!   available in Initialization Mode for `<InitialUnknowns>`) and rebuilt whenever a parameter
//!   is set during Initialization Mode. Parameters set before that change a private
//!   `ModelDef`/`SolverSettings` copy.
//! - **Discard keeps the instance usable**: a failed sub-step rolls the state back to the start of
//!   the communication step; the mode stays `StepComplete`, `fmi2LastSuccessfulTime` reports the
//!   time, and the next `fmi2DoStep` from there works.

pub mod api;
pub mod capabilities;
pub mod contract;
mod derivatives;
mod fmi3;
pub mod guid;
pub mod instance;
pub mod log;
pub mod mode;
mod params;
pub mod resource;
pub mod runtime_id;
pub mod snapshot;
mod start_gap;
pub mod status;

pub use api::Api;
pub use capabilities::{Capabilities, CAPABILITIES};
pub use instance::{allowed, Instance, Mode, Op};
pub use log::{Category, LogSink};
pub use snapshot::Snapshot;
pub use status::{FmuError, Status};
