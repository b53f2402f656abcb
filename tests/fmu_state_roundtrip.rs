//! FMU states continue bit-identically (interface.md §4): a run that stores its state at step
//! k, is disturbed, and restores it — or serialises it, frees the instance and deserialises it
//! into a fresh instance — produces from step k on exactly the same bytes as the undisturbed run.

mod fmu_support;

use fmu_support::*;
use triad::ffi::state::*;
use triad::ffi::types::*;
use triad::variables::Causality;

const H: f64 = 0.01;

fn drive(f: &Fmu, m: &TestModel, from: usize, to: usize) -> Vec<u64> {
    let ins = m.vrs(Causality::Input);
    let outs = m.vrs(Causality::Output);
    let mut trace = Vec::new();
    for n in from..to {
        let u: Vec<f64> = (0..ins.len()).map(|i| input(1, n, i)).collect();
        assert_eq!(f.set_real(&ins, &u), fmi2OK);
        assert_eq!(f.step(n as f64 * H, H), fmi2OK);
        trace.extend(f.get_real(&outs).1.iter().map(|x| x.to_bits()));
    }
    trace
}

#[test]
fn get_set_state_continues_bit_identically() {
    let m = TestModel::pendulum();
    let reference = Fmu::initialised(&m);
    let want = drive(&reference, &m, 0, 30);

    let f = Fmu::initialised(&m);
    let mut got = drive(&f, &m, 0, 10);
    let mut st: fmi2FMUstate = std::ptr::null_mut();
    assert_eq!(unsafe { fmi2GetFMUstate(f.c, &mut st) }, fmi2OK);
    // disturb: other inputs, a tunable change, more steps
    let damping = m.vr("joint.shoulder.damping");
    assert_eq!(f.set_real(&[damping], &[2.0]), fmi2OK);
    drive(&f, &m, 10, 15);
    assert_eq!(unsafe { fmi2SetFMUstate(f.c, st) }, fmi2OK);
    assert_eq!(f.get_real(&[damping]).1, vec![0.0], "tunable restored");
    got.extend(drive(&f, &m, 10, 30));
    // overwrite the same state object (FMI: *FMUstate != NULL is reused), then free
    assert_eq!(unsafe { fmi2GetFMUstate(f.c, &mut st) }, fmi2OK);
    assert_eq!(unsafe { fmi2FreeFMUstate(f.c, &mut st) }, fmi2OK);
    assert_eq!(got, want);
}

#[test]
fn serialize_free_deserialize_in_a_fresh_instance() {
    let m = TestModel::pendulum();
    let want = drive(&Fmu::initialised(&m), &m, 0, 30);

    let first = Fmu::initialised(&m);
    let mut got = drive(&first, &m, 0, 12);
    let bytes = first.serialize();
    drop(first);
    assert_eq!(&bytes[..8], b"TRIADFS\0");

    // a fresh instance, never initialised, takes the state over
    let second = Fmu::new(&m);
    assert_eq!(
        second.deserialize(&bytes),
        fmi2OK,
        "{:?}",
        second.messages()
    );
    got.extend(drive(&second, &m, 12, 30));
    assert_eq!(got, want);
    // serialising again gives the same bytes as the uninterrupted instance at the same point
    let again = Fmu::initialised(&m);
    drive(&again, &m, 0, 30);
    assert_eq!(second.serialize(), again.serialize());
}

#[test]
fn parameters_set_before_initialisation_travel_with_the_state() {
    let m = TestModel::pendulum();
    let ms = m.vr("solver.max_step");
    let a = Fmu::initialised_with(&m, &[ms], &[0.0025]);
    drive(&a, &m, 0, 3);
    let bytes = a.serialize();
    let b = Fmu::new(&m);
    assert_eq!(b.deserialize(&bytes), fmi2OK);
    assert_eq!(b.get_real(&[ms]).1, vec![0.0025]);
    assert_eq!(drive(&a, &m, 3, 8), drive(&b, &m, 3, 8));
}

#[test]
fn corrupt_or_foreign_states_are_rejected_and_change_nothing() {
    let m = TestModel::pendulum();
    let f = Fmu::initialised(&m);
    drive(&f, &m, 0, 3);
    let bytes = f.serialize();
    let before = f.serialize();
    for bad in [
        &bytes[..bytes.len() - 3],
        &b"not a state at all"[..],
        &[][..],
    ] {
        assert_eq!(f.deserialize(bad), fmi2Error);
    }
    let mut flipped = bytes.clone();
    flipped[20] ^= 1; // inside the GUID
    assert_eq!(f.deserialize(&flipped), fmi2Error);
    assert!(
        f.last_message().contains("checksum mismatch"),
        "{}",
        f.last_message()
    );
    let dp = triad::spec::bundled()
        .iter()
        .find(|(n, _)| *n == "double_pendulum")
        .unwrap()
        .1;
    let other = Fmu::initialised(&TestModel::new(dp)).serialize();
    assert_eq!(f.deserialize(&other), fmi2Error);
    assert!(
        f.last_message().contains("belongs to model"),
        "{}",
        f.last_message()
    );
    assert_eq!(f.serialize(), before);
    assert_eq!(f.step(3.0 * H, H), fmi2OK);
}

/// Under error-controlled steps (solver.rtol, solver.max_step as the ceiling, set before
/// initialisation; communication steps of 0.1 s, so each holds several internal steps of the
/// controller's choosing) a state serialised mid-run and deserialised into a fresh instance
/// continues bit for bit: the controller's proposal and samples travel with the state (without
/// them the controller restarts from a short step: `tests/adaptive.rs`).
#[test]
fn adaptive_state_travels_with_the_controller_memory() {
    let m = TestModel::pendulum();
    let (rtol, ms) = (m.vr("solver.rtol"), m.vr("solver.max_step"));
    let outs = m.vrs(Causality::Output);
    let run = |f: &Fmu, from: usize, to: usize| -> Vec<u64> {
        let mut trace = Vec::new();
        for n in from..to {
            assert_eq!(f.step(n as f64 * 0.1, 0.1), fmi2OK);
            trace.extend(f.get_real(&outs).1.iter().map(|x| x.to_bits()));
        }
        trace
    };
    let a = Fmu::initialised_with(&m, &[rtol, ms], &[1e-6, 0.1]);
    let want = run(&a, 0, 20);
    let b = Fmu::initialised_with(&m, &[rtol, ms], &[1e-6, 0.1]);
    let mut got = run(&b, 0, 7);
    let bytes = b.serialize();
    drop(b);
    let c = Fmu::new(&m);
    assert_eq!(c.deserialize(&bytes), fmi2OK, "{:?}", c.messages());
    assert_eq!(c.get_real(&[rtol]).1, vec![1e-6]);
    got.extend(run(&c, 7, 20));
    assert_eq!(got, want);
}
