//! The FMI functions as the FMU tests call them: the crate's own exports (linked statically,
//! the default) or, with `TRIAD_DYNAMIC_TESTS=1`, the same functions of the shared library
//! `cdylib()` (`TRIAD_CDYLIB`: e.g. the glibc-2.17 runtime) loaded as an importer loads an FMU's
//! binary. `.ci/run` runs the randomised call test both ways.
#![allow(
    dead_code,
    non_snake_case,
    clippy::missing_safety_doc,
    clippy::too_many_arguments
)]

use std::ffi::c_char;
use std::sync::OnceLock;
use triad::ffi::types::*;

/// An array of value references.
type VR = *const fmi2ValueReference;

mod linked {
    pub use triad::ffi::common::*;
    pub use triad::ffi::cosim::*;
    pub use triad::ffi::getset::*;
    pub use triad::ffi::state::*;
}

/// The loaded library's functions.
struct Table {
    _lib: libloading::Library,
    fmi2GetTypesPlatform: unsafe extern "C" fn() -> *const c_char,
    fmi2GetVersion: unsafe extern "C" fn() -> *const c_char,
    fmi2SetDebugLogging:
        unsafe extern "C" fn(fmi2Component, fmi2Boolean, usize, *const fmi2String) -> fmi2Status,
    fmi2Instantiate: unsafe extern "C" fn(
        fmi2String,
        fmi2Type,
        fmi2String,
        fmi2String,
        *const fmi2CallbackFunctions,
        fmi2Boolean,
        fmi2Boolean,
    ) -> fmi2Component,
    fmi2FreeInstance: unsafe extern "C" fn(fmi2Component),
    fmi2SetupExperiment: unsafe extern "C" fn(
        fmi2Component,
        fmi2Boolean,
        fmi2Real,
        fmi2Real,
        fmi2Boolean,
        fmi2Real,
    ) -> fmi2Status,
    fmi2EnterInitializationMode: unsafe extern "C" fn(fmi2Component) -> fmi2Status,
    fmi2ExitInitializationMode: unsafe extern "C" fn(fmi2Component) -> fmi2Status,
    fmi2Terminate: unsafe extern "C" fn(fmi2Component) -> fmi2Status,
    fmi2Reset: unsafe extern "C" fn(fmi2Component) -> fmi2Status,
    fmi2GetReal: unsafe extern "C" fn(fmi2Component, VR, usize, *mut fmi2Real) -> fmi2Status,
    fmi2GetInteger: unsafe extern "C" fn(fmi2Component, VR, usize, *mut fmi2Integer) -> fmi2Status,
    fmi2GetBoolean: unsafe extern "C" fn(fmi2Component, VR, usize, *mut fmi2Boolean) -> fmi2Status,
    fmi2GetString: unsafe extern "C" fn(fmi2Component, VR, usize, *mut fmi2String) -> fmi2Status,
    fmi2SetReal: unsafe extern "C" fn(fmi2Component, VR, usize, *const fmi2Real) -> fmi2Status,
    fmi2SetInteger:
        unsafe extern "C" fn(fmi2Component, VR, usize, *const fmi2Integer) -> fmi2Status,
    fmi2SetBoolean:
        unsafe extern "C" fn(fmi2Component, VR, usize, *const fmi2Boolean) -> fmi2Status,
    fmi2SetString: unsafe extern "C" fn(fmi2Component, VR, usize, *const fmi2String) -> fmi2Status,
    fmi2GetFMUstate: unsafe extern "C" fn(fmi2Component, *mut fmi2FMUstate) -> fmi2Status,
    fmi2SetFMUstate: unsafe extern "C" fn(fmi2Component, fmi2FMUstate) -> fmi2Status,
    fmi2FreeFMUstate: unsafe extern "C" fn(fmi2Component, *mut fmi2FMUstate) -> fmi2Status,
    fmi2SerializedFMUstateSize:
        unsafe extern "C" fn(fmi2Component, fmi2FMUstate, *mut usize) -> fmi2Status,
    fmi2SerializeFMUstate:
        unsafe extern "C" fn(fmi2Component, fmi2FMUstate, *mut fmi2Byte, usize) -> fmi2Status,
    fmi2DeSerializeFMUstate: unsafe extern "C" fn(
        fmi2Component,
        *const fmi2Byte,
        usize,
        *mut fmi2FMUstate,
    ) -> fmi2Status,
    fmi2GetDirectionalDerivative: unsafe extern "C" fn(
        fmi2Component,
        VR,
        usize,
        VR,
        usize,
        *const fmi2Real,
        *mut fmi2Real,
    ) -> fmi2Status,
    fmi2SetRealInputDerivatives: unsafe extern "C" fn(
        fmi2Component,
        VR,
        usize,
        *const fmi2Integer,
        *const fmi2Real,
    ) -> fmi2Status,
    fmi2GetRealOutputDerivatives: unsafe extern "C" fn(
        fmi2Component,
        VR,
        usize,
        *const fmi2Integer,
        *mut fmi2Real,
    ) -> fmi2Status,
    fmi2DoStep: unsafe extern "C" fn(fmi2Component, fmi2Real, fmi2Real, fmi2Boolean) -> fmi2Status,
    fmi2CancelStep: unsafe extern "C" fn(fmi2Component) -> fmi2Status,
    fmi2GetStatus:
        unsafe extern "C" fn(fmi2Component, fmi2StatusKind, *mut fmi2Status) -> fmi2Status,
    fmi2GetRealStatus:
        unsafe extern "C" fn(fmi2Component, fmi2StatusKind, *mut fmi2Real) -> fmi2Status,
    fmi2GetIntegerStatus:
        unsafe extern "C" fn(fmi2Component, fmi2StatusKind, *mut fmi2Integer) -> fmi2Status,
    fmi2GetBooleanStatus:
        unsafe extern "C" fn(fmi2Component, fmi2StatusKind, *mut fmi2Boolean) -> fmi2Status,
    fmi2GetStringStatus:
        unsafe extern "C" fn(fmi2Component, fmi2StatusKind, *mut fmi2String) -> fmi2Status,
}

