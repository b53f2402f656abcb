//! Life cycle (FMI 3.0 §2.3.1–§2.3.4, §4.2): version, debug logging, instantiation (Co-Simulation
//! only; Model Exchange and Scheduled Execution refuse with NULL), initialisation, termination,
//! reset, free.

use super::logger::C3Logger;
use super::types::*;
use crate::ffi::common::str_arg;
use crate::ffi::guard::{ffi_fn, free_component, into_component, slice, with_instance};
use crate::fmu::resource::{location_to_path, PathStyle};
use crate::fmu::{Api, Category, FmuError, Instance, LogSink, Status};
use std::ffi::c_char;
use std::path::PathBuf;

ffi_fn! {
    /// `fmi3GetVersion`: `"3.0"`.
    fn fmi3GetVersion() -> *const c_char {
        c"3.0".as_ptr()
    } ?= c"3.0".as_ptr()
}

ffi_fn! {
    /// `fmi3SetDebugLogging`: switches the named categories (all when `nCategories` is 0); an
    /// unknown category is an `fmi3Error` and changes nothing.
    fn fmi3SetDebugLogging(instance: fmi3Instance, loggingOn: fmi3Boolean, nCategories: usize, categories: *const fmi3String) -> fmi3Status {
        // SAFETY: FMI contract on the instance and the categories array.
        unsafe {
            with_instance(instance, "fmi3SetDebugLogging", |inst| {
                let ptrs = slice(categories, nCategories, "categories")?;
                let mut names = Vec::with_capacity(ptrs.len());
                for &p in ptrs {
                    names.push(str_arg(p).ok_or_else(|| FmuError::rejected("a category is NULL"))?);
                }
                let refs: Vec<&str> = names.iter().map(String::as_str).collect();
                inst.set_debug_logging(loggingOn, &refs)
            })
        }
    } ?= fmi3Fatal
}

/// Logs `message` as an error of `function` through `sink` and gives the NULL instance.
fn refuse(sink: &dyn LogSink, name: &str, function: &str, message: &str) -> fmi3Instance {
    sink.log(
        name,
        Status::Error,
        Category::LogStatusError,
        &format!("{function}: {message}"),
    );
    std::ptr::null_mut()
}

/// `resourcePath` → the resources directory: an absolute file system path of this system,
/// with or without a trailing separator (a `file:` URI, which FMI 3 does not pass, is taken too).
fn resource_dir(path: &str) -> Result<PathBuf, String> {
    location_to_path(path, PathStyle::HOST).map(PathBuf::from)
}

ffi_fn! {
    /// `fmi3InstantiateModelExchange`: this FMU provides Co-Simulation only → NULL, logged.
    fn fmi3InstantiateModelExchange(
        instanceName: fmi3String,
        instantiationToken: fmi3String,
        resourcePath: fmi3String,
        visible: fmi3Boolean,
        loggingOn: fmi3Boolean,
        instanceEnvironment: fmi3InstanceEnvironment,
        logMessage: fmi3LogMessageCallback,
    ) -> fmi3Instance {
        let _ = (instantiationToken, resourcePath, visible, loggingOn);
        let sink = C3Logger::new(logMessage, instanceEnvironment);
        // SAFETY: FMI contract: NULL or a NUL-terminated string.
        let name = unsafe { str_arg(instanceName) }.unwrap_or_default();
        refuse(&sink, &name, "fmi3InstantiateModelExchange", "this FMU provides Co-Simulation only (no <ModelExchange> in modelDescription.xml)")
    } ?= std::ptr::null_mut()
}

ffi_fn! {
    /// `fmi3InstantiateScheduledExecution`: this FMU provides Co-Simulation only → NULL, logged.
    fn fmi3InstantiateScheduledExecution(
        instanceName: fmi3String,
        instantiationToken: fmi3String,
        resourcePath: fmi3String,
        visible: fmi3Boolean,
        loggingOn: fmi3Boolean,
        instanceEnvironment: fmi3InstanceEnvironment,
        logMessage: fmi3LogMessageCallback,
        clockUpdate: fmi3ClockUpdateCallback,
        lockPreemption: fmi3LockPreemptionCallback,
        unlockPreemption: fmi3UnlockPreemptionCallback,
    ) -> fmi3Instance {
        let _ = (instantiationToken, resourcePath, visible, loggingOn, clockUpdate, lockPreemption, unlockPreemption);
        let sink = C3Logger::new(logMessage, instanceEnvironment);
        // SAFETY: FMI contract: NULL or a NUL-terminated string.
        let name = unsafe { str_arg(instanceName) }.unwrap_or_default();
        refuse(&sink, &name, "fmi3InstantiateScheduledExecution", "this FMU provides Co-Simulation only (no <ScheduledExecution> in modelDescription.xml)")
    } ?= std::ptr::null_mut()
}

