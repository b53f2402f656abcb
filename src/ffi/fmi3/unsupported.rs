//! The functions of `fmi3Functions.h` this Co-Simulation FMU does not provide: Model Exchange,
//! Scheduled Execution, Event Mode, clocks, Configuration Mode, variable dependencies, output
//! derivatives. Each
//! is exported (importers such as fmpy load every symbol) and returns `fmi3Error` with a
//! message naming the function and why; the instance stays usable. No argument but the
//! instance is read.

use super::types::*;
use crate::ffi::guard::{ffi_fn, with_instance};
use crate::fmu::{FmuError, Instance, Mode, Status};

const NO_EVENT_MODE: &str = "this FMU has no Event Mode (hasEventMode=\"false\")";
const CS_ONLY: &str = "this FMU provides Co-Simulation only (a Model Exchange function)";
const NO_CLOCKS: &str = "this FMU has no clocks";
const NO_CONFIGURATION: &str = "this FMU has no structural parameters, so no Configuration Mode";
const NO_DEPENDENCIES: &str =
    "variable dependencies are not provided (providesPerElementDependencies=\"false\")";

/// The refusal: `fmi3Error` with `why` (after a panic, the poisoned instance's message).
fn refuse(i: &Instance, why: &str) -> Result<Status, FmuError> {
    if i.mode() == Mode::Fatal {
        return Err(FmuError::Poisoned);
    }
    Err(FmuError::Unsupported(why.to_string()))
}

macro_rules! unsupported {
    ($($name:ident($($arg:ident: $ty:ty),*) => $why:expr;)*) => {
        $(
            ffi_fn! {
                #[doc = concat!("`", stringify!($name), "`: not provided; `fmi3Error` with a logged message.")]
                fn $name(instance: fmi3Instance $(, $arg: $ty)*) -> fmi3Status {
                    let _ = ($($arg,)*);
                    // SAFETY: FMI contract on the instance; no other argument is read.
                    unsafe { with_instance(instance, stringify!($name), |i| refuse(i, $why)) }
                } ?= fmi3Fatal
            }
        )*
    };
}

type VR = *const fmi3ValueReference;

unsupported! {
    fmi3EnterEventMode() => NO_EVENT_MODE;
    fmi3EvaluateDiscreteStates() => NO_EVENT_MODE;
    fmi3UpdateDiscreteStates(discreteStatesNeedUpdate: *mut fmi3Boolean, terminateSimulation: *mut fmi3Boolean, nominalsOfContinuousStatesChanged: *mut fmi3Boolean, valuesOfContinuousStatesChanged: *mut fmi3Boolean, nextEventTimeDefined: *mut fmi3Boolean, nextEventTime: *mut fmi3Float64) => NO_EVENT_MODE;
    fmi3EnterStepMode() => "this FMU has no Event Mode; it is in Step Mode from fmi3ExitInitializationMode on";
    fmi3GetOutputDerivatives(valueReferences: VR, nValueReferences: usize, orders: *const fmi3Int32, values: *mut fmi3Float64, nValues: usize) => "output derivatives are not provided (maxOutputDerivativeOrder=\"0\")";
    fmi3EnterConfigurationMode() => NO_CONFIGURATION;
    fmi3ExitConfigurationMode() => NO_CONFIGURATION;
    fmi3GetNumberOfVariableDependencies(valueReference: fmi3ValueReference, nDependencies: *mut usize) => NO_DEPENDENCIES;
    fmi3GetVariableDependencies(dependent: fmi3ValueReference, elementIndicesOfDependent: *mut usize, independents: *mut fmi3ValueReference, elementIndicesOfIndependents: *mut usize, dependencyKinds: *mut fmi3DependencyKind, nDependencies: usize) => NO_DEPENDENCIES;
    fmi3GetIntervalDecimal(valueReferences: VR, nValueReferences: usize, intervals: *mut fmi3Float64, qualifiers: *mut fmi3IntervalQualifier) => NO_CLOCKS;
    fmi3GetIntervalFraction(valueReferences: VR, nValueReferences: usize, counters: *mut fmi3UInt64, resolutions: *mut fmi3UInt64, qualifiers: *mut fmi3IntervalQualifier) => NO_CLOCKS;
    fmi3GetShiftDecimal(valueReferences: VR, nValueReferences: usize, shifts: *mut fmi3Float64) => NO_CLOCKS;
    fmi3GetShiftFraction(valueReferences: VR, nValueReferences: usize, counters: *mut fmi3UInt64, resolutions: *mut fmi3UInt64) => NO_CLOCKS;
    fmi3SetIntervalDecimal(valueReferences: VR, nValueReferences: usize, intervals: *const fmi3Float64) => NO_CLOCKS;
    fmi3SetIntervalFraction(valueReferences: VR, nValueReferences: usize, counters: *const fmi3UInt64, resolutions: *const fmi3UInt64) => NO_CLOCKS;
    fmi3SetShiftDecimal(valueReferences: VR, nValueReferences: usize, shifts: *const fmi3Float64) => NO_CLOCKS;
    fmi3SetShiftFraction(valueReferences: VR, nValueReferences: usize, counters: *const fmi3UInt64, resolutions: *const fmi3UInt64) => NO_CLOCKS;
    fmi3EnterContinuousTimeMode() => CS_ONLY;
    fmi3CompletedIntegratorStep(noSetFMUStatePriorToCurrentPoint: fmi3Boolean, enterEventMode: *mut fmi3Boolean, terminateSimulation: *mut fmi3Boolean) => CS_ONLY;
    fmi3SetTime(time: fmi3Float64) => CS_ONLY;
    fmi3SetContinuousStates(continuousStates: *const fmi3Float64, nContinuousStates: usize) => CS_ONLY;
    fmi3GetContinuousStateDerivatives(derivatives: *mut fmi3Float64, nContinuousStates: usize) => CS_ONLY;
    fmi3GetEventIndicators(eventIndicators: *mut fmi3Float64, nEventIndicators: usize) => CS_ONLY;
    fmi3GetContinuousStates(continuousStates: *mut fmi3Float64, nContinuousStates: usize) => CS_ONLY;
    fmi3GetNominalsOfContinuousStates(nominals: *mut fmi3Float64, nContinuousStates: usize) => CS_ONLY;
    fmi3GetNumberOfEventIndicators(nEventIndicators: *mut usize) => CS_ONLY;
    fmi3GetNumberOfContinuousStates(nContinuousStates: *mut usize) => CS_ONLY;
    fmi3ActivateModelPartition(clockReference: fmi3ValueReference, activationTime: fmi3Float64) => "Scheduled Execution is not provided";
}
