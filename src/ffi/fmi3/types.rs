//! FMI 3.0 C types, transcribed by hand from `fmi3PlatformTypes.h` and `fmi3FunctionTypes.h`
//! (FMI 3.0). `fmi3Status` is the `int`-sized C enum, the same codes as `fmi2Status`, so the
//! FMI 2 guards serve both. The `fmi3*TYPE` function types are checked against the exports in
//! `mod.rs`.
#![allow(non_camel_case_types, non_upper_case_globals)]

use std::ffi::{c_char, c_int, c_void};

/// Opaque instance pointer (`typedef void* fmi3Instance`).
pub type fmi3Instance = *mut c_void;
/// Importer's environment pointer, passed back to the callbacks.
pub type fmi3InstanceEnvironment = *mut c_void;
/// Opaque FMU state pointer.
pub type fmi3FMUState = *mut c_void;
/// Value reference (`uint32_t`).
pub type fmi3ValueReference = u32;
/// `float`.
pub type fmi3Float32 = f32;
/// `double`.
pub type fmi3Float64 = f64;
/// `int8_t`.
pub type fmi3Int8 = i8;
/// `uint8_t`.
pub type fmi3UInt8 = u8;
/// `int16_t`.
pub type fmi3Int16 = i16;
/// `uint16_t`.
pub type fmi3UInt16 = u16;
/// `int32_t`.
pub type fmi3Int32 = i32;
/// `uint32_t`.
pub type fmi3UInt32 = u32;
/// `int64_t`.
pub type fmi3Int64 = i64;
/// `uint64_t`.
pub type fmi3UInt64 = u64;
/// C `bool`.
pub type fmi3Boolean = bool;
/// Character.
pub type fmi3Char = c_char;
/// NUL-terminated UTF-8 string.
pub type fmi3String = *const fmi3Char;
/// Byte (`uint8_t`).
pub type fmi3Byte = u8;
/// Binary data (length passed separately).
pub type fmi3Binary = *const fmi3Byte;
/// Clock (C `bool`).
pub type fmi3Clock = bool;

/// `fmi3True`.
pub const fmi3True: fmi3Boolean = true;
/// `fmi3False`.
pub const fmi3False: fmi3Boolean = false;

/// `fmi3Status` (a C enum, `int` sized).
pub type fmi3Status = c_int;
/// All well.
pub const fmi3OK: fmi3Status = 0;
/// Something may be wrong; computation continues.
pub const fmi3Warning: fmi3Status = 1;
/// The step or value was not accepted.
pub const fmi3Discard: fmi3Status = 2;
/// This instance cannot continue without reset or restore.
pub const fmi3Error: fmi3Status = 3;
/// Everything is corrupted.
pub const fmi3Fatal: fmi3Status = 4;

/// `fmi3DependencyKind` (C enum).
pub type fmi3DependencyKind = c_int;
/// `fmi3IntervalQualifier` (C enum).
pub type fmi3IntervalQualifier = c_int;

/// `fmi3LogMessageCallback(instanceEnvironment, status, category, message)`: not variadic.
pub type fmi3LogMessageCallback =
    Option<unsafe extern "C" fn(fmi3InstanceEnvironment, fmi3Status, fmi3String, fmi3String)>;
/// `fmi3ClockUpdateCallback` (Scheduled Execution; never called).
pub type fmi3ClockUpdateCallback = Option<unsafe extern "C" fn(fmi3InstanceEnvironment)>;
/// `fmi3IntermediateUpdateCallback` (never called: `providesIntermediateUpdate` is false).
pub type fmi3IntermediateUpdateCallback = Option<
    unsafe extern "C" fn(
        fmi3InstanceEnvironment,
        fmi3Float64,
        fmi3Boolean,
        fmi3Boolean,
        fmi3Boolean,
        fmi3Boolean,
        *mut fmi3Boolean,
        *mut fmi3Float64,
    ),
>;
/// `fmi3LockPreemptionCallback` (Scheduled Execution; never called).
pub type fmi3LockPreemptionCallback = Option<unsafe extern "C" fn()>;
/// `fmi3UnlockPreemptionCallback` (Scheduled Execution; never called).
pub type fmi3UnlockPreemptionCallback = Option<unsafe extern "C" fn()>;

