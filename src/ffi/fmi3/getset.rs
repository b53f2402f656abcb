//! `fmi3Get*`/`fmi3Set*` (FMI 3.0 §2.3.5) by FMI 3 value reference (`variables::fmi3`):
//! `nValues` must be the sum of the variables' sizes, an array's values are row-major, value
//! reference 0 is `time` (Float64, read only). Float64 is the table's Real variables, Int32
//! its Integer ones; there is no variable of any other type, so their get/set accept only an
//! empty list. Sets are all-or-nothing; gets write the output array only on success.

use super::types::*;
use crate::ffi::guard::{ffi_fn, slice, slice_mut, with_instance};

ffi_fn! {
    /// `fmi3GetFloat64`.
    fn fmi3GetFloat64(instance: fmi3Instance, valueReferences: *const fmi3ValueReference, nValueReferences: usize, values: *mut fmi3Float64, nValues: usize) -> fmi3Status {
        // SAFETY: FMI contract: the arrays hold nValueReferences and nValues elements.
        unsafe {
            with_instance(instance, "fmi3GetFloat64", |i| {
                let vrs = slice(valueReferences, nValueReferences, "valueReferences")?;
                let out = slice_mut(values, nValues, "values")?;
                i.get_float64(vrs, out)
            })
        }
    } ?= fmi3Fatal
}

ffi_fn! {
    /// `fmi3SetFloat64`: inputs, and parameters as the state allows; NaN/Inf, unknown value
    /// references, `time`, a wrong `nValues` and forbidden sets are refused, nothing changed.
    fn fmi3SetFloat64(instance: fmi3Instance, valueReferences: *const fmi3ValueReference, nValueReferences: usize, values: *const fmi3Float64, nValues: usize) -> fmi3Status {
        // SAFETY: FMI contract: the arrays hold nValueReferences and nValues elements.
        unsafe {
            with_instance(instance, "fmi3SetFloat64", |i| {
                let vrs = slice(valueReferences, nValueReferences, "valueReferences")?;
                let vals = slice(values, nValues, "values")?;
                i.set_float64(vrs, vals)
            })
        }
    } ?= fmi3Fatal
}

ffi_fn! {
    /// `fmi3GetInt32`: the solver's integer parameters.
    fn fmi3GetInt32(instance: fmi3Instance, valueReferences: *const fmi3ValueReference, nValueReferences: usize, values: *mut fmi3Int32, nValues: usize) -> fmi3Status {
        // SAFETY: FMI contract: the arrays hold nValueReferences and nValues elements.
        unsafe {
            with_instance(instance, "fmi3GetInt32", |i| {
                let vrs = slice(valueReferences, nValueReferences, "valueReferences")?;
                let out = slice_mut(values, nValues, "values")?;
                i.get_int32(vrs, out)
            })
        }
    } ?= fmi3Fatal
}

ffi_fn! {
    /// `fmi3SetInt32`.
    fn fmi3SetInt32(instance: fmi3Instance, valueReferences: *const fmi3ValueReference, nValueReferences: usize, values: *const fmi3Int32, nValues: usize) -> fmi3Status {
        // SAFETY: FMI contract: the arrays hold nValueReferences and nValues elements.
        unsafe {
            with_instance(instance, "fmi3SetInt32", |i| {
                let vrs = slice(valueReferences, nValueReferences, "valueReferences")?;
                let vals = slice(values, nValues, "values")?;
                i.set_int32(vrs, vals)
            })
        }
    } ?= fmi3Fatal
}

/// Get and set of the FMI 3 types this FMU has no variables of: OK for no value references,
/// `fmi3Error` for any.
macro_rules! absent_type {
    ($($get:ident, $set:ident, $ty:ty, $name:literal;)*) => {
        $(
            ffi_fn! {
                #[doc = concat!("`", stringify!($get), "`: there are no ", $name, " variables.")]
                fn $get(instance: fmi3Instance, valueReferences: *const fmi3ValueReference, nValueReferences: usize, values: *mut $ty, nValues: usize) -> fmi3Status {
                    let _ = (values, nValues);
                    // SAFETY: FMI contract: valueReferences holds nValueReferences elements.
                    unsafe {
                        with_instance(instance, stringify!($get), |i| {
                            let vrs = slice(valueReferences, nValueReferences, "valueReferences")?;
                            i.access_absent_type(false, vrs, $name, stringify!($get))
                        })
                    }
                } ?= fmi3Fatal
            }

            ffi_fn! {
                #[doc = concat!("`", stringify!($set), "`: there are no ", $name, " variables.")]
                fn $set(instance: fmi3Instance, valueReferences: *const fmi3ValueReference, nValueReferences: usize, values: *const $ty, nValues: usize) -> fmi3Status {
                    let _ = (values, nValues);
                    // SAFETY: FMI contract: valueReferences holds nValueReferences elements.
                    unsafe {
                        with_instance(instance, stringify!($set), |i| {
                            let vrs = slice(valueReferences, nValueReferences, "valueReferences")?;
                            i.access_absent_type(true, vrs, $name, stringify!($set))
                        })
                    }
                } ?= fmi3Fatal
            }
        )*
    };
}

