//! FMI 3 helpers of the FMU tests: a shipped model as a [`TestModel`], an instance driven
//! through the exported `fmi3*` functions (linked), and a capturing `fmi3LogMessageCallback`
//! (not variadic, so an ordinary `extern "C"` function).

use super::api3::*;
use super::TestModel;
use std::ffi::{c_char, c_void, CStr, CString};
use std::sync::Mutex;
use triad::ffi::fmi3::types::*;
use triad::variables::fmi3::{Table3, Var3};
use triad::variables::{Causality, VarType};

/// A shipped model (`modelDescription/<name>/spec.toml`).
pub fn shipped(name: &str) -> TestModel {
    let text = triad::spec::bundled()
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, t)| *t)
        .unwrap_or_else(|| panic!("no shipped model {name}"));
    TestModel::new(text)
}

/// Captured messages: (status, category, message).
pub type Log3 = Mutex<Vec<(i32, String, String)>>;

unsafe extern "C" fn capture3(
    env: *mut c_void,
    status: fmi3Status,
    category: *const c_char,
    message: *const c_char,
) {
    let log = unsafe { &*(env as *const Log3) };
    let cat = unsafe { CStr::from_ptr(category) }
        .to_string_lossy()
        .into_owned();
    let msg = unsafe { CStr::from_ptr(message) }
        .to_string_lossy()
        .into_owned();
    log.lock().unwrap().push((status, cat, msg));
}

/// `fmi3InstantiateCoSimulation` with a capturing logger.
pub fn instantiate3(
    token: &str,
    path: Option<&str>,
    event_mode_used: bool,
    early_return_allowed: bool,
) -> (fmi3Instance, Box<Log3>) {
    let log: Box<Log3> = Box::new(Mutex::new(Vec::new()));
    let name = CString::new("inst3").unwrap();
    let token = CString::new(token).unwrap();
    let path = path.map(|p| CString::new(p).unwrap());
    let c = unsafe {
        fmi3InstantiateCoSimulation(
            name.as_ptr(),
            token.as_ptr(),
            path.as_ref().map_or(std::ptr::null(), |p| p.as_ptr()),
            false,
            false,
            event_mode_used,
            early_return_allowed,
            std::ptr::null(),
            0,
            &*log as *const Log3 as *mut c_void,
            Some(capture3),
            None,
        )
    };
    (c, log)
}

/// One FMI 3 instance; freed on drop.
pub struct Fmu3 {
    pub c: fmi3Instance,
    pub log: Box<Log3>,
    pub t3: Table3,
}

// each instance is driven from one thread at a time
unsafe impl Send for Fmu3 {}

/// What `fmi3DoStep` reports: (status, eventHandlingNeeded, terminateSimulation, earlyReturn,
/// lastSuccessfulTime).
pub type StepResult = (fmi3Status, bool, bool, bool, f64);

impl Fmu3 {
    pub fn new(m: &TestModel) -> Self {
        let path = m.resources().to_string_lossy().into_owned();
        let (c, log) = instantiate3(&m.guid, Some(&path), false, false);
        assert!(
            !c.is_null(),
            "instantiate failed: {:?}",
            log.lock().unwrap()
        );
        Self {
            c,
            log,
            t3: Table3::new(&m.table),
        }
    }

    /// Instantiated, initialised at t = 0, in Step Mode.
    pub fn initialised(m: &TestModel) -> Self {
        let f = Self::new(m);
        assert_eq!(f.enter_init(0.0), fmi3OK, "{:?}", f.messages());
        assert_eq!(unsafe { fmi3ExitInitializationMode(f.c) }, fmi3OK);
        f
    }

    pub fn enter_init(&self, start: f64) -> fmi3Status {
        unsafe { fmi3EnterInitializationMode(self.c, false, 0.0, start, false, 0.0) }
    }

    pub fn var(&self, name: &str) -> &Var3 {
        self.t3
            .by_name(name)
            .unwrap_or_else(|| panic!("no FMI 3 variable {name}"))
    }

