//! Life cycle: version, instantiation, experiment set-up, initialisation, termination, reset,
//! debug logging (FMI 2.0.4 §2.1.4–§2.1.6, §4.2.1).

use super::guard::{ffi_fn, free_component, into_component, slice, with_instance};
use super::logger::CLogger;
use super::types::*;
use crate::fmu::resource::uri_to_path;
use crate::fmu::{Category, Instance, LogSink, Status};
use std::ffi::{c_char, CStr};

/// A C string as `&str` (lossy), `None` for NULL.
///
/// # Safety
/// `p` must be NULL or a valid NUL-terminated string.
pub(crate) unsafe fn str_arg(p: *const c_char) -> Option<String> {
    if p.is_null() {
        return None;
    }
    // SAFETY: non-NULL and NUL-terminated per the caller.
    Some(unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned())
}

ffi_fn! {
    /// `fmi2GetTypesPlatform` (FMI 2.0.4 §2.1.4): `"default"`.
    fn fmi2GetTypesPlatform() -> *const c_char {
        c"default".as_ptr()
    } ?= c"default".as_ptr()
}

ffi_fn! {
    /// `fmi2GetVersion` (FMI 2.0.4 §2.1.4): `"2.0"`.
    fn fmi2GetVersion() -> *const c_char {
        c"2.0".as_ptr()
    } ?= c"2.0".as_ptr()
}

ffi_fn! {
    /// `fmi2SetDebugLogging` (FMI 2.0.4 §2.1.5): switches the named categories (all when
    /// `nCategories` is 0); an unknown category is an `fmi2Error` and changes nothing.
    fn fmi2SetDebugLogging(c: fmi2Component, loggingOn: fmi2Boolean, nCategories: usize, categories: *const fmi2String) -> fmi2Status {
        // SAFETY: FMI contract on c and the categories array.
        unsafe {
            with_instance(c, "fmi2SetDebugLogging", |inst| {
                let ptrs = slice(categories, nCategories, "categories")?;
                let mut names = Vec::with_capacity(ptrs.len());
                for &p in ptrs {
                    names.push(str_arg(p).ok_or_else(|| crate::fmu::FmuError::rejected("a category is NULL"))?);
                }
                let refs: Vec<&str> = names.iter().map(String::as_str).collect();
                inst.set_debug_logging(loggingOn != fmi2False, &refs)
            })
        }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2Instantiate` (FMI 2.0.4 §2.1.5): Co-Simulation only; reads
    /// `resources/model.json` from `fmuResourceLocation` (any `file:` URI form), recomputes the
    /// GUID and returns NULL (logged) on a mismatch, an unknown `fmuType` or missing arguments.
    /// The callback struct is copied; the memory callbacks are never used.
    fn fmi2Instantiate(
        instanceName: fmi2String,
        fmuType: fmi2Type,
        fmuGUID: fmi2String,
        fmuResourceLocation: fmi2String,
        functions: *const fmi2CallbackFunctions,
        visible: fmi2Boolean,
        loggingOn: fmi2Boolean,
    ) -> fmi2Component {
        let _ = visible;
        // SAFETY: functions is NULL or points to a valid struct (FMI contract); copied at once.
        let callbacks = unsafe { functions.as_ref() }.copied();
        let sink = match callbacks {
            Some(cb) => CLogger::new(cb.logger, cb.componentEnvironment),
            None => CLogger::new(None, std::ptr::null_mut()),
        };
        // SAFETY: FMI contract: NULL or NUL-terminated strings.
        let (name, guid, location) = unsafe { (str_arg(instanceName), str_arg(fmuGUID), str_arg(fmuResourceLocation)) };
        let name = name.unwrap_or_default();
        let fail = |msg: &str| {
            sink.log(&name, Status::Error, Category::LogStatusError, &format!("fmi2Instantiate: {msg}"));
            std::ptr::null_mut()
        };
        if name.is_empty() {
            return fail("instanceName is NULL or empty");
        }
        if fmuType != fmi2CoSimulation {
            return fail(&format!("fmuType {fmuType} is not supported: this FMU provides Co-Simulation only (fmi2CoSimulation = 1)"));
        }
        let Some(guid) = guid else { return fail("fmuGUID is NULL") };
        let Some(location) = location else {
            return fail("fmuResourceLocation is NULL; the model is read from resources/model.json");
        };
        let dir = match uri_to_path(&location) {
            Ok(d) => d,
            Err(e) => return fail(&format!("fmuResourceLocation: {e}")),
        };
        match Instance::from_resources(&name, &guid, &dir, loggingOn != fmi2False, Box::new(sink)) {
            Some(inst) => into_component(inst),
            None => std::ptr::null_mut(),
        }
    } ?= std::ptr::null_mut()
}

ffi_fn! {
    /// `fmi2FreeInstance` (FMI 2.0.4 §2.1.5): allowed in every mode, also after a panic.
    fn fmi2FreeInstance(c: fmi2Component) -> () {
        // SAFETY: FMI contract: c from fmi2Instantiate, not used afterwards.
        unsafe { free_component(c) }
    } ?= ()
}

ffi_fn! {
    /// `fmi2SetupExperiment` (FMI 2.0.4 §2.1.6): start time and optional stop time (a step
    /// beyond it is refused); a defined tolerance must be positive and finite and is not used
    /// otherwise (see the parameter `solver.tolerance`).
    fn fmi2SetupExperiment(c: fmi2Component, toleranceDefined: fmi2Boolean, tolerance: fmi2Real, startTime: fmi2Real, stopTimeDefined: fmi2Boolean, stopTime: fmi2Real) -> fmi2Status {
        let stop = (stopTimeDefined != fmi2False).then_some(stopTime);
        let tol = (toleranceDefined != fmi2False).then_some(tolerance);
        // SAFETY: FMI contract on c.
        unsafe { with_instance(c, "fmi2SetupExperiment", |i| i.setup_experiment(startTime, stop, tol)) }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2EnterInitializationMode` (FMI 2.0.4 §2.1.6): builds the simulation, so outputs can be
    /// read in Initialization Mode.
    fn fmi2EnterInitializationMode(c: fmi2Component) -> fmi2Status {
        // SAFETY: FMI contract on c.
        unsafe { with_instance(c, "fmi2EnterInitializationMode", Instance::enter_initialization_mode) }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2ExitInitializationMode` (FMI 2.0.4 §2.1.6).
    fn fmi2ExitInitializationMode(c: fmi2Component) -> fmi2Status {
        // SAFETY: FMI contract on c.
        unsafe { with_instance(c, "fmi2ExitInitializationMode", Instance::exit_initialization_mode) }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2Terminate` (FMI 2.0.4 §2.1.6).
    fn fmi2Terminate(c: fmi2Component) -> fmi2Status {
        // SAFETY: FMI contract on c.
        unsafe { with_instance(c, "fmi2Terminate", Instance::terminate) }
    } ?= fmi2Fatal
}

ffi_fn! {
    /// `fmi2Reset` (FMI 2.0.4 §2.1.6): back to Instantiated mode with the start values.
    fn fmi2Reset(c: fmi2Component) -> fmi2Status {
        // SAFETY: FMI contract on c.
        unsafe { with_instance(c, "fmi2Reset", Instance::reset) }
    } ?= fmi2Fatal
}