absent_type! {
    fmi3GetFloat32, fmi3SetFloat32, fmi3Float32, "Float32";
    fmi3GetInt8, fmi3SetInt8, fmi3Int8, "Int8";
    fmi3GetUInt8, fmi3SetUInt8, fmi3UInt8, "UInt8";
    fmi3GetInt16, fmi3SetInt16, fmi3Int16, "Int16";
    fmi3GetUInt16, fmi3SetUInt16, fmi3UInt16, "UInt16";
    fmi3GetUInt32, fmi3SetUInt32, fmi3UInt32, "UInt32";
    fmi3GetInt64, fmi3SetInt64, fmi3Int64, "Int64";
    fmi3GetUInt64, fmi3SetUInt64, fmi3UInt64, "UInt64";
    fmi3GetBoolean, fmi3SetBoolean, fmi3Boolean, "Boolean";
    fmi3GetString, fmi3SetString, fmi3String, "String";
}

ffi_fn! {
    /// `fmi3GetBinary`: there are no Binary variables.
    fn fmi3GetBinary(instance: fmi3Instance, valueReferences: *const fmi3ValueReference, nValueReferences: usize, valueSizes: *mut usize, values: *mut fmi3Binary, nValues: usize) -> fmi3Status {
        let _ = (valueSizes, values, nValues);
        // SAFETY: FMI contract: valueReferences holds nValueReferences elements.
        unsafe {
            with_instance(instance, "fmi3GetBinary", |i| {
                let vrs = slice(valueReferences, nValueReferences, "valueReferences")?;
                i.access_absent_type(false, vrs, "Binary", "fmi3GetBinary")
            })
        }
    } ?= fmi3Fatal
}

ffi_fn! {
    /// `fmi3SetBinary`: there are no Binary variables.
    fn fmi3SetBinary(instance: fmi3Instance, valueReferences: *const fmi3ValueReference, nValueReferences: usize, valueSizes: *const usize, values: *const fmi3Binary, nValues: usize) -> fmi3Status {
        let _ = (valueSizes, values, nValues);
        // SAFETY: FMI contract: valueReferences holds nValueReferences elements.
        unsafe {
            with_instance(instance, "fmi3SetBinary", |i| {
                let vrs = slice(valueReferences, nValueReferences, "valueReferences")?;
                i.access_absent_type(true, vrs, "Binary", "fmi3SetBinary")
            })
        }
    } ?= fmi3Fatal
}

ffi_fn! {
    /// `fmi3GetClock`: there are no clocks.
    fn fmi3GetClock(instance: fmi3Instance, valueReferences: *const fmi3ValueReference, nValueReferences: usize, values: *mut fmi3Clock) -> fmi3Status {
        let _ = values;
        // SAFETY: FMI contract: valueReferences holds nValueReferences elements.
        unsafe {
            with_instance(instance, "fmi3GetClock", |i| {
                let vrs = slice(valueReferences, nValueReferences, "valueReferences")?;
                i.access_absent_type(false, vrs, "Clock", "fmi3GetClock")
            })
        }
    } ?= fmi3Fatal
}

ffi_fn! {
    /// `fmi3SetClock`: there are no clocks.
    fn fmi3SetClock(instance: fmi3Instance, valueReferences: *const fmi3ValueReference, nValueReferences: usize, values: *const fmi3Clock) -> fmi3Status {
        let _ = values;
        // SAFETY: FMI contract: valueReferences holds nValueReferences elements.
        unsafe {
            with_instance(instance, "fmi3SetClock", |i| {
                let vrs = slice(valueReferences, nValueReferences, "valueReferences")?;
                i.access_absent_type(true, vrs, "Clock", "fmi3SetClock")
            })
        }
    } ?= fmi3Fatal
}

ffi_fn! {
    /// `fmi3GetDirectionalDerivative`: exact `sensitivity = J seed` at the current
    /// communication point (knowns: states and inputs; unknowns: outputs and state derivatives).
    fn fmi3GetDirectionalDerivative(instance: fmi3Instance, unknowns: *const fmi3ValueReference, nUnknowns: usize, knowns: *const fmi3ValueReference, nKnowns: usize, seed: *const fmi3Float64, nSeed: usize, sensitivity: *mut fmi3Float64, nSensitivity: usize) -> fmi3Status {
        // SAFETY: FMI contract: the arrays hold nUnknowns, nKnowns, nSeed and nSensitivity elements.
        unsafe {
            with_instance(instance, "fmi3GetDirectionalDerivative", |i| {
                let u = slice(unknowns, nUnknowns, "unknowns")?;
                let k = slice(knowns, nKnowns, "knowns")?;
                let s = slice(seed, nSeed, "seed")?;
                let out = slice_mut(sensitivity, nSensitivity, "sensitivity")?;
                i.directional_derivative3(u, k, s, out)
            })
        }
    } ?= fmi3Fatal
}

ffi_fn! {
    /// `fmi3GetAdjointDerivative`: exact `sensitivity = Jᵀ seed` at the current communication
    /// point.
    fn fmi3GetAdjointDerivative(instance: fmi3Instance, unknowns: *const fmi3ValueReference, nUnknowns: usize, knowns: *const fmi3ValueReference, nKnowns: usize, seed: *const fmi3Float64, nSeed: usize, sensitivity: *mut fmi3Float64, nSensitivity: usize) -> fmi3Status {
        // SAFETY: FMI contract: the arrays hold nUnknowns, nKnowns, nSeed and nSensitivity elements.
        unsafe {
            with_instance(instance, "fmi3GetAdjointDerivative", |i| {
                let u = slice(unknowns, nUnknowns, "unknowns")?;
                let k = slice(knowns, nKnowns, "knowns")?;
                let s = slice(seed, nSeed, "seed")?;
                let out = slice_mut(sensitivity, nSensitivity, "sensitivity")?;
                i.adjoint_derivative3(u, k, s, out)
            })
        }
    } ?= fmi3Fatal
}
