//! Shared helpers of the FMU tests: a test model written to a temporary `resources/`, a Rust
//! wrapper over the exported `fmi2*` functions, and a logger that captures messages.
//!
//! The logger ABI: `fmi2CallbackLogger` is C-variadic, and defining a variadic function is not
//! stable Rust (1.95). triad always calls the logger as `logger(env, name, status, category,
//! "%s", message)`, i.e. five fixed arguments and exactly one variadic `const char*`. On the
//! x86-64 System V and AArch64 Linux ABIs a variadic pointer argument travels in the same
//! register as the sixth fixed argument of a non-variadic function (x86-64 additionally sets
//! `%al`, which a non-variadic callee ignores), so the test logger is declared with six fixed
//! arguments and transmuted to the variadic type. This is test-only and NOT valid on Apple
//! AArch64 (variadic arguments go on the stack there).
#![allow(dead_code, unsafe_code, clippy::missing_safety_doc)]

use std::ffi::{c_char, c_void, CStr, CString};
use std::path::PathBuf;
use std::sync::Mutex;
/// Declares each FMI function once (`fn name(argument: type, …) -> return;`) and generates
/// from that list the table of the loaded library's functions, its loading, and one forwarder
/// per function that calls the loaded function or the linked export. The invoking module
/// provides `linked` (the exports) and `table()` (the loaded table, if any).
macro_rules! fmi_api {
    ($(fn $name:ident($($arg:ident: $ty:ty),*) -> $ret:ty;)*) => {
        /// The loaded library's functions.
        struct Table {
            _lib: libloading::Library,
            $($name: unsafe extern "C" fn($($ty),*) -> $ret,)*
        }

        impl Table {
            /// Every listed function of `lib`.
            ///
            /// # Safety
            /// `lib` is a triad runtime: every symbol has exactly the standard's type (checked in
            /// ffi/mod.rs).
            unsafe fn load(lib: libloading::Library) -> Table {
                // SAFETY (test): the caller's promise.
                unsafe {
                    Table {
                        $($name: *lib
                            .get(concat!(stringify!($name), "\0").as_bytes())
                            .expect(concat!(stringify!($name), " exported")),)*
                        _lib: lib,
                    }
                }
            }
        }

        /// The loaded functions, if `TRIAD_DYNAMIC_TESTS` asks for them.
        fn table() -> Option<&'static Table> {
            static TABLE: std::sync::OnceLock<Option<Table>> = std::sync::OnceLock::new();
            TABLE
                .get_or_init(|| {
                    std::env::var_os("TRIAD_DYNAMIC_TESTS")?;
                    let path = super::cdylib();
                    // SAFETY (test): loading the FMU runtime runs no foreign initialisers.
                    let lib = unsafe { libloading::Library::new(&path) }
                        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                    // SAFETY (test): `lib` is the triad runtime.
                    Some(unsafe { Table::load(lib) })
                })
                .as_ref()
        }

        /// Whether the tests call a loaded library (`TRIAD_DYNAMIC_TESTS`).
        #[must_use]
        pub fn dynamic() -> bool {
            table().is_some()
        }

        $(
            #[doc = concat!("`", stringify!($name), "`, linked or loaded (module docs).")]
            pub unsafe fn $name($($arg: $ty),*) -> $ret {
                match table() {
                    // SAFETY (test): the caller's FMI contract, forwarded.
                    Some(t) => unsafe { (t.$name)($($arg),*) },
                    // SAFETY (test): as above.
                    None => unsafe { linked::$name($($arg),*) },
                }
            }
        )*
    };
}

pub mod api;
pub mod api3;
pub mod fmi3;
use api::*;
use triad::ffi::types::*;
use triad::fmu::contract::{self, Format, Spec};
use triad::variables::{Causality, VariableTable};

/// A single actuated pendulum in the interface.md §2 format.
pub const PENDULUM: &str = r#"
name = "Pendulum"
description = "One link on a revolute joint (FMU tests)"
gravity = [0.0, 0.0, -9.81]

[experiment]
start = 0.0
stop = 1.0
step = 0.01

[solver]
max_step = 0.001
order = 2
tolerance = 1e-10

