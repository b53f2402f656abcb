//! FMI 3.0 Co-Simulation life cycle through the exported `fmi3*` functions, in-process:
//! instantiation with the instantiation token and a resource *path* (with or without a trailing
//! separator); a wrong token, Event Mode, Model Exchange, Scheduled Execution and NULL
//! arguments refused with NULL and a message; wrong-state calls refused and the instance
//! usable; `fmi3DoStep`'s outputs; the same step sequence as FMI 2 gives bit-identical
//! outputs; the unsupported functions return `fmi3Error` with a message and never crash.

mod fmu_support;

use fmu_support::fmi3::*;
use fmu_support::*;
use std::ffi::{c_void, CStr, CString};
use triad::ffi::fmi3::cosim::*;
use triad::ffi::fmi3::getset::*;
use triad::ffi::fmi3::lifecycle::*;
use triad::ffi::fmi3::types::*;
use triad::ffi::fmi3::unsupported::*;
use triad::ffi::types::fmi2OK;
use triad::variables::Causality;

#[test]
fn version_is_3_0() {
    let v = unsafe { CStr::from_ptr(fmi3GetVersion()) };
    assert_eq!(v.to_str().unwrap(), "3.0");
}

#[test]
fn the_resource_path_is_taken_with_or_without_a_trailing_separator() {
    let m = TestModel::pendulum();
    let path = m.resources().to_string_lossy().into_owned();
    for p in [
        path.clone(),
        format!("{path}/"),
        format!("{path}{}", std::path::MAIN_SEPARATOR),
    ] {
        let (c, log) = instantiate3(&m.guid, Some(&p), false, true);
        assert!(!c.is_null(), "{p}: {:?}", log.lock().unwrap());
        unsafe { fmi3FreeInstance(c) };
    }
}

#[test]
fn wrong_token_event_mode_and_null_arguments_give_null_with_a_message() {
    let m = TestModel::pendulum();
    let path = m.resources().to_string_lossy().into_owned();
    let (c, log) = instantiate3(
        "{00000000-0000-5000-8000-000000000000}",
        Some(&path),
        false,
        false,
    );
    assert!(c.is_null());
    let msgs = log.lock().unwrap().clone();
    assert!(
        msgs.iter().any(|(s, cat, msg)| *s == fmi3Error
            && cat == "logStatusError"
            && msg.contains("instantiationToken mismatch")),
        "{msgs:?}"
    );
    let (c, log) = instantiate3(&m.guid, Some(&path), true, false);
    assert!(c.is_null());
    assert!(log.lock().unwrap()[0].2.contains("eventModeUsed"));
    let (c, log) = instantiate3(&m.guid, None, false, false);
    assert!(c.is_null());
    assert!(log.lock().unwrap()[0].2.contains("resourcePath is NULL"));
    let (c, log) = instantiate3(&m.guid, Some("relative/dir"), false, false);
    assert!(c.is_null());
    assert!(!log.lock().unwrap().is_empty());
    // NULL token, NULL name, no logger at all: NULL and no crash
    let name = CString::new("x").unwrap();
    let p = CString::new(path.clone()).unwrap();
    let c = unsafe {
        fmi3InstantiateCoSimulation(
            name.as_ptr(),
            std::ptr::null(),
            p.as_ptr(),
            false,
            false,
            false,
            false,
            std::ptr::null(),
            0,
            std::ptr::null_mut(),
            None,
            None,
        )
    };
    assert!(c.is_null());
    let tok = CString::new(m.guid.clone()).unwrap();
    let c = unsafe {
        fmi3InstantiateCoSimulation(
            std::ptr::null(),
            tok.as_ptr(),
            p.as_ptr(),
            false,
            false,
            false,
            false,
            std::ptr::null(),
            0,
            std::ptr::null_mut(),
            None,
            None,
        )
    };
    assert!(c.is_null());
}

unsafe extern "C" fn capture(
    env: *mut c_void,
    status: fmi3Status,
    _c: fmi3String,
    msg: fmi3String,
) {
    let log = unsafe { &*(env as *const Log3) };
    let msg = unsafe { CStr::from_ptr(msg) }
        .to_string_lossy()
        .into_owned();
    log.lock().unwrap().push((status, String::new(), msg));
}