    /// The Float64 variables of causality `c`, with their total size.
    pub fn vrs(&self, m: &TestModel, c: Causality) -> (Vec<u32>, usize) {
        let vars: Vec<&Var3> = self
            .t3
            .vars
            .iter()
            .filter(|v| {
                let first = m.table.by_vr(v.members[0]).unwrap();
                first.causality == c && first.ty == VarType::Real
            })
            .collect();
        (
            vars.iter().map(|v| v.vr).collect(),
            vars.iter().map(|v| v.len()).sum(),
        )
    }

    pub fn get_f64(&self, vrs: &[u32], n: usize) -> (fmi3Status, Vec<f64>) {
        let mut out = vec![f64::NAN; n];
        let s = unsafe { fmi3GetFloat64(self.c, vrs.as_ptr(), vrs.len(), out.as_mut_ptr(), n) };
        (s, out)
    }

    pub fn set_f64(&self, vrs: &[u32], vals: &[f64]) -> fmi3Status {
        unsafe { fmi3SetFloat64(self.c, vrs.as_ptr(), vrs.len(), vals.as_ptr(), vals.len()) }
    }

    pub fn step(&self, t: f64, h: f64) -> StepResult {
        let (mut e, mut term, mut early, mut last) = (true, true, true, f64::NAN);
        let s = unsafe {
            fmi3DoStep(
                self.c, t, h, false, &mut e, &mut term, &mut early, &mut last,
            )
        };
        (s, e, term, early, last)
    }

    pub fn messages(&self) -> Vec<(i32, String, String)> {
        self.log.lock().unwrap().clone()
    }

    pub fn last_message(&self) -> String {
        self.messages()
            .last()
            .map(|m| m.2.clone())
            .expect("a message")
    }
}

impl Drop for Fmu3 {
    fn drop(&mut self) {
        unsafe { fmi3FreeInstance(self.c) };
    }
}

/// `fmi3GetDirectionalDerivative` of `unknowns` along `seed` over `knowns`, `n` values out (the
/// unknowns' sizes summed): the status and the values.
pub fn directional3(
    f: &Fmu3,
    unknowns: &[u32],
    knowns: &[u32],
    seed: &[f64],
    n: usize,
) -> (fmi3Status, Vec<f64>) {
    let mut out = vec![0.0; n];
    // SAFETY: the pointers and lengths come from live slices of the stated sizes.
    let s = unsafe {
        fmi3GetDirectionalDerivative(
            f.c,
            unknowns.as_ptr(),
            unknowns.len(),
            knowns.as_ptr(),
            knowns.len(),
            seed.as_ptr(),
            seed.len(),
            out.as_mut_ptr(),
            n,
        )
    };
    (s, out)
}

/// Asserts that `fmi3GetAdjointDerivative` is the transpose of the directional derivative
/// `jv = J v` of `unknowns` over `knowns`: `wᵀ(J v) = (Jᵀ w)ᵀ v` for a fixed `w`, not zero.
pub fn assert_adjoint_is_transpose(
    f: &Fmu3,
    unknowns: &[u32],
    knowns: &[u32],
    v: &[f64],
    jv: &[f64],
) {
    let w: Vec<f64> = (0..jv.len()).map(|i| 0.5 - 0.1 * i as f64).collect();
    let mut jtw = vec![0.0; v.len()];
    // SAFETY: the pointers and lengths come from live slices of the stated sizes.
    let s = unsafe {
        fmi3GetAdjointDerivative(
            f.c,
            unknowns.as_ptr(),
            unknowns.len(),
            knowns.as_ptr(),
            knowns.len(),
            w.as_ptr(),
            w.len(),
            jtw.as_mut_ptr(),
            jtw.len(),
        )
    };
    assert_eq!(s, fmi3OK, "{}", f.last_message());
    let lhs: f64 = w.iter().zip(jv).map(|(a, b)| a * b).sum();
    let rhs: f64 = jtw.iter().zip(v).map(|(a, b)| a * b).sum();
    assert!(
        (lhs - rhs).abs() <= 1e-12 * (1.0 + lhs.abs()),
        "{lhs} {rhs}"
    );
    assert!(lhs.abs() > 1e-3);
}
