//! The exported `fmi2*` C functions (FMI 2.0.4 §2.1 and §4.2): the only module with `unsafe`
//! code. Every function is thin: convert the C arguments, call an [`Instance`] method, turn the
//! result into an `fmi2Status`.
//!
//! Conventions (the contract with importers):
//! - **Panics** never cross the C boundary: every body runs inside `catch_unwind`
//!   (`ffi_fn!`). A panic is logged (`logStatusFatal`), poisons *that* instance (every later
//!   call but `fmi2FreeInstance` returns `fmi2Error`) and returns `fmi2Fatal`. Other instances
//!   are unaffected: there is no global state.
//! - **NULL** pointers (`non_null!`) are logged and rejected with `fmi2Error`; an array
//!   pointer may be NULL when its length is 0. A NULL `fmi2Component` returns `fmi2Error`
//!   (nothing to log to).
//! - **Logging** goes only through the importer's callback, always with the format `"%s"`.
//! - The component pointer is a `Box<Component>`; a magic word catches use of a freed or
//!   foreign pointer in most cases.
#![allow(unsafe_code)]
#![deny(unsafe_op_in_unsafe_fn)]
#![warn(clippy::undocumented_unsafe_blocks)]
#![allow(non_snake_case)]

use crate::fmu::{FmuError, Instance, Status};
use std::any::Any;
use std::panic::{catch_unwind, AssertUnwindSafe};

pub mod common;
pub mod cosim;
pub mod getset;
pub mod logger;
pub mod state;
pub mod types;

use types::{fmi2Component, fmi2Discard, fmi2Error, fmi2Fatal, fmi2OK, fmi2Status, fmi2Warning};

/// Defines an exported `extern "C"` function whose body runs inside `catch_unwind`; a panic
/// that escapes the body returns the fallback given after `?=`.
macro_rules! ffi_fn {
    ($(#[$m:meta])* fn $name:ident($($arg:ident: $ty:ty),* $(,)?) -> $ret:ty $body:block ?= $fallback:expr) => {
        $(#[$m])*
        ///
        /// # Safety
        /// Pointer arguments must be NULL or valid as the FMI 2.0.4 standard describes them; the
        /// component must come from `fmi2Instantiate` and not be used concurrently.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $name($($arg: $ty),*) -> $ret {
            match std::panic::catch_unwind(std::panic::AssertUnwindSafe(move || -> $ret { $body })) {
                Ok(v) => v,
                Err(_) => $fallback,
            }
        }
    };
}
pub(crate) use ffi_fn;

/// Inside a [`with_instance`] closure: rejects the call (`fmi2Error`, logged, nothing changed)
/// when `$ptr` is NULL.
macro_rules! non_null {
    ($ptr:expr, $what:expr) => {
        if $ptr.is_null() {
            return Err($crate::fmu::FmuError::rejected(format!(
                "argument {} is NULL",
                $what
            )));
        }
    };
}
pub(crate) use non_null;

const MAGIC: u64 = 0x7472_6961_645f_666d; // "triad_fm"

/// What an `fmi2Component` points to.
pub struct Component {
    magic: u64,
    /// The instance.
    pub instance: Instance,
}

/// The status code of a [`Status`].
#[must_use]
pub fn code(s: Status) -> fmi2Status {
    match s {
        Status::Ok => fmi2OK,
        Status::Warning => fmi2Warning,
        Status::Discard => fmi2Discard,
        Status::Error => fmi2Error,
        Status::Fatal => fmi2Fatal,
    }
}

fn panic_message(payload: &(dyn Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".to_string())
}

/// Turns a component pointer into the instance, or `None` for NULL / a bad magic word.
///
/// # Safety
/// `c` must be NULL or a pointer returned by `fmi2Instantiate` and not yet freed, not used
/// concurrently.
pub(crate) unsafe fn component<'a>(c: fmi2Component) -> Option<&'a mut Component> {
    if c.is_null() {
        return None;
    }
    // SAFETY: non-NULL and, per the caller's contract, a live `Box<Component>` from
    // `fmi2Instantiate` that no other thread uses now.
    let comp = unsafe { &mut *c.cast::<Component>() };
    (comp.magic == MAGIC).then_some(comp)
}

/// Runs `f` on the instance behind `c`: checks the pointer, catches a panic (→ poisoned,
/// `fmi2Fatal`), logs an error's reason and escalates it (→ `Instance::finish`).
///
/// # Safety
/// As [`component`].
pub(crate) unsafe fn with_instance(
    c: fmi2Component,
    function: &'static str,
    f: impl FnOnce(&mut Instance) -> Result<Status, FmuError>,
) -> fmi2Status {
    // SAFETY: forwarded caller contract.
    let Some(comp) = (unsafe { component(c) }) else {
        return fmi2Error;
    };
    match catch_unwind(AssertUnwindSafe(|| f(&mut comp.instance))) {
        Ok(result) => code(comp.instance.finish(function, result)),
        Err(payload) => {
            // poisoning the instance is what makes AssertUnwindSafe honest
            let msg = format!(
                "{function}: internal error (panic): {}",
                panic_message(&*payload)
            );
            comp.instance.poison(&msg);
            fmi2Fatal
        }
    }
}

/// Test hook: panics inside [`with_instance`], as an internal bug would, to exercise the
/// poisoning path. Not exported to C.
///
/// # Safety
/// As [`component`].
#[doc(hidden)]
pub unsafe fn triad_test_panic(c: fmi2Component) -> fmi2Status {
    // SAFETY: forwarded caller contract.
    unsafe { with_instance(c, "triad_test_panic", |_| panic!("injected test panic")) }
}

/// A C array as a slice; NULL is accepted only for length 0.
///
/// # Safety
/// A non-NULL `p` must point to `n` valid, initialised `T` that stay untouched during the call.
pub(crate) unsafe fn slice<'a, T>(p: *const T, n: usize, what: &str) -> Result<&'a [T], FmuError> {
    if n == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return Err(FmuError::rejected(format!(
            "argument {what} is NULL (length {n})"
        )));
    }
    // SAFETY: non-NULL, and the caller guarantees n valid elements.
    Ok(unsafe { std::slice::from_raw_parts(p, n) })
}

/// A mutable C array as a slice; NULL is accepted only for length 0.
///
/// # Safety
/// A non-NULL `p` must point to `n` writable `T` not aliased during the call.
pub(crate) unsafe fn slice_mut<'a, T>(
    p: *mut T,
    n: usize,
    what: &str,
) -> Result<&'a mut [T], FmuError> {
    if n == 0 {
        return Ok(&mut []);
    }
    if p.is_null() {
        return Err(FmuError::rejected(format!(
            "argument {what} is NULL (length {n})"
        )));
    }
    // SAFETY: non-NULL, and the caller guarantees n writable, unaliased elements.
    Ok(unsafe { std::slice::from_raw_parts_mut(p, n) })
}