#[test]
fn model_exchange_and_scheduled_execution_give_null_with_a_message() {
    let m = TestModel::pendulum();
    let log: Log3 = std::sync::Mutex::new(Vec::new());
    let env = &log as *const Log3 as *mut c_void;
    let name = CString::new("me").unwrap();
    let tok = CString::new(m.guid.clone()).unwrap();
    let p = CString::new(m.resources().to_string_lossy().into_owned()).unwrap();
    let c = unsafe {
        fmi3InstantiateModelExchange(
            name.as_ptr(),
            tok.as_ptr(),
            p.as_ptr(),
            false,
            false,
            env,
            Some(capture),
        )
    };
    assert!(c.is_null());
    let c = unsafe {
        fmi3InstantiateScheduledExecution(
            name.as_ptr(),
            tok.as_ptr(),
            p.as_ptr(),
            false,
            false,
            env,
            Some(capture),
            None,
            None,
            None,
        )
    };
    assert!(c.is_null());
    let msgs = log.lock().unwrap().clone();
    assert_eq!(msgs.len(), 2);
    assert!(msgs[0].2.starts_with("fmi3InstantiateModelExchange: "));
    assert!(msgs[1].2.starts_with("fmi3InstantiateScheduledExecution: "));
    // without a logger: NULL, no crash
    let c = unsafe {
        fmi3InstantiateModelExchange(
            std::ptr::null(),
            std::ptr::null(),
            std::ptr::null(),
            false,
            false,
            std::ptr::null_mut(),
            None,
        )
    };
    assert!(c.is_null());
}

#[test]
fn wrong_state_calls_are_refused_and_the_instance_keeps_working() {
    let m = TestModel::pendulum();
    let f = Fmu3::new(&m);
    // stepping, getting, exiting before initialisation
    assert_eq!(f.step(0.0, 0.01).0, fmi3Error);
    assert!(
        f.last_message()
            .contains("fmi3DoStep is not allowed in Instantiated mode"),
        "{}",
        f.last_message()
    );
    assert_eq!(unsafe { fmi3ExitInitializationMode(f.c) }, fmi3Error);
    assert_eq!(unsafe { fmi3Terminate(f.c) }, fmi3Error);
    let (vrs, n) = f.vrs(&m, Causality::Output);
    assert_eq!(f.get_f64(&vrs, n).0, fmi3Error);
    // a bad experiment is refused as a whole: still Instantiated
    assert_eq!(
        unsafe { fmi3EnterInitializationMode(f.c, true, -1.0, 0.0, false, 0.0) },
        fmi3Error
    );
    assert_eq!(
        unsafe { fmi3EnterInitializationMode(f.c, false, 0.0, 1.0, true, 0.5) },
        fmi3Error
    );
    assert_eq!(f.enter_init(0.0), fmi3OK);
    assert_eq!(f.enter_init(0.0), fmi3Error);
    assert!(f
        .last_message()
        .contains("fmi3EnterInitializationMode is not allowed"));
    assert_eq!(f.step(0.0, 0.01).0, fmi3Error);
    assert_eq!(unsafe { fmi3ExitInitializationMode(f.c) }, fmi3OK);
    // a communication point that is not the instance time
    assert_eq!(f.step(0.5, 0.01).0, fmi3Error);
    let (s, e, term, early, last) = f.step(0.0, 0.01);
    assert_eq!((s, e, term, early), (fmi3OK, false, false, false));
    assert_eq!(last, 0.01);
    assert_eq!(unsafe { fmi3Terminate(f.c) }, fmi3OK);
    assert_eq!(f.step(0.01, 0.01).0, fmi3Error);
    assert_eq!(unsafe { fmi3Reset(f.c) }, fmi3OK);
    assert_eq!(f.enter_init(0.0), fmi3OK);
}