[[body]]
name = "link1"
mass = 1.0
com = [0.0, 0.0, -0.5]
inertia = [0.0834, 0.0834, 1e-4]

[[joint]]
name = "shoulder"
type = "revolute"
parent = "world"
child = "link1"
axis = [0.0, 1.0, 0.0]
actuated = true
damping = 0.0
initial = { q = 1.0, qd = 0.0 }
"#;

/// A model: its spec, table and GUID, and a temporary directory holding `resources/model.json`.
pub struct TestModel {
    pub spec: Spec,
    pub table: VariableTable,
    pub guid: String,
    pub dir: tempfile::TempDir,
}

impl TestModel {
    pub fn new(toml_text: &str) -> Self {
        let spec = Spec::from_str(toml_text, Format::Toml, "test.toml").expect("test spec parses");
        let (def, settings) = spec.lower().expect("test spec lowers");
        let table = contract::table(&spec, &def, &settings);
        let guid = triad::fmu::guid::guid(&spec.canonical_json(), &table);
        let dir = tempfile::Builder::new()
            .prefix("triad fmu test ")
            .tempdir()
            .expect("tempdir");
        std::fs::create_dir_all(dir.path().join("resources")).expect("mkdir");
        std::fs::write(
            dir.path().join("resources/model.json"),
            spec.canonical_json(),
        )
        .expect("write");
        Self {
            spec,
            table,
            guid,
            dir,
        }
    }

    pub fn pendulum() -> Self {
        Self::new(PENDULUM)
    }

    pub fn resources(&self) -> PathBuf {
        self.dir.path().join("resources")
    }

    pub fn uri(&self) -> String {
        triad::fmu::resource::path_to_uri(&self.resources())
    }

    pub fn vr(&self, name: &str) -> u32 {
        self.table
            .vars
            .iter()
            .find(|v| v.name == name)
            .unwrap_or_else(|| panic!("no variable {name}"))
            .vr
    }

    pub fn vrs(&self, c: Causality) -> Vec<u32> {
        self.table
            .vars
            .iter()
            .filter(|v| v.causality == c && v.ty == triad::variables::VarType::Real)
            .map(|v| v.vr)
            .collect()
    }
}

/// Captured log messages: (status, category, message).
pub type Log = Mutex<Vec<(i32, String, String)>>;

unsafe extern "C" fn capture(
    env: *mut c_void,
    _name: *const c_char,
    status: i32,
    category: *const c_char,
    fmt: *const c_char,
    msg: *const c_char,
) {
    let log = unsafe { &*(env as *const Log) };
    let fmt = unsafe { CStr::from_ptr(fmt) }
        .to_string_lossy()
        .into_owned();
    assert_eq!(
        fmt, "%s",
        "the logger must be called with the format \"%s\""
    );
    let cat = unsafe { CStr::from_ptr(category) }
        .to_string_lossy()
        .into_owned();
    let msg = unsafe { CStr::from_ptr(msg) }
        .to_string_lossy()
        .into_owned();
    log.lock().unwrap().push((status, cat, msg));
}

type Fixed6 = unsafe extern "C" fn(
    *mut c_void,
    *const c_char,
    i32,
    *const c_char,
    *const c_char,
    *const c_char,
);

pub fn callbacks(log: &Log) -> fmi2CallbackFunctions {
    // SAFETY (test): see the module docs for why this ABI cast is sound on the tested targets.
    let logger = unsafe {
        std::mem::transmute::<
            Fixed6,
            unsafe extern "C" fn(
                fmi2ComponentEnvironment,
                fmi2String,
                fmi2Status,
                fmi2String,
                fmi2String,
                ...
            ),
        >(capture as Fixed6)
    };
    fmi2CallbackFunctions {
        logger: Some(logger),
        allocateMemory: None,
        freeMemory: None,
        stepFinished: None,
        componentEnvironment: log as *const Log as *mut c_void,
    }
}

/// One instance driven through the exported C functions; frees itself on drop.
pub struct Fmu {
    pub c: fmi2Component,
    pub log: Box<Log>,
    _callbacks: Box<fmi2CallbackFunctions>,
}

// the test drives each instance from one thread at a time
unsafe impl Send for Fmu {}

