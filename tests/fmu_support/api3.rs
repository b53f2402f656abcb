//! The FMI 3 functions as the FMU tests call them: the crate's own exports (linked statically,
//! the default) or, with `TRIAD_DYNAMIC_TESTS=1`, the same functions of the shared library
//! `cdylib()` (`TRIAD_CDYLIB`: e.g. the glibc-2.17 runtime) loaded as an importer loads an
//! FMU's binary (as `api` does for FMI 2). `.ci/run` runs the FMI 3 randomised call test and
//! the states test both ways.
#![allow(
    dead_code,
    non_snake_case,
    clippy::missing_safety_doc,
    clippy::too_many_arguments,
    clippy::unused_unit
)]

use triad::ffi::fmi3::types::*;

/// An array of value references.
type VR = *const fmi3ValueReference;
type I = fmi3Instance;
type S = fmi3Status;
type B = fmi3Boolean;

mod linked {
    pub use triad::ffi::fmi3::cosim::*;
    pub use triad::ffi::fmi3::getset::*;
    pub use triad::ffi::fmi3::lifecycle::*;
    pub use triad::ffi::fmi3::state::*;
}

fmi_api! {
    fn fmi3InstantiateCoSimulation(a0: fmi3String, a1: fmi3String, a2: fmi3String, a3: B, a4: B, a5: B, a6: B, a7: VR, a8: usize, a9: fmi3InstanceEnvironment, a10: fmi3LogMessageCallback, a11: fmi3IntermediateUpdateCallback) -> I;
    fn fmi3FreeInstance(a0: I) -> ();
    fn fmi3EnterInitializationMode(a0: I, a1: B, a2: f64, a3: f64, a4: B, a5: f64) -> S;
    fn fmi3ExitInitializationMode(a0: I) -> S;
    fn fmi3Terminate(a0: I) -> S;
    fn fmi3Reset(a0: I) -> S;
    fn fmi3DoStep(a0: I, a1: f64, a2: f64, a3: B, a4: *mut B, a5: *mut B, a6: *mut B, a7: *mut f64) -> S;
    fn fmi3GetFloat64(a0: I, a1: VR, a2: usize, a3: *mut fmi3Float64, a4: usize) -> S;
    fn fmi3SetFloat64(a0: I, a1: VR, a2: usize, a3: *const fmi3Float64, a4: usize) -> S;
    fn fmi3GetInt32(a0: I, a1: VR, a2: usize, a3: *mut fmi3Int32, a4: usize) -> S;
    fn fmi3SetInt32(a0: I, a1: VR, a2: usize, a3: *const fmi3Int32, a4: usize) -> S;
    fn fmi3GetFMUState(a0: I, a1: *mut fmi3FMUState) -> S;
    fn fmi3SetFMUState(a0: I, a1: fmi3FMUState) -> S;
    fn fmi3FreeFMUState(a0: I, a1: *mut fmi3FMUState) -> S;
    fn fmi3SerializedFMUStateSize(a0: I, a1: fmi3FMUState, a2: *mut usize) -> S;
    fn fmi3SerializeFMUState(a0: I, a1: fmi3FMUState, a2: *mut fmi3Byte, a3: usize) -> S;
    fn fmi3DeserializeFMUState(a0: I, a1: *const fmi3Byte, a2: usize, a3: *mut fmi3FMUState) -> S;
    fn fmi3GetDirectionalDerivative(a0: I, a1: VR, a2: usize, a3: VR, a4: usize, a5: *const f64, a6: usize, a7: *mut f64, a8: usize) -> S;
    fn fmi3GetAdjointDerivative(a0: I, a1: VR, a2: usize, a3: VR, a4: usize, a5: *const f64, a6: usize, a7: *mut f64, a8: usize) -> S;
}