#[test]
fn null_pointers_are_refused() {
    let m = TestModel::pendulum();
    let f = Fmu3::initialised(&m);
    let (mut e, mut t, mut r, mut last) = (false, false, false, 0.0);
    let null_b: *mut bool = std::ptr::null_mut();
    unsafe {
        assert_eq!(
            fmi3DoStep(f.c, 0.0, 0.01, false, null_b, &mut t, &mut r, &mut last),
            fmi3Error
        );
        assert_eq!(
            fmi3DoStep(f.c, 0.0, 0.01, false, &mut e, null_b, &mut r, &mut last),
            fmi3Error
        );
        assert_eq!(
            fmi3DoStep(f.c, 0.0, 0.01, false, &mut e, &mut t, null_b, &mut last),
            fmi3Error
        );
        assert_eq!(
            fmi3DoStep(
                f.c,
                0.0,
                0.01,
                false,
                &mut e,
                &mut t,
                &mut r,
                std::ptr::null_mut()
            ),
            fmi3Error
        );
        // nothing was stepped
        assert_eq!(
            fmi3DoStep(f.c, 0.0, 0.01, false, &mut e, &mut t, &mut r, &mut last),
            fmi3OK
        );
        assert_eq!(last, 0.01);
        // NULL arrays with a positive length
        let vr = [f.var("joint.shoulder.q").vr];
        let mut out = [0.0];
        assert_eq!(
            fmi3GetFloat64(f.c, std::ptr::null(), 1, out.as_mut_ptr(), 1),
            fmi3Error
        );
        assert_eq!(
            fmi3GetFloat64(f.c, vr.as_ptr(), 1, std::ptr::null_mut(), 1),
            fmi3Error
        );
        assert_eq!(
            fmi3SetFloat64(f.c, vr.as_ptr(), 1, std::ptr::null(), 1),
            fmi3Error
        );
        // a NULL instance
        let null = std::ptr::null_mut();
        assert_eq!(
            fmi3EnterInitializationMode(null, false, 0.0, 0.0, false, 0.0),
            fmi3Error
        );
        assert_eq!(fmi3ExitInitializationMode(null), fmi3Error);
        assert_eq!(
            fmi3DoStep(null, 0.0, 0.01, false, &mut e, &mut t, &mut r, &mut last),
            fmi3Error
        );
        assert_eq!(
            fmi3GetFloat64(null, vr.as_ptr(), 1, out.as_mut_ptr(), 1),
            fmi3Error
        );
        assert_eq!(fmi3Terminate(null), fmi3Error);
        assert_eq!(fmi3Reset(null), fmi3Error);
        assert_eq!(fmi3EnterEventMode(null), fmi3Error);
        fmi3FreeInstance(null);
    }
}