/// The loaded functions, if `TRIAD_DYNAMIC_TESTS` asks for them.
fn table() -> Option<&'static Table> {
    static TABLE: OnceLock<Option<Table>> = OnceLock::new();
    TABLE
        .get_or_init(|| {
            std::env::var_os("TRIAD_DYNAMIC_TESTS")?;
            let path = super::cdylib();
            // SAFETY (test): loading the FMU runtime runs no foreign initialisers.
            let lib = unsafe { libloading::Library::new(&path) }
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            // SAFETY (test): every symbol has exactly the standard's type (checked in ffi/mod.rs).
            unsafe {
                Some(Table {
                    fmi2GetTypesPlatform: *lib
                        .get(b"fmi2GetTypesPlatform\0")
                        .expect("fmi2GetTypesPlatform exported"),
                    fmi2GetVersion: *lib
                        .get(b"fmi2GetVersion\0")
                        .expect("fmi2GetVersion exported"),
                    fmi2SetDebugLogging: *lib
                        .get(b"fmi2SetDebugLogging\0")
                        .expect("fmi2SetDebugLogging exported"),
                    fmi2Instantiate: *lib
                        .get(b"fmi2Instantiate\0")
                        .expect("fmi2Instantiate exported"),
                    fmi2FreeInstance: *lib
                        .get(b"fmi2FreeInstance\0")
                        .expect("fmi2FreeInstance exported"),
                    fmi2SetupExperiment: *lib
                        .get(b"fmi2SetupExperiment\0")
                        .expect("fmi2SetupExperiment exported"),
                    fmi2EnterInitializationMode: *lib
                        .get(b"fmi2EnterInitializationMode\0")
                        .expect("fmi2EnterInitializationMode exported"),
                    fmi2ExitInitializationMode: *lib
                        .get(b"fmi2ExitInitializationMode\0")
                        .expect("fmi2ExitInitializationMode exported"),
                    fmi2Terminate: *lib.get(b"fmi2Terminate\0").expect("fmi2Terminate exported"),
                    fmi2Reset: *lib.get(b"fmi2Reset\0").expect("fmi2Reset exported"),
                    fmi2GetReal: *lib.get(b"fmi2GetReal\0").expect("fmi2GetReal exported"),
                    fmi2GetInteger: *lib
                        .get(b"fmi2GetInteger\0")
                        .expect("fmi2GetInteger exported"),
                    fmi2GetBoolean: *lib
                        .get(b"fmi2GetBoolean\0")
                        .expect("fmi2GetBoolean exported"),
                    fmi2GetString: *lib.get(b"fmi2GetString\0").expect("fmi2GetString exported"),
                    fmi2SetReal: *lib.get(b"fmi2SetReal\0").expect("fmi2SetReal exported"),
                    fmi2SetInteger: *lib
                        .get(b"fmi2SetInteger\0")
                        .expect("fmi2SetInteger exported"),
                    fmi2SetBoolean: *lib
                        .get(b"fmi2SetBoolean\0")
                        .expect("fmi2SetBoolean exported"),
                    fmi2SetString: *lib.get(b"fmi2SetString\0").expect("fmi2SetString exported"),
                    fmi2GetFMUstate: *lib
                        .get(b"fmi2GetFMUstate\0")
                        .expect("fmi2GetFMUstate exported"),
                    fmi2SetFMUstate: *lib
                        .get(b"fmi2SetFMUstate\0")
                        .expect("fmi2SetFMUstate exported"),
                    fmi2FreeFMUstate: *lib
                        .get(b"fmi2FreeFMUstate\0")
                        .expect("fmi2FreeFMUstate exported"),
                    fmi2SerializedFMUstateSize: *lib
                        .get(b"fmi2SerializedFMUstateSize\0")
                        .expect("fmi2SerializedFMUstateSize exported"),
                    fmi2SerializeFMUstate: *lib
                        .get(b"fmi2SerializeFMUstate\0")
                        .expect("fmi2SerializeFMUstate exported"),
                    fmi2DeSerializeFMUstate: *lib
                        .get(b"fmi2DeSerializeFMUstate\0")
                        .expect("fmi2DeSerializeFMUstate exported"),
                    fmi2GetDirectionalDerivative: *lib
                        .get(b"fmi2GetDirectionalDerivative\0")
                        .expect("fmi2GetDirectionalDerivative exported"),
                    fmi2SetRealInputDerivatives: *lib
                        .get(b"fmi2SetRealInputDerivatives\0")
                        .expect("fmi2SetRealInputDerivatives exported"),
                    fmi2GetRealOutputDerivatives: *lib
                        .get(b"fmi2GetRealOutputDerivatives\0")
                        .expect("fmi2GetRealOutputDerivatives exported"),
                    fmi2DoStep: *lib.get(b"fmi2DoStep\0").expect("fmi2DoStep exported"),
                    fmi2CancelStep: *lib
                        .get(b"fmi2CancelStep\0")
                        .expect("fmi2CancelStep exported"),
                    fmi2GetStatus: *lib.get(b"fmi2GetStatus\0").expect("fmi2GetStatus exported"),
                    fmi2GetRealStatus: *lib
                        .get(b"fmi2GetRealStatus\0")
                        .expect("fmi2GetRealStatus exported"),
                    fmi2GetIntegerStatus: *lib
                        .get(b"fmi2GetIntegerStatus\0")
                        .expect("fmi2GetIntegerStatus exported"),
                    fmi2GetBooleanStatus: *lib
                        .get(b"fmi2GetBooleanStatus\0")
                        .expect("fmi2GetBooleanStatus exported"),
                    fmi2GetStringStatus: *lib
                        .get(b"fmi2GetStringStatus\0")
                        .expect("fmi2GetStringStatus exported"),
                    _lib: lib,
                })
            }
        })
        .as_ref()
}