macro_rules! fn_types {
    ($($name:ident = fn($($arg:ty),*) -> $ret:ty;)*) => {
        $(
            #[doc = concat!("`", stringify!($name), "` of `fmi3FunctionTypes.h`.")]
            pub type $name = unsafe extern "C" fn($($arg),*) -> $ret;
        )*
    };
}

type I = fmi3Instance;
type S = fmi3Status;
type VR = *const fmi3ValueReference;
type B = fmi3Boolean;
fn_types! {
    fmi3GetVersionTYPE = fn() -> *const c_char;
    fmi3SetDebugLoggingTYPE = fn(I, B, usize, *const fmi3String) -> S;
    fmi3InstantiateModelExchangeTYPE = fn(fmi3String, fmi3String, fmi3String, B, B, fmi3InstanceEnvironment, fmi3LogMessageCallback) -> I;
    fmi3InstantiateCoSimulationTYPE = fn(fmi3String, fmi3String, fmi3String, B, B, B, B, VR, usize, fmi3InstanceEnvironment, fmi3LogMessageCallback, fmi3IntermediateUpdateCallback) -> I;
    fmi3InstantiateScheduledExecutionTYPE = fn(fmi3String, fmi3String, fmi3String, B, B, fmi3InstanceEnvironment, fmi3LogMessageCallback, fmi3ClockUpdateCallback, fmi3LockPreemptionCallback, fmi3UnlockPreemptionCallback) -> I;
    fmi3FreeInstanceTYPE = fn(I) -> ();
    fmi3EnterInitializationModeTYPE = fn(I, B, f64, f64, B, f64) -> S;
    fmi3ExitInitializationModeTYPE = fn(I) -> S;
    fmi3EnterEventModeTYPE = fn(I) -> S;
    fmi3TerminateTYPE = fn(I) -> S;
    fmi3ResetTYPE = fn(I) -> S;
    fmi3GetFloat32TYPE = fn(I, VR, usize, *mut fmi3Float32, usize) -> S;
    fmi3GetFloat64TYPE = fn(I, VR, usize, *mut fmi3Float64, usize) -> S;
    fmi3GetInt8TYPE = fn(I, VR, usize, *mut fmi3Int8, usize) -> S;
    fmi3GetUInt8TYPE = fn(I, VR, usize, *mut fmi3UInt8, usize) -> S;
    fmi3GetInt16TYPE = fn(I, VR, usize, *mut fmi3Int16, usize) -> S;
    fmi3GetUInt16TYPE = fn(I, VR, usize, *mut fmi3UInt16, usize) -> S;
    fmi3GetInt32TYPE = fn(I, VR, usize, *mut fmi3Int32, usize) -> S;
    fmi3GetUInt32TYPE = fn(I, VR, usize, *mut fmi3UInt32, usize) -> S;
    fmi3GetInt64TYPE = fn(I, VR, usize, *mut fmi3Int64, usize) -> S;
    fmi3GetUInt64TYPE = fn(I, VR, usize, *mut fmi3UInt64, usize) -> S;
    fmi3GetBooleanTYPE = fn(I, VR, usize, *mut fmi3Boolean, usize) -> S;
    fmi3GetStringTYPE = fn(I, VR, usize, *mut fmi3String, usize) -> S;
    fmi3GetBinaryTYPE = fn(I, VR, usize, *mut usize, *mut fmi3Binary, usize) -> S;
    fmi3GetClockTYPE = fn(I, VR, usize, *mut fmi3Clock) -> S;
    fmi3SetFloat32TYPE = fn(I, VR, usize, *const fmi3Float32, usize) -> S;
    fmi3SetFloat64TYPE = fn(I, VR, usize, *const fmi3Float64, usize) -> S;
    fmi3SetInt8TYPE = fn(I, VR, usize, *const fmi3Int8, usize) -> S;
    fmi3SetUInt8TYPE = fn(I, VR, usize, *const fmi3UInt8, usize) -> S;
    fmi3SetInt16TYPE = fn(I, VR, usize, *const fmi3Int16, usize) -> S;
    fmi3SetUInt16TYPE = fn(I, VR, usize, *const fmi3UInt16, usize) -> S;
    fmi3SetInt32TYPE = fn(I, VR, usize, *const fmi3Int32, usize) -> S;
    fmi3SetUInt32TYPE = fn(I, VR, usize, *const fmi3UInt32, usize) -> S;
    fmi3SetInt64TYPE = fn(I, VR, usize, *const fmi3Int64, usize) -> S;
    fmi3SetUInt64TYPE = fn(I, VR, usize, *const fmi3UInt64, usize) -> S;
    fmi3SetBooleanTYPE = fn(I, VR, usize, *const fmi3Boolean, usize) -> S;
    fmi3SetStringTYPE = fn(I, VR, usize, *const fmi3String, usize) -> S;
    fmi3SetBinaryTYPE = fn(I, VR, usize, *const usize, *const fmi3Binary, usize) -> S;
    fmi3SetClockTYPE = fn(I, VR, usize, *const fmi3Clock) -> S;
    fmi3GetNumberOfVariableDependenciesTYPE = fn(I, fmi3ValueReference, *mut usize) -> S;
    fmi3GetVariableDependenciesTYPE = fn(I, fmi3ValueReference, *mut usize, *mut fmi3ValueReference, *mut usize, *mut fmi3DependencyKind, usize) -> S;
    fmi3GetFMUStateTYPE = fn(I, *mut fmi3FMUState) -> S;
    fmi3SetFMUStateTYPE = fn(I, fmi3FMUState) -> S;
    fmi3FreeFMUStateTYPE = fn(I, *mut fmi3FMUState) -> S;
    fmi3SerializedFMUStateSizeTYPE = fn(I, fmi3FMUState, *mut usize) -> S;
    fmi3SerializeFMUStateTYPE = fn(I, fmi3FMUState, *mut fmi3Byte, usize) -> S;
    fmi3DeserializeFMUStateTYPE = fn(I, *const fmi3Byte, usize, *mut fmi3FMUState) -> S;
    fmi3GetDirectionalDerivativeTYPE = fn(I, VR, usize, VR, usize, *const f64, usize, *mut f64, usize) -> S;
    fmi3GetAdjointDerivativeTYPE = fn(I, VR, usize, VR, usize, *const f64, usize, *mut f64, usize) -> S;
    fmi3EnterConfigurationModeTYPE = fn(I) -> S;
    fmi3ExitConfigurationModeTYPE = fn(I) -> S;
    fmi3GetIntervalDecimalTYPE = fn(I, VR, usize, *mut f64, *mut fmi3IntervalQualifier) -> S;
    fmi3GetIntervalFractionTYPE = fn(I, VR, usize, *mut u64, *mut u64, *mut fmi3IntervalQualifier) -> S;
    fmi3GetShiftDecimalTYPE = fn(I, VR, usize, *mut f64) -> S;
    fmi3GetShiftFractionTYPE = fn(I, VR, usize, *mut u64, *mut u64) -> S;
    fmi3SetIntervalDecimalTYPE = fn(I, VR, usize, *const f64) -> S;
    fmi3SetIntervalFractionTYPE = fn(I, VR, usize, *const u64, *const u64) -> S;
    fmi3SetShiftDecimalTYPE = fn(I, VR, usize, *const f64) -> S;
    fmi3SetShiftFractionTYPE = fn(I, VR, usize, *const u64, *const u64) -> S;
    fmi3EvaluateDiscreteStatesTYPE = fn(I) -> S;
    fmi3UpdateDiscreteStatesTYPE = fn(I, *mut B, *mut B, *mut B, *mut B, *mut B, *mut f64) -> S;
    fmi3EnterContinuousTimeModeTYPE = fn(I) -> S;
    fmi3CompletedIntegratorStepTYPE = fn(I, B, *mut B, *mut B) -> S;
    fmi3SetTimeTYPE = fn(I, f64) -> S;
    fmi3SetContinuousStatesTYPE = fn(I, *const f64, usize) -> S;
    fmi3GetContinuousStateDerivativesTYPE = fn(I, *mut f64, usize) -> S;
    fmi3GetEventIndicatorsTYPE = fn(I, *mut f64, usize) -> S;
    fmi3GetContinuousStatesTYPE = fn(I, *mut f64, usize) -> S;
    fmi3GetNominalsOfContinuousStatesTYPE = fn(I, *mut f64, usize) -> S;
    fmi3GetNumberOfEventIndicatorsTYPE = fn(I, *mut usize) -> S;
    fmi3GetNumberOfContinuousStatesTYPE = fn(I, *mut usize) -> S;
    fmi3EnterStepModeTYPE = fn(I) -> S;
    fmi3GetOutputDerivativesTYPE = fn(I, VR, usize, *const fmi3Int32, *mut f64, usize) -> S;
    fmi3DoStepTYPE = fn(I, f64, f64, B, *mut B, *mut B, *mut B, *mut f64) -> S;
    fmi3ActivateModelPartitionTYPE = fn(I, fmi3ValueReference, f64) -> S;
}

