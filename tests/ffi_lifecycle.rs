//! The FMI 2.0.4 call-sequence contract, exercised through the exported C functions in-process:
//! `fmi2Instantiate` accepts every `file:` URI form and refuses a wrong GUID or Model Exchange
//! (NULL, logged); illegal calls (wrong mode, output set, unknown VR, NULL pointers, NaN)
//! return `fmi2Error` with a logged reason, change nothing, and the instance keeps working; a
//! panic returns `fmi2Fatal` and poisons only that instance.

mod fmu_support;

use fmu_support::*;
use std::ffi::CString;
use triad::ffi::common::*;
use triad::ffi::cosim::*;
use triad::ffi::getset::*;
use triad::ffi::types::*;
use triad::variables::Causality;

#[test]
fn version_and_platform() {
    let v = unsafe { std::ffi::CStr::from_ptr(fmi2GetVersion()) };
    assert_eq!(v.to_str().unwrap(), "2.0");
    let p = unsafe { std::ffi::CStr::from_ptr(fmi2GetTypesPlatform()) };
    assert_eq!(p.to_str().unwrap(), "default");
}

#[test]
fn every_resource_uri_form_instantiates() {
    let m = TestModel::pendulum();
    let path = m.resources().to_string_lossy().into_owned();
    assert!(
        path.contains(' '),
        "the temp dir name has a space to test percent-encoding"
    );
    let enc = m.uri(); // file:///...%20...
    let raw_path = enc.trim_start_matches("file://").to_string();
    for uri in [
        enc.clone(),
        format!("{enc}/"),
        format!("file:{raw_path}"),
        format!("file://localhost{raw_path}"),
        format!("file://localhost{raw_path}/"),
        format!("file://{path}"), // unencoded space, tolerated
    ] {
        let f = Fmu::with_uri(&m, &uri);
        assert_eq!(f.setup(0.0), fmi2OK, "{uri}");
    }
}

#[test]
fn wrong_guid_unknown_type_and_bad_uri_give_null_with_a_message() {
    let m = TestModel::pendulum();
    let (c, log, _cb) = instantiate_with(
        "a",
        fmi2CoSimulation,
        "{00000000-0000-5000-8000-000000000000}",
        Some(&m.uri()),
        false,
    );
    assert!(c.is_null());
    assert!(log
        .lock()
        .unwrap()
        .iter()
        .any(|(s, _, msg)| *s == fmi2Error && msg.contains("GUID mismatch")));
    let (c, log, _cb) = instantiate_with("b", fmi2ModelExchange, &m.guid, Some(&m.uri()), false);
    assert!(c.is_null());
    assert!(log.lock().unwrap()[0].2.contains("Co-Simulation only"));
    for uri in [
        None,
        Some("http://example.com/resources"),
        Some("file:///nonexistent/dir"),
    ] {
        let (c, log, _cb) = instantiate_with("c", fmi2CoSimulation, &m.guid, uri, false);
        assert!(c.is_null(), "{uri:?}");
        assert_eq!(log.lock().unwrap().len(), 1, "{uri:?}");
    }
    // a NULL callbacks struct is tolerated for failures too
    let name = CString::new("d").unwrap();
    let c = unsafe {
        fmi2Instantiate(
            name.as_ptr(),
            fmi2CoSimulation,
            name.as_ptr(),
            std::ptr::null(),
            std::ptr::null(),
            0,
            0,
        )
    };
    assert!(c.is_null());
}