/// Whether the tests call a loaded library (`TRIAD_DYNAMIC_TESTS`).
#[must_use]
pub fn dynamic() -> bool {
    table().is_some()
}

/// `fmi2GetTypesPlatform`, linked or loaded (module docs).
pub unsafe fn fmi2GetTypesPlatform() -> *const c_char {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2GetTypesPlatform)() },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2GetTypesPlatform() },
    }
}

/// `fmi2GetVersion`, linked or loaded (module docs).
pub unsafe fn fmi2GetVersion() -> *const c_char {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2GetVersion)() },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2GetVersion() },
    }
}

/// `fmi2SetDebugLogging`, linked or loaded (module docs).
pub unsafe fn fmi2SetDebugLogging(
    a0: fmi2Component,
    a1: fmi2Boolean,
    a2: usize,
    a3: *const fmi2String,
) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2SetDebugLogging)(a0, a1, a2, a3) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2SetDebugLogging(a0, a1, a2, a3) },
    }
}

/// `fmi2Instantiate`, linked or loaded (module docs).
pub unsafe fn fmi2Instantiate(
    a0: fmi2String,
    a1: fmi2Type,
    a2: fmi2String,
    a3: fmi2String,
    a4: *const fmi2CallbackFunctions,
    a5: fmi2Boolean,
    a6: fmi2Boolean,
) -> fmi2Component {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2Instantiate)(a0, a1, a2, a3, a4, a5, a6) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2Instantiate(a0, a1, a2, a3, a4, a5, a6) },
    }
}

