//! The FMI 3.0 Co-Simulation interface: every function of `fmi3Functions.h` (75), exported
//! beside the `fmi2*` ones from the same library over the same `fmu::Instance`. The
//! conventions of `ffi` hold (no panic crosses the boundary, NULL refused, logging only
//! through the importer's callback); an `fmi3Instance` is the same `Component` pointer.
//! Co-Simulation without Event Mode: every Model Exchange, Scheduled Execution, event, clock
//! and configuration function returns `fmi3Error` with a logged message (`unsupported.rs`).

pub mod cosim;
pub mod getset;
pub mod lifecycle;
pub mod logger;
pub mod state;
pub mod types;
pub mod unsupported;

// every export has exactly the C type transcribed in types.rs
use cosim::*;
use getset::*;
use lifecycle::*;
use state::*;
use types::*;
use unsupported::*;
const _: fmi3GetVersionTYPE = fmi3GetVersion;
const _: fmi3SetDebugLoggingTYPE = fmi3SetDebugLogging;
const _: fmi3InstantiateModelExchangeTYPE = fmi3InstantiateModelExchange;
const _: fmi3InstantiateCoSimulationTYPE = fmi3InstantiateCoSimulation;
const _: fmi3InstantiateScheduledExecutionTYPE = fmi3InstantiateScheduledExecution;
const _: fmi3FreeInstanceTYPE = fmi3FreeInstance;
const _: fmi3EnterInitializationModeTYPE = fmi3EnterInitializationMode;
const _: fmi3ExitInitializationModeTYPE = fmi3ExitInitializationMode;
const _: fmi3EnterEventModeTYPE = fmi3EnterEventMode;
const _: fmi3TerminateTYPE = fmi3Terminate;
const _: fmi3ResetTYPE = fmi3Reset;
const _: fmi3GetFloat32TYPE = fmi3GetFloat32;
const _: fmi3GetFloat64TYPE = fmi3GetFloat64;
const _: fmi3GetInt8TYPE = fmi3GetInt8;
const _: fmi3GetUInt8TYPE = fmi3GetUInt8;
const _: fmi3GetInt16TYPE = fmi3GetInt16;
const _: fmi3GetUInt16TYPE = fmi3GetUInt16;
const _: fmi3GetInt32TYPE = fmi3GetInt32;
const _: fmi3GetUInt32TYPE = fmi3GetUInt32;
const _: fmi3GetInt64TYPE = fmi3GetInt64;
const _: fmi3GetUInt64TYPE = fmi3GetUInt64;
const _: fmi3GetBooleanTYPE = fmi3GetBoolean;
const _: fmi3GetStringTYPE = fmi3GetString;
const _: fmi3GetBinaryTYPE = fmi3GetBinary;
const _: fmi3GetClockTYPE = fmi3GetClock;
const _: fmi3SetFloat32TYPE = fmi3SetFloat32;
const _: fmi3SetFloat64TYPE = fmi3SetFloat64;
const _: fmi3SetInt8TYPE = fmi3SetInt8;
const _: fmi3SetUInt8TYPE = fmi3SetUInt8;
const _: fmi3SetInt16TYPE = fmi3SetInt16;
const _: fmi3SetUInt16TYPE = fmi3SetUInt16;
const _: fmi3SetInt32TYPE = fmi3SetInt32;
const _: fmi3SetUInt32TYPE = fmi3SetUInt32;
const _: fmi3SetInt64TYPE = fmi3SetInt64;
const _: fmi3SetUInt64TYPE = fmi3SetUInt64;
const _: fmi3SetBooleanTYPE = fmi3SetBoolean;
const _: fmi3SetStringTYPE = fmi3SetString;
const _: fmi3SetBinaryTYPE = fmi3SetBinary;
const _: fmi3SetClockTYPE = fmi3SetClock;
const _: fmi3GetNumberOfVariableDependenciesTYPE = fmi3GetNumberOfVariableDependencies;
const _: fmi3GetVariableDependenciesTYPE = fmi3GetVariableDependencies;
const _: fmi3GetFMUStateTYPE = fmi3GetFMUState;
const _: fmi3SetFMUStateTYPE = fmi3SetFMUState;
const _: fmi3FreeFMUStateTYPE = fmi3FreeFMUState;
const _: fmi3SerializedFMUStateSizeTYPE = fmi3SerializedFMUStateSize;
const _: fmi3SerializeFMUStateTYPE = fmi3SerializeFMUState;
const _: fmi3DeserializeFMUStateTYPE = fmi3DeserializeFMUState;
const _: fmi3GetDirectionalDerivativeTYPE = fmi3GetDirectionalDerivative;
const _: fmi3GetAdjointDerivativeTYPE = fmi3GetAdjointDerivative;
const _: fmi3EnterConfigurationModeTYPE = fmi3EnterConfigurationMode;
const _: fmi3ExitConfigurationModeTYPE = fmi3ExitConfigurationMode;
const _: fmi3GetIntervalDecimalTYPE = fmi3GetIntervalDecimal;
const _: fmi3GetIntervalFractionTYPE = fmi3GetIntervalFraction;
const _: fmi3GetShiftDecimalTYPE = fmi3GetShiftDecimal;
const _: fmi3GetShiftFractionTYPE = fmi3GetShiftFraction;
const _: fmi3SetIntervalDecimalTYPE = fmi3SetIntervalDecimal;
const _: fmi3SetIntervalFractionTYPE = fmi3SetIntervalFraction;
const _: fmi3SetShiftDecimalTYPE = fmi3SetShiftDecimal;
const _: fmi3SetShiftFractionTYPE = fmi3SetShiftFraction;
const _: fmi3EvaluateDiscreteStatesTYPE = fmi3EvaluateDiscreteStates;
const _: fmi3UpdateDiscreteStatesTYPE = fmi3UpdateDiscreteStates;
const _: fmi3EnterContinuousTimeModeTYPE = fmi3EnterContinuousTimeMode;
const _: fmi3CompletedIntegratorStepTYPE = fmi3CompletedIntegratorStep;
const _: fmi3SetTimeTYPE = fmi3SetTime;
const _: fmi3SetContinuousStatesTYPE = fmi3SetContinuousStates;
const _: fmi3GetContinuousStateDerivativesTYPE = fmi3GetContinuousStateDerivatives;
const _: fmi3GetEventIndicatorsTYPE = fmi3GetEventIndicators;
const _: fmi3GetContinuousStatesTYPE = fmi3GetContinuousStates;
const _: fmi3GetNominalsOfContinuousStatesTYPE = fmi3GetNominalsOfContinuousStates;
const _: fmi3GetNumberOfEventIndicatorsTYPE = fmi3GetNumberOfEventIndicators;
const _: fmi3GetNumberOfContinuousStatesTYPE = fmi3GetNumberOfContinuousStates;
const _: fmi3EnterStepModeTYPE = fmi3EnterStepMode;
const _: fmi3GetOutputDerivativesTYPE = fmi3GetOutputDerivatives;
const _: fmi3DoStepTYPE = fmi3DoStep;
const _: fmi3ActivateModelPartitionTYPE = fmi3ActivateModelPartition;
