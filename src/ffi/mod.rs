//! The exported `fmi2*` C functions (FMI 2.0.4 §2.1 and §4.2) and, in `fmi3/`, the `fmi3*` ones
//! (FMI 3.0): the only module with `unsafe` code. Every function is thin: convert the C
//! arguments, call an [`Instance`](crate::fmu::Instance) method, turn the result into an
//! `fmi2Status` (an `fmi3Status` has the same codes).
//!
//! Conventions (the contract with importers):
//! - **Panics** never cross the C boundary: every body runs inside `catch_unwind`
//!   (`ffi_fn!`). A panic is logged (`logStatusFatal`), poisons *that* instance (every later
//!   call but `fmi2FreeInstance` returns `fmi2Error`) and returns `fmi2Fatal`. Other instances
//!   are unaffected. The one process-wide structure is the registry of live FMU states
//!   (`registry.rs`, behind a lock), so that a state moves between instances of a model.
//! - **NULL** pointers (`non_null!`) are logged and rejected with `fmi2Error`; an array
//!   pointer may be NULL when its length is 0. A NULL `fmi2Component` returns `fmi2Error`
//!   (nothing to log to).
//! - **Logging** goes only through the importer's callback, always with the format `"%s"`.
//! - The component pointer is a `Box<Component>`; a magic word catches use of a freed or
//!   foreign pointer in most cases.
#![allow(unsafe_code)]
#![deny(unsafe_op_in_unsafe_fn)]
#![warn(clippy::undocumented_unsafe_blocks)]
#![allow(non_snake_case)]

pub mod common;
pub mod cosim;
pub mod fmi3;
pub mod getset;
mod guard;
pub mod logger;
mod registry;
pub mod state;
pub mod types;

pub use guard::{code, triad_test_panic, Component};
pub use registry::live_count as live_fmu_states;

// every export has exactly the standard's C type
use common::*;
use cosim::*;
use getset::*;
use state::*;
use types::*;
const _: fmi2GetTypesPlatformTYPE = fmi2GetTypesPlatform;
const _: fmi2GetVersionTYPE = fmi2GetVersion;
const _: fmi2SetDebugLoggingTYPE = fmi2SetDebugLogging;
const _: fmi2InstantiateTYPE = fmi2Instantiate;
const _: fmi2FreeInstanceTYPE = fmi2FreeInstance;
const _: fmi2SetupExperimentTYPE = fmi2SetupExperiment;
const _: fmi2EnterInitializationModeTYPE = fmi2EnterInitializationMode;
const _: fmi2ExitInitializationModeTYPE = fmi2ExitInitializationMode;
const _: fmi2TerminateTYPE = fmi2Terminate;
const _: fmi2ResetTYPE = fmi2Reset;
const _: fmi2GetRealTYPE = fmi2GetReal;
const _: fmi2GetIntegerTYPE = fmi2GetInteger;
const _: fmi2GetBooleanTYPE = fmi2GetBoolean;
const _: fmi2GetStringTYPE = fmi2GetString;
const _: fmi2SetRealTYPE = fmi2SetReal;
const _: fmi2SetIntegerTYPE = fmi2SetInteger;
const _: fmi2SetBooleanTYPE = fmi2SetBoolean;
const _: fmi2SetStringTYPE = fmi2SetString;
const _: fmi2GetFMUstateTYPE = fmi2GetFMUstate;
const _: fmi2SetFMUstateTYPE = fmi2SetFMUstate;
const _: fmi2FreeFMUstateTYPE = fmi2FreeFMUstate;
const _: fmi2SerializedFMUstateSizeTYPE = fmi2SerializedFMUstateSize;
const _: fmi2SerializeFMUstateTYPE = fmi2SerializeFMUstate;
const _: fmi2DeSerializeFMUstateTYPE = fmi2DeSerializeFMUstate;
const _: fmi2GetDirectionalDerivativeTYPE = fmi2GetDirectionalDerivative;
const _: fmi2SetRealInputDerivativesTYPE = fmi2SetRealInputDerivatives;
const _: fmi2GetRealOutputDerivativesTYPE = fmi2GetRealOutputDerivatives;
const _: fmi2DoStepTYPE = fmi2DoStep;
const _: fmi2CancelStepTYPE = fmi2CancelStep;
const _: fmi2GetStatusTYPE = fmi2GetStatus;
const _: fmi2GetRealStatusTYPE = fmi2GetRealStatus;
const _: fmi2GetIntegerStatusTYPE = fmi2GetIntegerStatus;
const _: fmi2GetBooleanStatusTYPE = fmi2GetBooleanStatus;
const _: fmi2GetStringStatusTYPE = fmi2GetStringStatus;