pub fn instantiate_with(
    name: &str,
    ty: fmi2Type,
    guid: &str,
    uri: Option<&str>,
    logging_on: bool,
) -> (fmi2Component, Box<Log>, Box<fmi2CallbackFunctions>) {
    let log: Box<Log> = Box::new(Mutex::new(Vec::new()));
    let cb = Box::new(callbacks(&log));
    let name = CString::new(name).unwrap();
    let guid = CString::new(guid).unwrap();
    let uri = uri.map(|u| CString::new(u).unwrap());
    let c = unsafe {
        fmi2Instantiate(
            name.as_ptr(),
            ty,
            guid.as_ptr(),
            uri.as_ref().map_or(std::ptr::null(), |u| u.as_ptr()),
            &*cb,
            fmi2False,
            i32::from(logging_on),
        )
    };
    (c, log, cb)
}

impl Fmu {
    pub fn new(m: &TestModel) -> Self {
        Self::with_uri(m, &m.uri())
    }

    pub fn with_uri(m: &TestModel, uri: &str) -> Self {
        let (c, log, cb) = instantiate_with("inst", fmi2CoSimulation, &m.guid, Some(uri), false);
        assert!(
            !c.is_null(),
            "instantiate failed: {:?}",
            log.lock().unwrap()
        );
        Self {
            c,
            log,
            _callbacks: cb,
        }
    }

    /// Instantiated, experiment set up at t = 0, initialised.
    pub fn initialised(m: &TestModel) -> Self {
        let f = Self::new(m);
        assert_eq!(f.setup(0.0), fmi2OK);
        assert_eq!(unsafe { fmi2EnterInitializationMode(f.c) }, fmi2OK);
        assert_eq!(unsafe { fmi2ExitInitializationMode(f.c) }, fmi2OK);
        f
    }

    /// An instance with the Real parameters `vrs` set to `values` before initialisation.
    pub fn initialised_with(m: &TestModel, vrs: &[fmi2ValueReference], values: &[f64]) -> Self {
        let f = Self::new(m);
        assert_eq!(f.set_real(vrs, values), fmi2OK);
        assert_eq!(f.setup(0.0), fmi2OK);
        assert_eq!(unsafe { fmi2EnterInitializationMode(f.c) }, fmi2OK);
        assert_eq!(unsafe { fmi2ExitInitializationMode(f.c) }, fmi2OK);
        f
    }

    pub fn setup(&self, start: f64) -> fmi2Status {
        unsafe { fmi2SetupExperiment(self.c, fmi2False, 0.0, start, fmi2False, 0.0) }
    }

    pub fn set_real(&self, vrs: &[u32], vals: &[f64]) -> fmi2Status {
        unsafe { fmi2SetReal(self.c, vrs.as_ptr(), vrs.len(), vals.as_ptr()) }
    }

    pub fn get_real(&self, vrs: &[u32]) -> (fmi2Status, Vec<f64>) {
        let mut out = vec![f64::NAN; vrs.len()];
        let s = unsafe { fmi2GetReal(self.c, vrs.as_ptr(), vrs.len(), out.as_mut_ptr()) };
        (s, out)
    }

    pub fn step(&self, t: f64, h: f64) -> fmi2Status {
        unsafe { fmi2DoStep(self.c, t, h, fmi2False) }
    }

    pub fn last_successful_time(&self) -> f64 {
        let mut t = f64::NAN;
        assert_eq!(
            unsafe { fmi2GetRealStatus(self.c, fmi2LastSuccessfulTime, &mut t) },
            fmi2OK
        );
        t
    }

    pub fn messages(&self) -> Vec<(i32, String, String)> {
        self.log.lock().unwrap().clone()
    }

    /// The last logged message (panics when nothing was logged).
    pub fn last_message(&self) -> String {
        self.log
            .lock()
            .unwrap()
            .last()
            .map(|m| m.2.clone())
            .expect("a log message")
    }