/// Boxes an instance into a component pointer.
pub(crate) fn into_component(instance: Instance) -> fmi2Component {
    Box::into_raw(Box::new(Component {
        magic: MAGIC,
        instance,
    }))
    .cast()
}

/// Frees a component pointer.
///
/// # Safety
/// As [`component`]; the pointer must not be used afterwards.
pub(crate) unsafe fn free_component(c: fmi2Component) {
    // SAFETY: forwarded caller contract: a live Box<Component>.
    if let Some(comp) = unsafe { component(c) } {
        comp.magic = 0;
        // SAFETY: the pointer came from Box::into_raw in into_component and is freed once (magic reset).
        drop(unsafe { Box::from_raw(c.cast::<Component>()) });
    }
}

// every export has exactly the standard's C type
use common::*;
use cosim::*;
use getset::*;
use state::*;
use types::*;
const _: fmi2GetTypesPlatformTYPE = fmi2GetTypesPlatform;
const _: fmi2GetVersionTYPE = fmi2GetVersion;
const _: fmi2SetDebugLoggingTYPE = fmi2SetDebugLogging;
const _: fmi2InstantiateTYPE = fmi2Instantiate;
const _: fmi2FreeInstanceTYPE = fmi2FreeInstance;
const _: fmi2SetupExperimentTYPE = fmi2SetupExperiment;
const _: fmi2EnterInitializationModeTYPE = fmi2EnterInitializationMode;
const _: fmi2ExitInitializationModeTYPE = fmi2ExitInitializationMode;
const _: fmi2TerminateTYPE = fmi2Terminate;
const _: fmi2ResetTYPE = fmi2Reset;
const _: fmi2GetRealTYPE = fmi2GetReal;
const _: fmi2GetIntegerTYPE = fmi2GetInteger;
const _: fmi2GetBooleanTYPE = fmi2GetBoolean;
const _: fmi2GetStringTYPE = fmi2GetString;
const _: fmi2SetRealTYPE = fmi2SetReal;
const _: fmi2SetIntegerTYPE = fmi2SetInteger;
const _: fmi2SetBooleanTYPE = fmi2SetBoolean;
const _: fmi2SetStringTYPE = fmi2SetString;
const _: fmi2GetFMUstateTYPE = fmi2GetFMUstate;
const _: fmi2SetFMUstateTYPE = fmi2SetFMUstate;
const _: fmi2FreeFMUstateTYPE = fmi2FreeFMUstate;
const _: fmi2SerializedFMUstateSizeTYPE = fmi2SerializedFMUstateSize;
const _: fmi2SerializeFMUstateTYPE = fmi2SerializeFMUstate;
const _: fmi2DeSerializeFMUstateTYPE = fmi2DeSerializeFMUstate;
const _: fmi2GetDirectionalDerivativeTYPE = fmi2GetDirectionalDerivative;
const _: fmi2SetRealInputDerivativesTYPE = fmi2SetRealInputDerivatives;
const _: fmi2GetRealOutputDerivativesTYPE = fmi2GetRealOutputDerivatives;
const _: fmi2DoStepTYPE = fmi2DoStep;
const _: fmi2CancelStepTYPE = fmi2CancelStep;
const _: fmi2GetStatusTYPE = fmi2GetStatus;
const _: fmi2GetRealStatusTYPE = fmi2GetRealStatus;
const _: fmi2GetIntegerStatusTYPE = fmi2GetIntegerStatus;
const _: fmi2GetBooleanStatusTYPE = fmi2GetBooleanStatus;
const _: fmi2GetStringStatusTYPE = fmi2GetStringStatus;