/// `fmi2FreeInstance`, linked or loaded (module docs).
pub unsafe fn fmi2FreeInstance(a0: fmi2Component) {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2FreeInstance)(a0) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2FreeInstance(a0) },
    }
}

/// `fmi2SetupExperiment`, linked or loaded (module docs).
pub unsafe fn fmi2SetupExperiment(
    a0: fmi2Component,
    a1: fmi2Boolean,
    a2: fmi2Real,
    a3: fmi2Real,
    a4: fmi2Boolean,
    a5: fmi2Real,
) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2SetupExperiment)(a0, a1, a2, a3, a4, a5) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2SetupExperiment(a0, a1, a2, a3, a4, a5) },
    }
}

/// `fmi2EnterInitializationMode`, linked or loaded (module docs).
pub unsafe fn fmi2EnterInitializationMode(a0: fmi2Component) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2EnterInitializationMode)(a0) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2EnterInitializationMode(a0) },
    }
}

/// `fmi2ExitInitializationMode`, linked or loaded (module docs).
pub unsafe fn fmi2ExitInitializationMode(a0: fmi2Component) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2ExitInitializationMode)(a0) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2ExitInitializationMode(a0) },
    }
}

/// `fmi2Terminate`, linked or loaded (module docs).
pub unsafe fn fmi2Terminate(a0: fmi2Component) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2Terminate)(a0) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2Terminate(a0) },
    }
}

/// `fmi2Reset`, linked or loaded (module docs).
pub unsafe fn fmi2Reset(a0: fmi2Component) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2Reset)(a0) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2Reset(a0) },
    }
}

/// `fmi2GetReal`, linked or loaded (module docs).
pub unsafe fn fmi2GetReal(a0: fmi2Component, a1: VR, a2: usize, a3: *mut fmi2Real) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2GetReal)(a0, a1, a2, a3) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2GetReal(a0, a1, a2, a3) },
    }
}

/// `fmi2GetInteger`, linked or loaded (module docs).
pub unsafe fn fmi2GetInteger(
    a0: fmi2Component,
    a1: VR,
    a2: usize,
    a3: *mut fmi2Integer,
) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2GetInteger)(a0, a1, a2, a3) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2GetInteger(a0, a1, a2, a3) },
    }
}

