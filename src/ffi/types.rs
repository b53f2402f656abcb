//! FMI 2.0 C types, transcribed by hand from `fmi2TypesPlatform.h` and `fmi2FunctionTypes.h`
//! (FMI 2.0.4, "default" platform). C enums that the importer passes *in* are plain `c_int`
//! with constants, so an out-of-range value can never become an invalid Rust enum. The
//! `fmi2*TYPE` function types are checked against the exports at the bottom of `mod.rs`.
#![allow(non_camel_case_types, non_upper_case_globals)]

use std::ffi::{c_char, c_int, c_uint, c_void};

/// Opaque instance pointer (`typedef void* fmi2Component`).
pub type fmi2Component = *mut c_void;
/// Importer's environment pointer, passed back to the logger.
pub type fmi2ComponentEnvironment = *mut c_void;
/// Opaque FMU state pointer.
pub type fmi2FMUstate = *mut c_void;
/// Value reference.
pub type fmi2ValueReference = c_uint;
/// Real.
pub type fmi2Real = f64;
/// Integer.
pub type fmi2Integer = c_int;
/// Boolean (`int`, 0 or 1).
pub type fmi2Boolean = c_int;
/// Character.
pub type fmi2Char = c_char;
/// NUL-terminated string.
pub type fmi2String = *const fmi2Char;
/// Byte of a serialised FMU state.
pub type fmi2Byte = c_char;

/// `fmi2True`.
pub const fmi2True: fmi2Boolean = 1;
/// `fmi2False`.
pub const fmi2False: fmi2Boolean = 0;

/// `fmi2Status` (a C enum, `int` sized).
pub type fmi2Status = c_int;
/// All well.
pub const fmi2OK: fmi2Status = 0;
/// Something may be wrong; computation continues.
pub const fmi2Warning: fmi2Status = 1;
/// The step or value was not accepted.
pub const fmi2Discard: fmi2Status = 2;
/// This instance cannot continue without reset or restore.
pub const fmi2Error: fmi2Status = 3;
/// Everything is corrupted.
pub const fmi2Fatal: fmi2Status = 4;
/// Asynchronous step in progress (never returned by triad).
pub const fmi2Pending: fmi2Status = 5;

/// `fmi2Type`.
pub type fmi2Type = c_int;
/// Model Exchange.
pub const fmi2ModelExchange: fmi2Type = 0;
/// Co-Simulation.
pub const fmi2CoSimulation: fmi2Type = 1;

/// `fmi2StatusKind`.
pub type fmi2StatusKind = c_int;
/// Status of an asynchronous `fmi2DoStep`.
pub const fmi2DoStepStatus: fmi2StatusKind = 0;
/// String describing a pending step.
pub const fmi2PendingStatus: fmi2StatusKind = 1;
/// Time of the last successful step.
pub const fmi2LastSuccessfulTime: fmi2StatusKind = 2;
/// Whether the slave wants to stop.
pub const fmi2Terminated: fmi2StatusKind = 3;

/// `typedef void (*fmi2CallbackLogger)(fmi2ComponentEnvironment, fmi2String instanceName,
/// fmi2Status, fmi2String category, fmi2String message, ...)`: variadic, printf-style.
pub type fmi2CallbackLogger = Option<
    unsafe extern "C" fn(
        fmi2ComponentEnvironment,
        fmi2String,
        fmi2Status,
        fmi2String,
        fmi2String,
        ...
    ),
>;
/// `calloc`-like allocator callback (ignored: canNotUseMemoryManagementFunctions).
pub type fmi2CallbackAllocateMemory = Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>;
/// `free`-like callback (ignored).
pub type fmi2CallbackFreeMemory = Option<unsafe extern "C" fn(*mut c_void)>;
/// Asynchronous step completion callback (unused).
pub type fmi2StepFinished = Option<unsafe extern "C" fn(fmi2ComponentEnvironment, fmi2Status)>;

/// `fmi2CallbackFunctions`, copied at instantiation.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct fmi2CallbackFunctions {
    /// Logger (may be NULL: then nothing is logged).
    pub logger: fmi2CallbackLogger,
    /// Allocator.
    pub allocateMemory: fmi2CallbackAllocateMemory,
    /// Deallocator.
    pub freeMemory: fmi2CallbackFreeMemory,
    /// Asynchronous step callback.
    pub stepFinished: fmi2StepFinished,
    /// Passed back as the logger's first argument.
    pub componentEnvironment: fmi2ComponentEnvironment,
}

macro_rules! fn_types {
    ($($name:ident = fn($($arg:ty),*) -> $ret:ty;)*) => {
        $(
            #[doc = concat!("`", stringify!($name), "` of `fmi2FunctionTypes.h`.")]
            pub type $name = unsafe extern "C" fn($($arg),*) -> $ret;
        )*
    };
}

