//! The FMI functions as the FMU tests call them: the crate's own exports (linked statically,
//! the default) or, with `TRIAD_DYNAMIC_TESTS=1`, the same functions of the shared library
//! `cdylib()` (`TRIAD_CDYLIB`: e.g. the glibc-2.17 runtime) loaded as an importer loads an FMU's
//! binary. `.ci/run` runs the randomised call test both ways.
#![allow(
    dead_code,
    non_snake_case,
    clippy::missing_safety_doc,
    clippy::too_many_arguments,
    clippy::unused_unit
)]

use std::ffi::c_char;
use triad::ffi::types::*;

/// An array of value references.
type VR = *const fmi2ValueReference;

mod linked {
    pub use triad::ffi::common::*;
    pub use triad::ffi::cosim::*;
    pub use triad::ffi::getset::*;
    pub use triad::ffi::state::*;
}

fmi_api! {
    fn fmi2GetTypesPlatform() -> *const c_char;
    fn fmi2GetVersion() -> *const c_char;
    fn fmi2SetDebugLogging(a0: fmi2Component, a1: fmi2Boolean, a2: usize, a3: *const fmi2String) -> fmi2Status;
    fn fmi2Instantiate(a0: fmi2String, a1: fmi2Type, a2: fmi2String, a3: fmi2String, a4: *const fmi2CallbackFunctions, a5: fmi2Boolean, a6: fmi2Boolean) -> fmi2Component;
    fn fmi2FreeInstance(a0: fmi2Component) -> ();
    fn fmi2SetupExperiment(a0: fmi2Component, a1: fmi2Boolean, a2: fmi2Real, a3: fmi2Real, a4: fmi2Boolean, a5: fmi2Real) -> fmi2Status;
    fn fmi2EnterInitializationMode(a0: fmi2Component) -> fmi2Status;
    fn fmi2ExitInitializationMode(a0: fmi2Component) -> fmi2Status;
    fn fmi2Terminate(a0: fmi2Component) -> fmi2Status;
    fn fmi2Reset(a0: fmi2Component) -> fmi2Status;
    fn fmi2GetReal(a0: fmi2Component, a1: VR, a2: usize, a3: *mut fmi2Real) -> fmi2Status;
    fn fmi2GetInteger(a0: fmi2Component, a1: VR, a2: usize, a3: *mut fmi2Integer) -> fmi2Status;
    fn fmi2GetBoolean(a0: fmi2Component, a1: VR, a2: usize, a3: *mut fmi2Boolean) -> fmi2Status;
    fn fmi2GetString(a0: fmi2Component, a1: VR, a2: usize, a3: *mut fmi2String) -> fmi2Status;
    fn fmi2SetReal(a0: fmi2Component, a1: VR, a2: usize, a3: *const fmi2Real) -> fmi2Status;
    fn fmi2SetInteger(a0: fmi2Component, a1: VR, a2: usize, a3: *const fmi2Integer) -> fmi2Status;
    fn fmi2SetBoolean(a0: fmi2Component, a1: VR, a2: usize, a3: *const fmi2Boolean) -> fmi2Status;
    fn fmi2SetString(a0: fmi2Component, a1: VR, a2: usize, a3: *const fmi2String) -> fmi2Status;
    fn fmi2GetFMUstate(a0: fmi2Component, a1: *mut fmi2FMUstate) -> fmi2Status;
    fn fmi2SetFMUstate(a0: fmi2Component, a1: fmi2FMUstate) -> fmi2Status;
    fn fmi2FreeFMUstate(a0: fmi2Component, a1: *mut fmi2FMUstate) -> fmi2Status;
    fn fmi2SerializedFMUstateSize(a0: fmi2Component, a1: fmi2FMUstate, a2: *mut usize) -> fmi2Status;
    fn fmi2SerializeFMUstate(a0: fmi2Component, a1: fmi2FMUstate, a2: *mut fmi2Byte, a3: usize) -> fmi2Status;
    fn fmi2DeSerializeFMUstate(a0: fmi2Component, a1: *const fmi2Byte, a2: usize, a3: *mut fmi2FMUstate) -> fmi2Status;
    fn fmi2GetDirectionalDerivative(a0: fmi2Component, a1: VR, a2: usize, a3: VR, a4: usize, a5: *const fmi2Real, a6: *mut fmi2Real) -> fmi2Status;
    fn fmi2SetRealInputDerivatives(a0: fmi2Component, a1: VR, a2: usize, a3: *const fmi2Integer, a4: *const fmi2Real) -> fmi2Status;
    fn fmi2GetRealOutputDerivatives(a0: fmi2Component, a1: VR, a2: usize, a3: *const fmi2Integer, a4: *mut fmi2Real) -> fmi2Status;
    fn fmi2DoStep(a0: fmi2Component, a1: fmi2Real, a2: fmi2Real, a3: fmi2Boolean) -> fmi2Status;
    fn fmi2CancelStep(a0: fmi2Component) -> fmi2Status;
    fn fmi2GetStatus(a0: fmi2Component, a1: fmi2StatusKind, a2: *mut fmi2Status) -> fmi2Status;
    fn fmi2GetRealStatus(a0: fmi2Component, a1: fmi2StatusKind, a2: *mut fmi2Real) -> fmi2Status;
    fn fmi2GetIntegerStatus(a0: fmi2Component, a1: fmi2StatusKind, a2: *mut fmi2Integer) -> fmi2Status;
    fn fmi2GetBooleanStatus(a0: fmi2Component, a1: fmi2StatusKind, a2: *mut fmi2Boolean) -> fmi2Status;
    fn fmi2GetStringStatus(a0: fmi2Component, a1: fmi2StatusKind, a2: *mut fmi2String) -> fmi2Status;
}