#[test]
fn illegal_calls_are_rejected_logged_and_harmless() {
    let m = TestModel::pendulum();
    let f = Fmu::new(&m);
    let ins = m.vrs(Causality::Input);
    let outs = m.vrs(Causality::Output);
    assert!(!ins.is_empty() && !outs.is_empty());

    // DoStep and GetReal before initialisation
    assert_eq!(f.step(0.0, 0.01), fmi2Error);
    assert!(
        f.last_message()
            .contains("fmi2DoStep is not allowed in Instantiated mode"),
        "{}",
        f.last_message()
    );
    assert_eq!(f.get_real(&outs).0, fmi2Error);
    assert_eq!(unsafe { fmi2ExitInitializationMode(f.c) }, fmi2Error);
    assert_eq!(unsafe { fmi2Terminate(f.c) }, fmi2Error);

    assert_eq!(f.setup(0.0), fmi2OK);
    assert_eq!(unsafe { fmi2EnterInitializationMode(f.c) }, fmi2OK);
    assert_eq!(unsafe { fmi2ExitInitializationMode(f.c) }, fmi2OK);
    let (_, before) = f.get_real(&outs);

    // set an output
    assert_eq!(f.set_real(&outs[..1], &[1.0]), fmi2Error);
    assert!(
        f.last_message().contains("is an output"),
        "{}",
        f.last_message()
    );
    // unknown value reference, all-or-nothing: the valid first value is not applied either
    let (_, u0) = f.get_real(&ins[..1]);
    assert_eq!(f.set_real(&[ins[0], 999_999], &[5.0, 1.0]), fmi2Error);
    assert!(f.last_message().contains("unknown value reference 999999"));
    assert_eq!(f.get_real(&ins[..1]).1, u0);
    assert_eq!(f.get_real(&[999_999]).0, fmi2Error);
    // NaN and Inf inputs
    for bad in [f64::NAN, f64::INFINITY] {
        assert_eq!(f.set_real(&ins[..1], &[bad]), fmi2Error);
        assert!(f.last_message().contains("not finite"));
    }
    assert_eq!(f.get_real(&ins[..1]).1, u0);
    // a fixed parameter after initialisation
    let ms = m.vr("solver.max_step");
    assert_eq!(f.set_real(&[ms], &[0.01]), fmi2Error);
    assert!(
        f.last_message().contains("fixed parameter"),
        "{}",
        f.last_message()
    );
    // NULL pointers
    let s = unsafe { fmi2GetReal(f.c, std::ptr::null(), 1, std::ptr::null_mut()) };
    assert_eq!(s, fmi2Error);
    assert!(f.last_message().contains("NULL"));
    let s = unsafe { fmi2SetReal(f.c, ins.as_ptr(), 1, std::ptr::null()) };
    assert_eq!(s, fmi2Error);
    assert_eq!(
        unsafe { fmi2GetRealStatus(f.c, fmi2LastSuccessfulTime, std::ptr::null_mut()) },
        fmi2Error
    );
    assert_eq!(
        unsafe { fmi2DoStep(std::ptr::null_mut(), 0.0, 0.01, 0) },
        fmi2Error
    );
    // nvr = 0 with NULL arrays is fine
    assert_eq!(
        unsafe { fmi2GetReal(f.c, std::ptr::null(), 0, std::ptr::null_mut()) },
        fmi2OK
    );
    // wrong communication point, bad step size
    assert_eq!(f.step(0.5, 0.01), fmi2Error);
    assert!(f
        .last_message()
        .contains("does not match the instance time"));
    assert_eq!(f.step(0.0, -1.0), fmi2Error);
    assert_eq!(f.step(0.0, f64::NAN), fmi2Error);
    // no Boolean/String variables
    let vr = [0u32];
    let mut b = [0i32];
    assert_eq!(
        unsafe { fmi2GetBoolean(f.c, vr.as_ptr(), 1, b.as_mut_ptr()) },
        fmi2Error
    );
    // unsupported functions
    assert_eq!(unsafe { fmi2CancelStep(f.c) }, fmi2Error);
    assert!(f.last_message().contains("synchronous"));
    let mut d = [0.0];
    assert_eq!(
        unsafe {
            fmi2GetDirectionalDerivative(
                f.c,
                vr.as_ptr(),
                1,
                vr.as_ptr(),
                1,
                d.as_ptr(),
                d.as_mut_ptr(),
            )
        },
        fmi2Error
    );
    assert_eq!(
        unsafe { fmi2SetRealInputDerivatives(f.c, vr.as_ptr(), 1, [1].as_ptr(), d.as_ptr()) },
        fmi2Error
    );
    assert_eq!(
        unsafe { fmi2GetRealOutputDerivatives(f.c, vr.as_ptr(), 1, [1].as_ptr(), d.as_mut_ptr()) },
        fmi2Error
    );
    // every rejection was logged as an error in logStatusError
    assert!(f
        .messages()
        .iter()
        .all(|(s, c, _)| *s == fmi2Error && c == "logStatusError"));

    // nothing changed, and the instance still works
    assert_eq!(f.get_real(&outs), (fmi2OK, before));
    assert_eq!(f.set_real(&ins[..1], &[0.5]), fmi2OK);
    assert_eq!(f.step(0.0, 0.01), fmi2OK);
    assert_eq!(f.last_successful_time(), 0.01);
    let mut term = 1;
    assert_eq!(
        unsafe { fmi2GetBooleanStatus(f.c, fmi2Terminated, &mut term) },
        fmi2OK
    );
    assert_eq!(term, fmi2False);
    assert_eq!(unsafe { fmi2Terminate(f.c) }, fmi2OK);
    assert_eq!(f.step(0.01, 0.01), fmi2Error);
    // reset: back to Instantiated with start values
    assert_eq!(unsafe { fmi2Reset(f.c) }, fmi2OK);
    assert_eq!(f.setup(0.0), fmi2OK);
    assert_eq!(unsafe { fmi2EnterInitializationMode(f.c) }, fmi2OK);
    assert_eq!(f.get_real(&ins[..1]).1, vec![0.0]);
}

