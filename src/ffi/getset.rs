//! `fmi2Get*`/`fmi2Set*` (FMI 2.0.4 §2.1.7) and `fmi2GetDirectionalDerivative` (§2.1.9).
//! Sets are all-or-nothing (`Instance::set_real`); gets write the output array only on success.

use super::guard::{ffi_fn, slice, slice_mut, with_instance};
use super::types::*;

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
    /// `fmi2GetDirectionalDerivative` (FMI 2.0.4 §2.1.9): exact derivatives of outputs and
    /// state derivatives with respect to states and inputs at the current communication point
    /// (`providesDirectionalDerivative="true"` for trees without contact; otherwise
    /// `fmi2Error` with a message). Bad references, NULL arrays and NaN seeds are refused.
    fn fmi2GetDirectionalDerivative(c: fmi2Component, vUnknown_ref: *const fmi2ValueReference, nUnknown: usize, vKnown_ref: *const fmi2ValueReference, nKnown: usize, dvKnown: *const fmi2Real, dvUnknown: *mut fmi2Real) -> fmi2Status {
        // SAFETY: FMI contract: the unknown arrays hold nUnknown and the known ones nKnown elements.
        unsafe {
            with_instance(c, "fmi2GetDirectionalDerivative", |i| {
                let unknowns = slice(vUnknown_ref, nUnknown, "vUnknown_ref")?;
                let knowns = slice(vKnown_ref, nKnown, "vKnown_ref")?;
                let seed = slice(dvKnown, nKnown, "dvKnown")?;
                let out = slice_mut(dvUnknown, nUnknown, "dvUnknown")?;
                i.directional_derivative(unknowns, knowns, seed, out)
            })
        }
    } ?= fmi2Fatal
}
