//! Co-Simulation functions (FMI 2.0.4 §4.2.2–§4.2.3): `fmi2DoStep`, `fmi2CancelStep`, the
//! status queries and the (unsupported) input/output derivative functions.

use super::guard::{ffi_fn, non_null, with_instance};
use super::types::*;
use crate::fmu::{FmuError, Mode, Op, Status};

ffi_fn! {
    /// `fmi2SetRealInputDerivatives` (FMI 2.0.4 §4.2.2): not supported
    /// (`canInterpolateInputs="false"`); returns `fmi2Error` with a message.
    fn fmi2SetRealInputDerivatives(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, order: *const fmi2Integer, value: *const fmi2Real) -> fmi2Status {
        let _ = (vr, nvr, order, value);
        // SAFETY: FMI contract on c.
        unsafe {
            with_instance(c, "fmi2SetRealInputDerivatives", |i| {
                i.check(Op::SetRealInputDerivatives, "fmi2SetRealInputDerivatives")?;
                Err(FmuError::Unsupported("input derivatives are not supported (canInterpolateInputs=\"false\")".into()))
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2GetRealOutputDerivatives` (FMI 2.0.4 §4.2.2): not supported
    /// (`maxOutputDerivativeOrder="0"`); returns `fmi2Error` with a message.
    fn fmi2GetRealOutputDerivatives(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, order: *const fmi2Integer, value: *mut fmi2Real) -> fmi2Status {
        let _ = (vr, nvr, order, value);
        // SAFETY: FMI contract on c.
        unsafe {
            with_instance(c, "fmi2GetRealOutputDerivatives", |i| {
                i.check(Op::GetRealOutputDerivatives, "fmi2GetRealOutputDerivatives")?;
                Err(FmuError::Unsupported("output derivatives are not provided (maxOutputDerivativeOrder=\"0\")".into()))
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2DoStep` (FMI 2.0.4 §4.2.2): advances from `currentCommunicationPoint` (checked
    /// against the instance time) by `communicationStepSize` in `ceil(H/max_step)` equal
    /// sub-steps. A failed sub-step returns `fmi2Discard` with the state rolled back to the last
    /// good time (see `fmi2GetRealStatus(fmi2LastSuccessfulTime)`); the instance stays usable.
    fn fmi2DoStep(c: fmi2Component, currentCommunicationPoint: fmi2Real, communicationStepSize: fmi2Real, noSetFMUStatePriorToCurrentPoint: fmi2Boolean) -> fmi2Status {
        let _ = noSetFMUStatePriorToCurrentPoint;
        // SAFETY: FMI contract on c.
        unsafe { with_instance(c, "fmi2DoStep", |i| i.do_step(currentCommunicationPoint, communicationStepSize)) }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2CancelStep` (FMI 2.0.4 §4.2.2): `fmi2DoStep` is synchronous, so there is never a
    /// step to cancel: `fmi2Error` with a message.
    fn fmi2CancelStep(c: fmi2Component) -> fmi2Status {
        // SAFETY: FMI contract on c.
        unsafe {
            with_instance(c, "fmi2CancelStep", |i| {
                if i.mode() == Mode::Fatal {
                    return Err(FmuError::Poisoned);
                }
                Err(FmuError::Unsupported("fmi2DoStep is synchronous (canRunAsynchronuously=\"false\"): there is no step to cancel".into()))
            })
        }
    } ?= fmi2Fatal
}

/// The status kinds a query cannot answer: `fmi2Discard` with a message.
fn not_available(kind: fmi2StatusKind, function: &str) -> FmuError {
    FmuError::Discard(format!(
        "status kind {kind} is not available from {function} (fmi2DoStep is synchronous)"
    ))
}

ffi_fn! {
    /// `fmi2GetStatus` (FMI 2.0.4 §4.2.3): only meaningful for asynchronous steps → `fmi2Discard`.
    fn fmi2GetStatus(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Status) -> fmi2Status {
        // SAFETY: FMI contract on c.
        unsafe {
            with_instance(c, "fmi2GetStatus", |i| {
                i.check(Op::GetStatus, "fmi2GetStatus")?;
                non_null!(value, "value");
                Err(not_available(s, "fmi2GetStatus"))
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2GetRealStatus` (FMI 2.0.4 §4.2.3): `fmi2LastSuccessfulTime` is the end of the last
    /// completed step (after a Discard, the time the state was rolled back to).
    fn fmi2GetRealStatus(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Real) -> fmi2Status {
        // SAFETY: FMI contract on c; value checked for NULL before the write.
        unsafe {
            with_instance(c, "fmi2GetRealStatus", |i| {
                let t = i.last_successful_time()?;
                non_null!(value, "value");
                if s != fmi2LastSuccessfulTime {
                    return Err(not_available(s, "fmi2GetRealStatus"));
                }
                *value = t;
                Ok(Status::Ok)
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2GetIntegerStatus` (FMI 2.0.4 §4.2.3): no integer status kinds → `fmi2Discard`.
    fn fmi2GetIntegerStatus(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Integer) -> fmi2Status {
        // SAFETY: FMI contract on c.
        unsafe {
            with_instance(c, "fmi2GetIntegerStatus", |i| {
                i.check(Op::GetStatus, "fmi2GetIntegerStatus")?;
                non_null!(value, "value");
                Err(not_available(s, "fmi2GetIntegerStatus"))
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2GetBooleanStatus` (FMI 2.0.4 §4.2.3): `fmi2Terminated` is always false (the model
    /// never asks the master to stop).
    fn fmi2GetBooleanStatus(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Boolean) -> fmi2Status {
        // SAFETY: FMI contract on c; value checked for NULL before the write.
        unsafe {
            with_instance(c, "fmi2GetBooleanStatus", |i| {
                let terminated = i.terminated_status()?;
                non_null!(value, "value");
                if s != fmi2Terminated {
                    return Err(not_available(s, "fmi2GetBooleanStatus"));
                }
                *value = if terminated { fmi2True } else { fmi2False };
                Ok(Status::Ok)
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2GetStringStatus` (FMI 2.0.4 §4.2.3): `fmi2PendingStatus` never applies → `fmi2Discard`.
    fn fmi2GetStringStatus(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2String) -> fmi2Status {
        // SAFETY: FMI contract on c.
        unsafe {
            with_instance(c, "fmi2GetStringStatus", |i| {
                i.check(Op::GetStatus, "fmi2GetStringStatus")?;
                non_null!(value, "value");
                Err(not_available(s, "fmi2GetStringStatus"))
            })
        }
    } ?= fmi2Fatal
}