type VR = *const fmi2ValueReference;
fn_types! {
    fmi2GetTypesPlatformTYPE = fn() -> *const c_char;
    fmi2GetVersionTYPE = fn() -> *const c_char;
    fmi2SetDebugLoggingTYPE = fn(fmi2Component, fmi2Boolean, usize, *const fmi2String) -> fmi2Status;
    fmi2InstantiateTYPE = fn(fmi2String, fmi2Type, fmi2String, fmi2String, *const fmi2CallbackFunctions, fmi2Boolean, fmi2Boolean) -> fmi2Component;
    fmi2FreeInstanceTYPE = fn(fmi2Component) -> ();
    fmi2SetupExperimentTYPE = fn(fmi2Component, fmi2Boolean, fmi2Real, fmi2Real, fmi2Boolean, fmi2Real) -> fmi2Status;
    fmi2EnterInitializationModeTYPE = fn(fmi2Component) -> fmi2Status;
    fmi2ExitInitializationModeTYPE = fn(fmi2Component) -> fmi2Status;
    fmi2TerminateTYPE = fn(fmi2Component) -> fmi2Status;
    fmi2ResetTYPE = fn(fmi2Component) -> fmi2Status;
    fmi2GetRealTYPE = fn(fmi2Component, VR, usize, *mut fmi2Real) -> fmi2Status;
    fmi2GetIntegerTYPE = fn(fmi2Component, VR, usize, *mut fmi2Integer) -> fmi2Status;
    fmi2GetBooleanTYPE = fn(fmi2Component, VR, usize, *mut fmi2Boolean) -> fmi2Status;
    fmi2GetStringTYPE = fn(fmi2Component, VR, usize, *mut fmi2String) -> fmi2Status;
    fmi2SetRealTYPE = fn(fmi2Component, VR, usize, *const fmi2Real) -> fmi2Status;
    fmi2SetIntegerTYPE = fn(fmi2Component, VR, usize, *const fmi2Integer) -> fmi2Status;
    fmi2SetBooleanTYPE = fn(fmi2Component, VR, usize, *const fmi2Boolean) -> fmi2Status;
    fmi2SetStringTYPE = fn(fmi2Component, VR, usize, *const fmi2String) -> fmi2Status;
    fmi2GetFMUstateTYPE = fn(fmi2Component, *mut fmi2FMUstate) -> fmi2Status;
    fmi2SetFMUstateTYPE = fn(fmi2Component, fmi2FMUstate) -> fmi2Status;
    fmi2FreeFMUstateTYPE = fn(fmi2Component, *mut fmi2FMUstate) -> fmi2Status;
    fmi2SerializedFMUstateSizeTYPE = fn(fmi2Component, fmi2FMUstate, *mut usize) -> fmi2Status;
    fmi2SerializeFMUstateTYPE = fn(fmi2Component, fmi2FMUstate, *mut fmi2Byte, usize) -> fmi2Status;
    fmi2DeSerializeFMUstateTYPE = fn(fmi2Component, *const fmi2Byte, usize, *mut fmi2FMUstate) -> fmi2Status;
    fmi2GetDirectionalDerivativeTYPE = fn(fmi2Component, VR, usize, VR, usize, *const fmi2Real, *mut fmi2Real) -> fmi2Status;
    fmi2SetRealInputDerivativesTYPE = fn(fmi2Component, VR, usize, *const fmi2Integer, *const fmi2Real) -> fmi2Status;
    fmi2GetRealOutputDerivativesTYPE = fn(fmi2Component, VR, usize, *const fmi2Integer, *mut fmi2Real) -> fmi2Status;
    fmi2DoStepTYPE = fn(fmi2Component, fmi2Real, fmi2Real, fmi2Boolean) -> fmi2Status;
    fmi2CancelStepTYPE = fn(fmi2Component) -> fmi2Status;
    fmi2GetStatusTYPE = fn(fmi2Component, fmi2StatusKind, *mut fmi2Status) -> fmi2Status;
    fmi2GetRealStatusTYPE = fn(fmi2Component, fmi2StatusKind, *mut fmi2Real) -> fmi2Status;
    fmi2GetIntegerStatusTYPE = fn(fmi2Component, fmi2StatusKind, *mut fmi2Integer) -> fmi2Status;
    fmi2GetBooleanStatusTYPE = fn(fmi2Component, fmi2StatusKind, *mut fmi2Boolean) -> fmi2Status;
    fmi2GetStringStatusTYPE = fn(fmi2Component, fmi2StatusKind, *mut fmi2String) -> fmi2Status;
}

/// The names of all 34 FMI 2.0 Co-Simulation functions (25 common + 9 CS), as exported.
pub const FMI2_CS_FUNCTIONS: [&str; 34] = [
    "fmi2GetTypesPlatform",
    "fmi2GetVersion",
    "fmi2SetDebugLogging",
    "fmi2Instantiate",
    "fmi2FreeInstance",
    "fmi2SetupExperiment",
    "fmi2EnterInitializationMode",
    "fmi2ExitInitializationMode",
    "fmi2Terminate",
    "fmi2Reset",
    "fmi2GetReal",
    "fmi2GetInteger",
    "fmi2GetBoolean",
    "fmi2GetString",
    "fmi2SetReal",
    "fmi2SetInteger",
    "fmi2SetBoolean",
    "fmi2SetString",
    "fmi2GetFMUstate",
    "fmi2SetFMUstate",
    "fmi2FreeFMUstate",
    "fmi2SerializedFMUstateSize",
    "fmi2SerializeFMUstate",
    "fmi2DeSerializeFMUstate",
    "fmi2GetDirectionalDerivative",
    "fmi2SetRealInputDerivatives",
    "fmi2GetRealOutputDerivatives",
    "fmi2DoStep",
    "fmi2CancelStep",
    "fmi2GetStatus",
    "fmi2GetRealStatus",
    "fmi2GetIntegerStatus",
    "fmi2GetBooleanStatus",
    "fmi2GetStringStatus",
];
