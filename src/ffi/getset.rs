//! `fmi2Get*`/`fmi2Set*` (FMI 2.0.4 §2.1.7) and `fmi2GetDirectionalDerivative` (§2.1.9).
//! Sets are all-or-nothing (`Instance::set_real`); gets write the output array only on success.

use super::guard::{ffi_fn, slice, slice_mut, with_instance};
use super::types::*;
use crate::fmu::FmuError;

ffi_fn! {
    /// `fmi2GetReal` (FMI 2.0.4 §2.1.7).
    fn fmi2GetReal(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *mut fmi2Real) -> fmi2Status {
        // SAFETY: FMI contract: vr and value hold nvr elements.
        unsafe {
            with_instance(c, "fmi2GetReal", |i| {
                let vrs = slice(vr, nvr, "vr")?;
                let out = slice_mut(value, nvr, "value")?;
                i.get_real(vrs, out)
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2GetInteger` (FMI 2.0.4 §2.1.7).
    fn fmi2GetInteger(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *mut fmi2Integer) -> fmi2Status {
        // SAFETY: FMI contract: vr and value hold nvr elements.
        unsafe {
            with_instance(c, "fmi2GetInteger", |i| {
                let vrs = slice(vr, nvr, "vr")?;
                let out = slice_mut(value, nvr, "value")?;
                i.get_integer(vrs, out)
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2GetBoolean` (FMI 2.0.4 §2.1.7): triad declares no Boolean variables.
    fn fmi2GetBoolean(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *mut fmi2Boolean) -> fmi2Status {
        // SAFETY: FMI contract: vr and value hold nvr elements.
        unsafe {
            with_instance(c, "fmi2GetBoolean", |i| {
                let vrs = slice(vr, nvr, "vr")?;
                slice_mut(value, nvr, "value")?;
                i.get_other(vrs, true)
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2GetString` (FMI 2.0.4 §2.1.7): triad declares no String variables.
    fn fmi2GetString(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *mut fmi2String) -> fmi2Status {
        // SAFETY: FMI contract: vr and value hold nvr elements.
        unsafe {
            with_instance(c, "fmi2GetString", |i| {
                let vrs = slice(vr, nvr, "vr")?;
                slice_mut(value, nvr, "value")?;
                i.get_other(vrs, false)
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2SetReal` (FMI 2.0.4 §2.1.7): inputs, and parameters as the mode allows; NaN/Inf,
    /// unknown value references and forbidden sets are rejected with nothing changed.
    fn fmi2SetReal(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *const fmi2Real) -> fmi2Status {
        // SAFETY: FMI contract: vr and value hold nvr elements.
        unsafe {
            with_instance(c, "fmi2SetReal", |i| {
                let vrs = slice(vr, nvr, "vr")?;
                let vals = slice(value, nvr, "value")?;
                i.set_real(vrs, vals)
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2SetInteger` (FMI 2.0.4 §2.1.7).
    fn fmi2SetInteger(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *const fmi2Integer) -> fmi2Status {
        // SAFETY: FMI contract: vr and value hold nvr elements.
        unsafe {
            with_instance(c, "fmi2SetInteger", |i| {
                let vrs = slice(vr, nvr, "vr")?;
                let vals = slice(value, nvr, "value")?;
                i.set_integer(vrs, vals)
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2SetBoolean` (FMI 2.0.4 §2.1.7): no Boolean variables.
    fn fmi2SetBoolean(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *const fmi2Boolean) -> fmi2Status {
        // SAFETY: FMI contract: vr and value hold nvr elements.
        unsafe {
            with_instance(c, "fmi2SetBoolean", |i| {
                let vrs = slice(vr, nvr, "vr")?;
                slice(value, nvr, "value")?;
                i.set_other(vrs, true)
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2SetString` (FMI 2.0.4 §2.1.7): no String variables.
    fn fmi2SetString(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *const fmi2String) -> fmi2Status {
        // SAFETY: FMI contract: vr and value hold nvr elements.
        unsafe {
            with_instance(c, "fmi2SetString", |i| {
                let vrs = slice(vr, nvr, "vr")?;
                slice(value, nvr, "value")?;
                i.set_other(vrs, false)
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2GetDirectionalDerivative` (FMI 2.0.4 §2.1.9): not provided
    /// (`providesDirectionalDerivative="false"`); returns `fmi2Error` with a message.
    fn fmi2GetDirectionalDerivative(c: fmi2Component, vUnknown_ref: *const fmi2ValueReference, nUnknown: usize, vKnown_ref: *const fmi2ValueReference, nKnown: usize, dvKnown: *const fmi2Real, dvUnknown: *mut fmi2Real) -> fmi2Status {
        let _ = (vUnknown_ref, nUnknown, vKnown_ref, nKnown, dvKnown, dvUnknown);
        // SAFETY: FMI contract on c.
        unsafe {
            with_instance(c, "fmi2GetDirectionalDerivative", |i| {
                i.check(crate::fmu::Op::GetDirectionalDerivative, "fmi2GetDirectionalDerivative")?;
                Err(FmuError::Unsupported("directional derivatives are not provided (providesDirectionalDerivative=\"false\")".into()))
            })
        }
    } ?= fmi2Fatal
}
