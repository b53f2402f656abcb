//! FMI 3 FMU states through the exported functions: get/set continues bit-identically;
//! serialise/deserialise into a second instance continues bit-identically; a state moves
//! between FMI 2 and FMI 3 instances of the model; bad pointers and buffers are refused.

mod fmu_support;

use fmu_support::api3::*;
use fmu_support::fmi3::*;
use fmu_support::*;
use triad::ffi::fmi3::types::*;
use triad::variables::Causality;

/// Steps `f` from step `from` to `to` with the deterministic inputs; every output's bits.
fn run(m: &TestModel, f: &Fmu3, from: usize, to: usize, h: f64) -> Vec<u64> {
    let (ins, n_in) = f.vrs(m, Causality::Input);
    let (outs, n_out) = f.vrs(m, Causality::Output);
    let mut trace = Vec::new();
    for n in from..to {
        let u: Vec<f64> = (0..n_in).map(|i| input(2, n, i)).collect();
        assert_eq!(f.set_f64(&ins, &u), fmi3OK);
        let (s, .., last) = f.step(n as f64 * h, h);
        assert_eq!(s, fmi3OK, "{:?}", f.messages());
        trace.push(last.to_bits());
        let (s, y) = f.get_f64(&outs, n_out);
        assert_eq!(s, fmi3OK);
        trace.extend(y.iter().map(|x| x.to_bits()));
    }
    trace
}

fn get_state(f: &Fmu3) -> fmi3FMUState {
    let mut st: fmi3FMUState = std::ptr::null_mut();
    assert_eq!(unsafe { fmi3GetFMUState(f.c, &mut st) }, fmi3OK);
    assert!(!st.is_null());
    st
}

fn serialize(f: &Fmu3, st: fmi3FMUState) -> Vec<u8> {
    let mut n = 0usize;
    assert_eq!(
        unsafe { fmi3SerializedFMUStateSize(f.c, st, &mut n) },
        fmi3OK
    );
    let mut buf = vec![0u8; n];
    assert_eq!(
        unsafe { fmi3SerializeFMUState(f.c, st, buf.as_mut_ptr(), n) },
        fmi3OK
    );
    if n > 0 {
        assert_eq!(
            unsafe { fmi3SerializeFMUState(f.c, st, buf.as_mut_ptr(), n - 1) },
            fmi3Error
        );
    }
    buf
}

#[test]
fn get_set_continues_bit_identically() {
    let m = shipped("robot_arm");
    let f = Fmu3::initialised(&m);
    run(&m, &f, 0, 20, 0.01);
    let mut st = get_state(&f);
    let first = run(&m, &f, 20, 40, 0.01);
    assert_eq!(unsafe { fmi3SetFMUState(f.c, st) }, fmi3OK);
    let again = run(&m, &f, 20, 40, 0.01);
    assert_eq!(first, again);
    // a second get into the same pointer overwrites it
    let before = st;
    assert_eq!(unsafe { fmi3GetFMUState(f.c, &mut st) }, fmi3OK);
    assert_eq!(st, before);
    assert_eq!(unsafe { fmi3FreeFMUState(f.c, &mut st) }, fmi3OK);
    assert!(st.is_null());
    // freed: refused without being dereferenced
    assert_eq!(unsafe { fmi3SetFMUState(f.c, before) }, fmi3Error);
    assert!(f.last_message().starts_with("fmi3SetFMUState: "));
    assert_eq!(
        unsafe { fmi3FreeFMUState(f.c, &mut st) },
        fmi3OK,
        "NULL: no-op"
    );
}

