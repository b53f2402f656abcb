//! The C boundary's guards: `ffi_fn!` (every export's body inside `catch_unwind`), `non_null!`,
//! the `Component` behind an `fmi2Component` (with a magic word against freed or foreign
//! pointers), `with_instance` (state checks, logging, panic → `fmi2Fatal` and a poisoned
//! instance), and the array views `slice`/`slice_mut` that accept NULL only for length 0.

use crate::fmu::{FmuError, Instance, Status};
use std::any::Any;
use std::panic::{catch_unwind, AssertUnwindSafe};

use super::types::{
    fmi2Component, fmi2Discard, fmi2Error, fmi2Fatal, fmi2OK, fmi2Status, fmi2Warning,
};

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
    unsafe { with_component(c, function, |comp| f(&mut comp.instance)) }
}

/// [`with_instance`] for calls that also need the component itself (its address owns the FMU
/// states it allocates, see `registry`).
///
/// # Safety
/// As [`component`].
pub(crate) unsafe fn with_component(
    c: fmi2Component,
    function: &'static str,
    f: impl FnOnce(&mut Component) -> Result<Status, FmuError>,
) -> fmi2Status {
    // SAFETY: forwarded caller contract.
    let Some(comp) = (unsafe { component(c) }) else {
        return fmi2Error;
    };
    match catch_unwind(AssertUnwindSafe(|| f(comp))) {
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
        super::registry::free_owned_by(c as usize);
        // SAFETY: the pointer came from Box::into_raw in into_component and is freed once (magic reset).
        drop(unsafe { Box::from_raw(c.cast::<Component>()) });
    }
}