/// `fmi2GetBoolean`, linked or loaded (module docs).
pub unsafe fn fmi2GetBoolean(
    a0: fmi2Component,
    a1: VR,
    a2: usize,
    a3: *mut fmi2Boolean,
) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2GetBoolean)(a0, a1, a2, a3) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2GetBoolean(a0, a1, a2, a3) },
    }
}

/// `fmi2GetString`, linked or loaded (module docs).
pub unsafe fn fmi2GetString(
    a0: fmi2Component,
    a1: VR,
    a2: usize,
    a3: *mut fmi2String,
) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2GetString)(a0, a1, a2, a3) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2GetString(a0, a1, a2, a3) },
    }
}

/// `fmi2SetReal`, linked or loaded (module docs).
pub unsafe fn fmi2SetReal(a0: fmi2Component, a1: VR, a2: usize, a3: *const fmi2Real) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2SetReal)(a0, a1, a2, a3) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2SetReal(a0, a1, a2, a3) },
    }
}

/// `fmi2SetInteger`, linked or loaded (module docs).
pub unsafe fn fmi2SetInteger(
    a0: fmi2Component,
    a1: VR,
    a2: usize,
    a3: *const fmi2Integer,
) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2SetInteger)(a0, a1, a2, a3) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2SetInteger(a0, a1, a2, a3) },
    }
}

/// `fmi2SetBoolean`, linked or loaded (module docs).
pub unsafe fn fmi2SetBoolean(
    a0: fmi2Component,
    a1: VR,
    a2: usize,
    a3: *const fmi2Boolean,
) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2SetBoolean)(a0, a1, a2, a3) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2SetBoolean(a0, a1, a2, a3) },
    }
}

/// `fmi2SetString`, linked or loaded (module docs).
pub unsafe fn fmi2SetString(
    a0: fmi2Component,
    a1: VR,
    a2: usize,
    a3: *const fmi2String,
) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2SetString)(a0, a1, a2, a3) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2SetString(a0, a1, a2, a3) },
    }
}

/// `fmi2GetFMUstate`, linked or loaded (module docs).
pub unsafe fn fmi2GetFMUstate(a0: fmi2Component, a1: *mut fmi2FMUstate) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2GetFMUstate)(a0, a1) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2GetFMUstate(a0, a1) },
    }
}

/// `fmi2SetFMUstate`, linked or loaded (module docs).
pub unsafe fn fmi2SetFMUstate(a0: fmi2Component, a1: fmi2FMUstate) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2SetFMUstate)(a0, a1) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2SetFMUstate(a0, a1) },
    }
}

/// `fmi2FreeFMUstate`, linked or loaded (module docs).
pub unsafe fn fmi2FreeFMUstate(a0: fmi2Component, a1: *mut fmi2FMUstate) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2FreeFMUstate)(a0, a1) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2FreeFMUstate(a0, a1) },
    }
}

/// `fmi2SerializedFMUstateSize`, linked or loaded (module docs).
pub unsafe fn fmi2SerializedFMUstateSize(
    a0: fmi2Component,
    a1: fmi2FMUstate,
    a2: *mut usize,
) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2SerializedFMUstateSize)(a0, a1, a2) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2SerializedFMUstateSize(a0, a1, a2) },
    }
}

/// `fmi2SerializeFMUstate`, linked or loaded (module docs).
pub unsafe fn fmi2SerializeFMUstate(
    a0: fmi2Component,
    a1: fmi2FMUstate,
    a2: *mut fmi2Byte,
    a3: usize,
) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2SerializeFMUstate)(a0, a1, a2, a3) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2SerializeFMUstate(a0, a1, a2, a3) },
    }
}

/// `fmi2DeSerializeFMUstate`, linked or loaded (module docs).
pub unsafe fn fmi2DeSerializeFMUstate(
    a0: fmi2Component,
    a1: *const fmi2Byte,
    a2: usize,
    a3: *mut fmi2FMUstate,
) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2DeSerializeFMUstate)(a0, a1, a2, a3) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2DeSerializeFMUstate(a0, a1, a2, a3) },
    }
}

