//! Co-Simulation (FMI 3.0 §4.2): `fmi3DoStep` over the same core step as `fmi2DoStep`, so the
//! FMI 2 and FMI 3 FMUs of a model give bit-identical results.

use super::types::*;
use crate::ffi::guard::{ffi_fn, non_null, with_instance};

ffi_fn! {
    /// `fmi3DoStep`: advances from `currentCommunicationPoint` (checked against the instance
    /// time) by `communicationStepSize` exactly as `fmi2DoStep`; with `earlyReturnAllowed` it
    /// returns early (`earlyReturn`, `lastSuccessfulTime` = that time) when a joint reaches or
    /// leaves a stop or a contact touches or leaves. No event handling, never a request to
    /// terminate: those outputs are false; `lastSuccessfulTime` is the time reached, also after
    /// `fmi3Discard` (the state is left there and the instance usable). A NULL output pointer
    /// is `fmi3Error`, nothing done.
    fn fmi3DoStep(
        instance: fmi3Instance,
        currentCommunicationPoint: fmi3Float64,
        communicationStepSize: fmi3Float64,
        noSetFMUStatePriorToCurrentPoint: fmi3Boolean,
        eventHandlingNeeded: *mut fmi3Boolean,
        terminateSimulation: *mut fmi3Boolean,
        earlyReturn: *mut fmi3Boolean,
        lastSuccessfulTime: *mut fmi3Float64,
    ) -> fmi3Status {
        let _ = noSetFMUStatePriorToCurrentPoint;
        // SAFETY: FMI contract on the instance; each output pointer is checked for NULL before
        // it is written and points to one writable value.
        unsafe {
            with_instance(instance, "fmi3DoStep", |i| {
                non_null!(eventHandlingNeeded, "eventHandlingNeeded");
                non_null!(terminateSimulation, "terminateSimulation");
                non_null!(earlyReturn, "earlyReturn");
                non_null!(lastSuccessfulTime, "lastSuccessfulTime");
                let result = i.do_step3(currentCommunicationPoint, communicationStepSize);
                *eventHandlingNeeded = false;
                *terminateSimulation = false;
                *earlyReturn = matches!(result, Ok((_, true)));
                *lastSuccessfulTime = i.time_reached();
                result.map(|(status, _)| status)
            })
        }
    } ?= fmi3Fatal
}