/// The names of all 75 functions of `fmi3Functions.h`, as exported.
pub const FMI3_FUNCTIONS: [&str; 75] = [
    "fmi3GetVersion",
    "fmi3SetDebugLogging",
    "fmi3InstantiateModelExchange",
    "fmi3InstantiateCoSimulation",
    "fmi3InstantiateScheduledExecution",
    "fmi3FreeInstance",
    "fmi3EnterInitializationMode",
    "fmi3ExitInitializationMode",
    "fmi3EnterEventMode",
    "fmi3Terminate",
    "fmi3Reset",
    "fmi3GetFloat32",
    "fmi3GetFloat64",
    "fmi3GetInt8",
    "fmi3GetUInt8",
    "fmi3GetInt16",
    "fmi3GetUInt16",
    "fmi3GetInt32",
    "fmi3GetUInt32",
    "fmi3GetInt64",
    "fmi3GetUInt64",
    "fmi3GetBoolean",
    "fmi3GetString",
    "fmi3GetBinary",
    "fmi3GetClock",
    "fmi3SetFloat32",
    "fmi3SetFloat64",
    "fmi3SetInt8",
    "fmi3SetUInt8",
    "fmi3SetInt16",
    "fmi3SetUInt16",
    "fmi3SetInt32",
    "fmi3SetUInt32",
    "fmi3SetInt64",
    "fmi3SetUInt64",
    "fmi3SetBoolean",
    "fmi3SetString",
    "fmi3SetBinary",
    "fmi3SetClock",
    "fmi3GetNumberOfVariableDependencies",
    "fmi3GetVariableDependencies",
    "fmi3GetFMUState",
    "fmi3SetFMUState",
    "fmi3FreeFMUState",
    "fmi3SerializedFMUStateSize",
    "fmi3SerializeFMUState",
    "fmi3DeserializeFMUState",
    "fmi3GetDirectionalDerivative",
    "fmi3GetAdjointDerivative",
    "fmi3EnterConfigurationMode",
    "fmi3ExitConfigurationMode",
    "fmi3GetIntervalDecimal",
    "fmi3GetIntervalFraction",
    "fmi3GetShiftDecimal",
    "fmi3GetShiftFraction",
    "fmi3SetIntervalDecimal",
    "fmi3SetIntervalFraction",
    "fmi3SetShiftDecimal",
    "fmi3SetShiftFraction",
    "fmi3EvaluateDiscreteStates",
    "fmi3UpdateDiscreteStates",
    "fmi3EnterContinuousTimeMode",
    "fmi3CompletedIntegratorStep",
    "fmi3SetTime",
    "fmi3SetContinuousStates",
    "fmi3GetContinuousStateDerivatives",
    "fmi3GetEventIndicators",
    "fmi3GetContinuousStates",
    "fmi3GetNominalsOfContinuousStates",
    "fmi3GetNumberOfEventIndicators",
    "fmi3GetNumberOfContinuousStates",
    "fmi3EnterStepMode",
    "fmi3GetOutputDerivatives",
    "fmi3DoStep",
    "fmi3ActivateModelPartition",
];