#[test]
fn serialised_states_continue_in_another_instance() {
    let m = shipped("double_pendulum");
    let a = Fmu3::initialised(&m);
    run(&m, &a, 0, 30, 0.01);
    let mut st = get_state(&a);
    let bytes = serialize(&a, st);
    assert_eq!(unsafe { fmi3FreeFMUState(a.c, &mut st) }, fmi3OK);
    let want = run(&m, &a, 30, 60, 0.01);

    let b = Fmu3::new(&m);
    let mut st2: fmi3FMUState = std::ptr::null_mut();
    assert_eq!(
        unsafe { fmi3DeserializeFMUState(b.c, bytes.as_ptr(), bytes.len(), &mut st2) },
        fmi3OK
    );
    assert_eq!(unsafe { fmi3SetFMUState(b.c, st2) }, fmi3OK);
    assert_eq!(run(&m, &b, 30, 60, 0.01), want);
    assert_eq!(unsafe { fmi3FreeFMUState(b.c, &mut st2) }, fmi3OK);

    // a corrupt buffer, a truncated one, NULL: refused
    let mut bad = bytes.clone();
    let k = bad.len() / 2;
    bad[k] ^= 1;
    let mut st3: fmi3FMUState = std::ptr::null_mut();
    for buf in [&bad[..], &bytes[..bytes.len() - 1]] {
        assert_eq!(
            unsafe { fmi3DeserializeFMUState(b.c, buf.as_ptr(), buf.len(), &mut st3) },
            fmi3Error
        );
        assert!(st3.is_null());
    }
    assert_eq!(
        unsafe { fmi3DeserializeFMUState(b.c, std::ptr::null(), 10, &mut st3) },
        fmi3Error
    );
    assert_eq!(
        unsafe { fmi3DeserializeFMUState(b.c, bytes.as_ptr(), bytes.len(), std::ptr::null_mut()) },
        fmi3Error
    );
}

#[test]
fn a_state_moves_between_live_instances_fmi2_and_fmi3() {
    let m = shipped("robot_arm");
    let a = Fmu3::initialised(&m);
    let b = Fmu3::initialised(&m);
    run(&m, &a, 0, 25, 0.01);
    let st = get_state(&a);
    let want = run(&m, &a, 25, 50, 0.01);
    // set into another FMI 3 instance
    assert_eq!(unsafe { fmi3SetFMUState(b.c, st) }, fmi3OK);
    assert_eq!(run(&m, &b, 25, 50, 0.01), want);
    // and into an FMI 2 instance of the same model: the same continuation
    let f2 = Fmu::initialised(&m);
    assert_eq!(
        unsafe { fmu_support::api::fmi2SetFMUstate(f2.c, st) },
        triad::ffi::types::fmi2OK
    );
    let ins2 = m.vrs(Causality::Input);
    let outs2 = m.vrs(Causality::Output);
    let mut trace = Vec::new();
    for n in 25..50 {
        let u: Vec<f64> = (0..ins2.len()).map(|i| input(2, n, i)).collect();
        assert_eq!(f2.set_real(&ins2, &u), triad::ffi::types::fmi2OK);
        assert_eq!(f2.step(n as f64 * 0.01, 0.01), triad::ffi::types::fmi2OK);
        trace.push(f2.last_successful_time().to_bits());
        trace.extend(f2.get_real(&outs2).1.iter().map(|x| x.to_bits()));
    }
    assert_eq!(trace, want);
    // freeing the owner frees its states: then refused everywhere
    drop(a);
    assert_eq!(unsafe { fmi3SetFMUState(b.c, st) }, fmi3Error);
}

#[test]
fn a_state_of_another_model_is_refused() {
    let m1 = shipped("robot_arm");
    let m2 = shipped("double_pendulum");
    let a = Fmu3::initialised(&m1);
    let b = Fmu3::initialised(&m2);
    let mut st = get_state(&a);
    assert_eq!(unsafe { fmi3SetFMUState(b.c, st) }, fmi3Error);
    let mut n = 0;
    assert_eq!(
        unsafe { fmi3SerializedFMUStateSize(b.c, st, &mut n) },
        fmi3Error
    );
    assert_eq!(unsafe { fmi3FreeFMUState(b.c, &mut st) }, fmi3Error);
    assert!(!st.is_null());
    assert_eq!(unsafe { fmi3FreeFMUState(a.c, &mut st) }, fmi3OK);
    // b still works
    assert_eq!(b.step(0.0, 0.01).0, fmi3OK);
}