#[test]
fn debug_logging_categories() {
    let m = TestModel::pendulum();
    let f = Fmu::new(&m);
    let cat = |names: &[&str], on| {
        let cs: Vec<CString> = names.iter().map(|n| CString::new(*n).unwrap()).collect();
        let ps: Vec<fmi2String> = cs.iter().map(|c| c.as_ptr()).collect();
        unsafe { fmi2SetDebugLogging(f.c, on, ps.len(), ps.as_ptr()) }
    };
    assert_eq!(cat(&["logEvents", "logStatusError"], fmi2True), fmi2OK);
    assert_eq!(cat(&["logNoSuchThing"], fmi2True), fmi2Error);
    assert!(f
        .last_message()
        .contains("unknown log category 'logNoSuchThing'"));
    // events are logged when enabled
    f.log.lock().unwrap().clear();
    assert_eq!(unsafe { fmi2EnterInitializationMode(f.c) }, fmi2OK);
    assert!(f
        .messages()
        .iter()
        .any(|(s, c, _)| *s == fmi2OK && c == "logEvents"));
    // all off: even errors are silent
    assert_eq!(cat(&[], fmi2False), fmi2OK);
    f.log.lock().unwrap().clear();
    assert_eq!(f.step(0.0, 0.1), fmi2Error);
    assert!(f.messages().is_empty());
    // logAll switches everything back on
    assert_eq!(cat(&["logAll"], fmi2True), fmi2OK);
    assert_eq!(f.step(0.0, 0.1), fmi2Error);
    assert_eq!(f.messages().len(), 1);
}

#[test]
fn a_panic_is_fatal_and_poisons_only_its_instance() {
    let m = TestModel::pendulum();
    let a = Fmu::initialised(&m);
    let b = Fmu::initialised(&m);
    assert_eq!(unsafe { triad::ffi::triad_test_panic(a.c) }, fmi2Fatal);
    assert!(a.messages().iter().any(|(s, c, msg)| *s == fmi2Fatal
        && c == "logStatusFatal"
        && msg.contains("injected test panic")));
    assert_eq!(a.step(0.0, 0.01), fmi2Error);
    assert!(a.last_message().contains("fmi2FreeInstance"));
    assert_eq!(unsafe { fmi2Reset(a.c) }, fmi2Error);
    assert_eq!(b.step(0.0, 0.01), fmi2OK);
}