/// `fmi2GetDirectionalDerivative`, linked or loaded (module docs).
pub unsafe fn fmi2GetDirectionalDerivative(
    a0: fmi2Component,
    a1: VR,
    a2: usize,
    a3: VR,
    a4: usize,
    a5: *const fmi2Real,
    a6: *mut fmi2Real,
) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2GetDirectionalDerivative)(a0, a1, a2, a3, a4, a5, a6) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2GetDirectionalDerivative(a0, a1, a2, a3, a4, a5, a6) },
    }
}

/// `fmi2SetRealInputDerivatives`, linked or loaded (module docs).
pub unsafe fn fmi2SetRealInputDerivatives(
    a0: fmi2Component,
    a1: VR,
    a2: usize,
    a3: *const fmi2Integer,
    a4: *const fmi2Real,
) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2SetRealInputDerivatives)(a0, a1, a2, a3, a4) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2SetRealInputDerivatives(a0, a1, a2, a3, a4) },
    }
}

/// `fmi2GetRealOutputDerivatives`, linked or loaded (module docs).
pub unsafe fn fmi2GetRealOutputDerivatives(
    a0: fmi2Component,
    a1: VR,
    a2: usize,
    a3: *const fmi2Integer,
    a4: *mut fmi2Real,
) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2GetRealOutputDerivatives)(a0, a1, a2, a3, a4) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2GetRealOutputDerivatives(a0, a1, a2, a3, a4) },
    }
}

/// `fmi2DoStep`, linked or loaded (module docs).
pub unsafe fn fmi2DoStep(
    a0: fmi2Component,
    a1: fmi2Real,
    a2: fmi2Real,
    a3: fmi2Boolean,
) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2DoStep)(a0, a1, a2, a3) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2DoStep(a0, a1, a2, a3) },
    }
}

/// `fmi2CancelStep`, linked or loaded (module docs).
pub unsafe fn fmi2CancelStep(a0: fmi2Component) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2CancelStep)(a0) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2CancelStep(a0) },
    }
}

/// `fmi2GetStatus`, linked or loaded (module docs).
pub unsafe fn fmi2GetStatus(
    a0: fmi2Component,
    a1: fmi2StatusKind,
    a2: *mut fmi2Status,
) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2GetStatus)(a0, a1, a2) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2GetStatus(a0, a1, a2) },
    }
}

/// `fmi2GetRealStatus`, linked or loaded (module docs).
pub unsafe fn fmi2GetRealStatus(
    a0: fmi2Component,
    a1: fmi2StatusKind,
    a2: *mut fmi2Real,
) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2GetRealStatus)(a0, a1, a2) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2GetRealStatus(a0, a1, a2) },
    }
}

/// `fmi2GetIntegerStatus`, linked or loaded (module docs).
pub unsafe fn fmi2GetIntegerStatus(
    a0: fmi2Component,
    a1: fmi2StatusKind,
    a2: *mut fmi2Integer,
) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2GetIntegerStatus)(a0, a1, a2) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2GetIntegerStatus(a0, a1, a2) },
    }
}

/// `fmi2GetBooleanStatus`, linked or loaded (module docs).
pub unsafe fn fmi2GetBooleanStatus(
    a0: fmi2Component,
    a1: fmi2StatusKind,
    a2: *mut fmi2Boolean,
) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2GetBooleanStatus)(a0, a1, a2) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2GetBooleanStatus(a0, a1, a2) },
    }
}

/// `fmi2GetStringStatus`, linked or loaded (module docs).
pub unsafe fn fmi2GetStringStatus(
    a0: fmi2Component,
    a1: fmi2StatusKind,
    a2: *mut fmi2String,
) -> fmi2Status {
    match table() {
        // SAFETY (test): the caller's FMI contract, forwarded.
        Some(t) => unsafe { (t.fmi2GetStringStatus)(a0, a1, a2) },
        // SAFETY (test): as above.
        None => unsafe { linked::fmi2GetStringStatus(a0, a1, a2) },
    }
}