#[test]
fn unsupported_functions_return_error_with_a_message_and_the_instance_keeps_working() {
    let m = TestModel::pendulum();
    let f = Fmu3::initialised(&m);
    let vr = [1u32];
    let mut x = [0.0f64; 4];
    let mut n = 0usize;
    let mut b = false;
    unsafe {
        assert_eq!(fmi3EnterEventMode(f.c), fmi3Error);
        assert!(f.last_message().starts_with("fmi3EnterEventMode: "));
        assert!(f.last_message().contains("Event Mode"));
        assert_eq!(
            fmi3GetDirectionalDerivative(
                f.c,
                vr.as_ptr(),
                1,
                vr.as_ptr(),
                1,
                x.as_ptr(),
                1,
                x.as_mut_ptr(),
                1
            ),
            fmi3Error
        );
        assert!(
            f.last_message()
                .contains("is not an output or state derivative that can be differentiated"),
            "{}",
            f.last_message()
        );
        assert_eq!(
            fmi3GetAdjointDerivative(
                f.c,
                vr.as_ptr(),
                1,
                vr.as_ptr(),
                1,
                x.as_ptr(),
                1,
                x.as_mut_ptr(),
                1
            ),
            fmi3Error
        );
        // an input is no unknown: refused with a message (tests/fmu_directional.rs: the rest)
        assert!(f.last_message().contains("is not an output"));
        assert_eq!(fmi3SetTime(f.c, 0.0), fmi3Error);
        assert!(f.last_message().starts_with("fmi3SetTime: "));
        assert_eq!(fmi3GetNumberOfContinuousStates(f.c, &mut n), fmi3Error);
        assert_eq!(fmi3GetContinuousStates(f.c, x.as_mut_ptr(), 4), fmi3Error);
        assert_eq!(
            fmi3CompletedIntegratorStep(f.c, false, &mut b, &mut b),
            fmi3Error
        );
        assert_eq!(fmi3ActivateModelPartition(f.c, 1, 0.0), fmi3Error);
        assert_eq!(fmi3EnterConfigurationMode(f.c), fmi3Error);
        assert_eq!(
            fmi3GetShiftDecimal(f.c, vr.as_ptr(), 1, x.as_mut_ptr()),
            fmi3Error
        );
        assert_eq!(
            fmi3SetIntervalFraction(f.c, vr.as_ptr(), 1, std::ptr::null(), std::ptr::null()),
            fmi3Error
        );
        assert_eq!(
            fmi3GetNumberOfVariableDependencies(f.c, 1, &mut n),
            fmi3Error
        );
        assert_eq!(fmi3EnterStepMode(f.c), fmi3Error);
        assert_eq!(
            fmi3UpdateDiscreteStates(f.c, &mut b, &mut b, &mut b, &mut b, &mut b, x.as_mut_ptr()),
            fmi3Error
        );
        // all NULL: still no crash
        assert_eq!(
            fmi3GetEventIndicators(f.c, std::ptr::null_mut(), 7),
            fmi3Error
        );
    }
    assert!(f.messages().iter().all(|(s, _, _)| *s == fmi3Error));
    assert_eq!(f.step(0.0, 0.01).0, fmi3OK);
}

/// Steps `model` through FMI 2 and FMI 3 with the same inputs; every output after every step
/// must have the same bits.
fn same_as_fmi2(model: &str, steps: usize, h: f64) {
    let m = shipped(model);
    let f2 = Fmu::initialised(&m);
    let f3 = Fmu3::initialised(&m);
    let ins2 = m.vrs(Causality::Input);
    let outs2 = m.vrs(Causality::Output);
    let (ins3, n_in) = f3.vrs(&m, Causality::Input);
    let (outs3, n_out) = f3.vrs(&m, Causality::Output);
    assert_eq!((n_in, n_out), (ins2.len(), outs2.len()));
    assert!(n_in > 0, "{model} has inputs");
    for n in 0..steps {
        let u: Vec<f64> = (0..n_in).map(|i| input(1, n, i)).collect();
        assert_eq!(f2.set_real(&ins2, &u), fmi2OK);
        assert_eq!(f3.set_f64(&ins3, &u), fmi3OK);
        let t = n as f64 * h;
        assert_eq!(f2.step(t, h), fmi2OK);
        let (s, e, term, early, last) = f3.step(t, h);
        assert_eq!(
            (s, e, term, early),
            (fmi3OK, false, false, false),
            "{:?}",
            f3.messages()
        );
        assert_eq!(last.to_bits(), f2.last_successful_time().to_bits());
        let (s2, y2) = f2.get_real(&outs2);
        let (s3, y3) = f3.get_f64(&outs3, n_out);
        assert_eq!((s2, s3), (fmi2OK, fmi3OK));
        let b2: Vec<u64> = y2.iter().map(|x| x.to_bits()).collect();
        let b3: Vec<u64> = y3.iter().map(|x| x.to_bits()).collect();
        assert_eq!(b2, b3, "{model}: outputs differ after step {n}");
        let (s, time) = f3.get_f64(&[0], 1);
        assert_eq!(s, fmi3OK);
        assert_eq!(time[0], last);
    }
}

#[test]
fn robot_arm_gives_the_fmi2_results_bit_for_bit() {
    same_as_fmi2("robot_arm", 100, 0.01);
}

#[test]
fn double_pendulum_gives_the_fmi2_results_bit_for_bit() {
    same_as_fmi2("double_pendulum", 100, 0.01);
}