ffi_fn! {
    /// `fmi3InstantiateCoSimulation`: reads `resources/model.json` under `resourcePath` (a
    /// file system path, with or without a trailing separator), recomputes the
    /// instantiation token (the FMI 2 GUID) and returns NULL (logged) on a mismatch, missing
    /// arguments or `eventModeUsed` (this FMU has no Event Mode). `earlyReturnAllowed` is
    /// recorded; intermediate update is not provided, so `requiredIntermediateVariables` and
    /// `intermediateUpdate` are not used.
    fn fmi3InstantiateCoSimulation(
        instanceName: fmi3String,
        instantiationToken: fmi3String,
        resourcePath: fmi3String,
        visible: fmi3Boolean,
        loggingOn: fmi3Boolean,
        eventModeUsed: fmi3Boolean,
        earlyReturnAllowed: fmi3Boolean,
        requiredIntermediateVariables: *const fmi3ValueReference,
        nRequiredIntermediateVariables: usize,
        instanceEnvironment: fmi3InstanceEnvironment,
        logMessage: fmi3LogMessageCallback,
        intermediateUpdate: fmi3IntermediateUpdateCallback,
    ) -> fmi3Instance {
        let _ = (visible, requiredIntermediateVariables, intermediateUpdate);
        let sink = C3Logger::new(logMessage, instanceEnvironment);
        const F: &str = "fmi3InstantiateCoSimulation";
        // SAFETY: FMI contract: NULL or NUL-terminated strings.
        let (name, token, path) = unsafe { (str_arg(instanceName), str_arg(instantiationToken), str_arg(resourcePath)) };
        let name = name.unwrap_or_default();
        if name.is_empty() {
            return refuse(&sink, &name, F, "instanceName is NULL or empty");
        }
        let Some(token) = token else { return refuse(&sink, &name, F, "instantiationToken is NULL") };
        if eventModeUsed {
            return refuse(&sink, &name, F, "eventModeUsed is true, but this FMU has no Event Mode (hasEventMode=\"false\")");
        }
        let Some(path) = path else {
            return refuse(&sink, &name, F, "resourcePath is NULL; the model is read from resources/model.json");
        };
        let dir = match resource_dir(&path) {
            Ok(d) => d,
            Err(e) => return refuse(&sink, &name, F, &format!("resourcePath: {e}")),
        };
        if nRequiredIntermediateVariables > 0 {
            sink.log(&name, Status::Warning, Category::LogStatusWarning, &format!("{F}: {nRequiredIntermediateVariables} requiredIntermediateVariables ignored: this FMU does not provide intermediate update (providesIntermediateUpdate=\"false\")"));
        }
        let api = Api::Fmi3 { early_return_allowed: earlyReturnAllowed };
        match Instance::from_resources_for(api, &name, &token, &dir, loggingOn, Box::new(sink)) {
            Some(inst) => into_component(inst),
            None => std::ptr::null_mut(),
        }
    } ?= std::ptr::null_mut()
}

ffi_fn! {
    /// `fmi3FreeInstance`: allowed in every state, also after a panic; frees the FMU states
    /// the instance allocated.
    fn fmi3FreeInstance(instance: fmi3Instance) -> () {
        // SAFETY: FMI contract: the instance came from fmi3InstantiateCoSimulation and is not
        // used afterwards.
        unsafe { free_component(instance) }
    } ?= ()
}

ffi_fn! {
    /// `fmi3EnterInitializationMode`: the experiment (start time, optional stop time, a
    /// defined tolerance checked but not used: see `solver.tolerance`) and the build of the
    /// simulation; refused as a whole, the instance unchanged.
    fn fmi3EnterInitializationMode(instance: fmi3Instance, toleranceDefined: fmi3Boolean, tolerance: fmi3Float64, startTime: fmi3Float64, stopTimeDefined: fmi3Boolean, stopTime: fmi3Float64) -> fmi3Status {
        let tol = toleranceDefined.then_some(tolerance);
        let stop = stopTimeDefined.then_some(stopTime);
        // SAFETY: FMI contract on the instance.
        unsafe { with_instance(instance, "fmi3EnterInitializationMode", |i| i.enter_initialization_mode3(tol, startTime, stop)) }
    } ?= fmi3Fatal
}

ffi_fn! {
    /// `fmi3ExitInitializationMode`: into Step Mode.
    fn fmi3ExitInitializationMode(instance: fmi3Instance) -> fmi3Status {
        // SAFETY: FMI contract on the instance.
        unsafe { with_instance(instance, "fmi3ExitInitializationMode", Instance::exit_initialization_mode) }
    } ?= fmi3Fatal
}

ffi_fn! {
    /// `fmi3Terminate`.
    fn fmi3Terminate(instance: fmi3Instance) -> fmi3Status {
        // SAFETY: FMI contract on the instance.
        unsafe { with_instance(instance, "fmi3Terminate", Instance::terminate) }
    } ?= fmi3Fatal
}

ffi_fn! {
    /// `fmi3Reset`: back to Instantiated with the start values.
    fn fmi3Reset(instance: fmi3Instance) -> fmi3Status {
        // SAFETY: FMI contract on the instance.
        unsafe { with_instance(instance, "fmi3Reset", Instance::reset) }
    } ?= fmi3Fatal
}