#[test]
fn parameters_before_initialisation_and_tunables_between_steps() {
    let m = TestModel::pendulum();
    let f = Fmu::new(&m);
    let ms = m.vr("solver.max_step");
    let damping = m.vr("joint.shoulder.damping");
    assert_eq!(f.set_real(&[ms], &[0.0005]), fmi2OK);
    assert_eq!(
        f.set_real(&[ms], &[-1.0]),
        fmi2Error,
        "invalid value rejected by write_param"
    );
    assert_eq!(unsafe { fmi2EnterInitializationMode(f.c) }, fmi2OK);
    assert_eq!(f.get_real(&[ms]).1, vec![0.0005]);
    // outputs (the InitialUnknowns) are available in Initialization Mode
    let (s, y) = f.get_real(&m.vrs(Causality::Output));
    assert_eq!(s, fmi2OK);
    assert!(y.iter().all(|x| x.is_finite()));
    assert_eq!(
        f.set_real(&[ms], &[0.002]),
        fmi2OK,
        "exact parameters may be set in Initialization Mode"
    );
    assert_eq!(unsafe { fmi2ExitInitializationMode(f.c) }, fmi2OK);
    assert_eq!(
        f.set_real(&[damping], &[0.3]),
        fmi2OK,
        "tunable between steps"
    );
    assert_eq!(f.get_real(&[damping]).1, vec![0.3]);
    assert_eq!(f.step(0.0, 0.01), fmi2OK);
    // a new stiffness shows in the energy output at once: E' − E = ½ k q²
    let (stiff, q, e) = (
        m.vr("joint.shoulder.stiffness"),
        m.vr("joint.shoulder.q"),
        m.vr("system.energy"),
    );
    let before = f.get_real(&[q, e]).1;
    assert_eq!(f.set_real(&[stiff], &[2.0]), fmi2OK);
    let after = f.get_real(&[e]).1[0];
    let expected = before[1] + 0.5 * 2.0 * before[0] * before[0];
    assert!(
        (after - expected).abs() <= 1e-12 * expected.abs().max(1.0) && before[0] != 0.0,
        "energy {} → {after}, expected {expected}",
        before[1]
    );
    let order = m.vr("solver.order");
    let mut v = [0i32];
    assert_eq!(
        unsafe { fmi2GetInteger(f.c, [order].as_ptr(), 1, v.as_mut_ptr()) },
        fmi2OK
    );
    assert_eq!(v[0], 2);
}

#[test]
fn parameters_that_break_a_joint_rule_are_refused_at_initialisation_and_can_be_fixed() {
    let m = TestModel::pendulum();
    let f = Fmu::new(&m);
    // each entry is a valid number, but the tensor violates the triangle inequality: the
    // rule involving several parameters is checked by fmi2EnterInitializationMode, which
    // refuses and leaves the instance in Instantiated mode with the parameters as set
    let ixx = m.vr("body.link1.inertia[1,1]");
    assert_eq!(f.set_real(&[ixx], &[100.0]), fmi2OK);
    assert_eq!(unsafe { fmi2EnterInitializationMode(f.c) }, fmi2Error);
    assert!(
        f.last_message().contains("triangle inequality"),
        "{}",
        f.last_message()
    );
    assert_eq!(unsafe { fmi2ExitInitializationMode(f.c) }, fmi2Error);
    assert!(
        f.last_message().contains("Instantiated mode"),
        "{}",
        f.last_message()
    );
    // correct it and go on
    assert_eq!(f.set_real(&[ixx], &[0.0834]), fmi2OK);
    assert_eq!(unsafe { fmi2EnterInitializationMode(f.c) }, fmi2OK);
    assert_eq!(unsafe { fmi2ExitInitializationMode(f.c) }, fmi2OK);
    assert_eq!(f.step(0.0, 0.01), fmi2OK);
    // reset: back to the spec's values, usable again
    assert_eq!(unsafe { fmi2Reset(f.c) }, fmi2OK);
    assert_eq!(unsafe { fmi2EnterInitializationMode(f.c) }, fmi2OK);
    assert_eq!(unsafe { fmi2ExitInitializationMode(f.c) }, fmi2OK);
    assert_eq!(f.step(0.0, 0.01), fmi2OK);
}