    pub fn serialize(&self) -> Vec<u8> {
        let mut st: fmi2FMUstate = std::ptr::null_mut();
        assert_eq!(unsafe { fmi2GetFMUstate(self.c, &mut st) }, fmi2OK);
        let mut n = 0usize;
        assert_eq!(
            unsafe { fmi2SerializedFMUstateSize(self.c, st, &mut n) },
            fmi2OK
        );
        let mut buf = vec![0u8; n];
        assert_eq!(
            unsafe { fmi2SerializeFMUstate(self.c, st, buf.as_mut_ptr().cast(), n) },
            fmi2OK
        );
        assert_eq!(unsafe { fmi2FreeFMUstate(self.c, &mut st) }, fmi2OK);
        assert!(st.is_null());
        buf
    }

    pub fn deserialize(&self, bytes: &[u8]) -> fmi2Status {
        let mut st: fmi2FMUstate = std::ptr::null_mut();
        let s =
            unsafe { fmi2DeSerializeFMUstate(self.c, bytes.as_ptr().cast(), bytes.len(), &mut st) };
        if s != fmi2OK {
            return s;
        }
        let s = unsafe { fmi2SetFMUstate(self.c, st) };
        assert_eq!(unsafe { fmi2FreeFMUstate(self.c, &mut st) }, fmi2OK);
        s
    }
}

impl Drop for Fmu {
    fn drop(&mut self) {
        unsafe { fmi2FreeInstance(self.c) };
    }
}

/// Deterministic input signal for run `k` at step `n`.
pub fn input(k: usize, n: usize, i: usize) -> f64 {
    0.3 * ((k + 1) as f64) * ((n as f64) * 0.05 + i as f64).sin()
}

/// Runs `steps` steps of size `h` with inputs `input(k, n, ·)`, returning every Real output and
/// input after every step (bit patterns).
pub fn run(m: &TestModel, k: usize, steps: usize, h: f64) -> Vec<u64> {
    let f = Fmu::initialised(m);
    let ins = m.vrs(Causality::Input);
    let outs = m.vrs(Causality::Output);
    let mut trace = Vec::new();
    for n in 0..steps {
        let u: Vec<f64> = (0..ins.len()).map(|i| input(k, n, i)).collect();
        assert_eq!(f.set_real(&ins, &u), fmi2OK);
        assert_eq!(f.step(n as f64 * h, h), fmi2OK, "{:?}", f.messages());
        let (s, y) = f.get_real(&outs);
        assert_eq!(s, fmi2OK);
        trace.extend(y.iter().map(|x| x.to_bits()));
    }
    trace
}

/// The cdylib under test: `$TRIAD_CDYLIB` (CI sets it to the glibc 2.17 runtime of
/// `scripts/platforms.sh`), else the one built next to the test executable
/// (`target/<profile>/libtriad.so`).
pub fn cdylib() -> PathBuf {
    if let Some(p) = std::env::var_os("TRIAD_CDYLIB") {
        let p = PathBuf::from(p);
        assert!(p.is_file(), "TRIAD_CDYLIB={} is not a file", p.display());
        return p;
    }
    let exe = std::env::current_exe().unwrap();
    let deps = exe.parent().unwrap();
    let (file, _) = triad::package::cdylib_names();
    let newest = [deps.parent().unwrap(), deps]
        .into_iter()
        .map(|d| d.join(file))
        .filter_map(|p| Some((p.metadata().ok()?.modified().ok()?, p)))
        .max();
    if let Some((_, p)) = newest {
        return p;
    }
    panic!("{file} not found next to {}", exe.display());
}

/// splitmix64: small, seeded, good enough to pick calls.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    pub fn pick<T: Copy>(&mut self, xs: &[T]) -> T {
        xs[self.below(xs.len())]
    }
    pub fn chance(&mut self, p: f64) -> bool {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64 <= p
    }
}

/// `fmi2GetDirectionalDerivative` of `unknowns` along `seed` over `knowns`: the status and
/// the values (NaN where nothing was written).
pub fn dd(f: &Fmu, unknowns: &[u32], knowns: &[u32], seed: &[f64]) -> (fmi2Status, Vec<f64>) {
    let mut out = vec![f64::NAN; unknowns.len()];
    let s = unsafe {
        triad::ffi::getset::fmi2GetDirectionalDerivative(
            f.c,
            unknowns.as_ptr(),
            unknowns.len(),
            knowns.as_ptr(),
            knowns.len(),
            seed.as_ptr(),
            out.as_mut_ptr(),
        )
    };
    (s, out)
}
