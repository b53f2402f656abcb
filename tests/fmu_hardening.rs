//! What a hostile importer can throw at the FMU and what it gets back (issue "hardening"):
//! - tiny and denormal communication steps return OK with finite outputs and exact invariants
//!   (a step shorter than 1e-6 max_step is carried into the next one), on every shipped model;
//! - one `fmi2DoStep` does at most `solver.max_substeps` sub-steps, then returns `fmi2Discard`
//!   at the progress made, from where the run goes on;
//! - parameters outside their range are refused with nothing changed;
//! - saved states are verified: a bit flip anywhere, a mode `fmi2GetFMUstate` never records, a
//!   re-checksummed buffer with a bad field — each refused, instance unchanged; FMU-state
//!   pointers that the instance did not hand out (or freed) are refused.

mod fmu_support;

use fmu_support::*;
use triad::ffi::common::*;
use triad::ffi::getset::*;
use triad::ffi::types::*;
use triad::variables::Causality;

fn value(m: &TestModel, f: &Fmu, name: &str) -> f64 {
    f.get_real(&[m.vr(name)]).1[0]
}

fn all_outputs(m: &TestModel, f: &Fmu) -> Vec<f64> {
    let (s, out) = f.get_real(&m.vrs(Causality::Output));
    assert_eq!(s, fmi2OK);
    out
}

#[test]
fn tiny_and_denormal_steps_keep_every_output_finite_and_the_invariants_exact() {
    for (name, text) in triad::spec::bundled() {
        let m = TestModel::new(text);
        for h in [1e-10, 1e-15, 1e-100, 1e-300, 2.2e-308, 4.9e-324] {
            let f = Fmu::initialised(&m);
            assert_eq!(f.step(0.0, 0.01), fmi2OK);
            let e0 = value(&m, &f, "system.energy") - value(&m, &f, "system.work");
            let mut t = 0.01;
            for _ in 0..100 {
                assert_eq!(f.step(t, h), fmi2OK, "{name} H = {h:e}: {:?}", f.messages());
                t += h;
                let out = all_outputs(&m, &f);
                assert!(out.iter().all(|x| x.is_finite()), "{name} H = {h:e}");
            }
            // the next ordinary steps integrate the carried span too
            for _ in 0..10 {
                assert_eq!(f.step(t, 0.01), fmi2OK, "{name} after H = {h:e}");
                t += 0.01;
            }
            let e1 = value(&m, &f, "system.energy") - value(&m, &f, "system.work");
            assert!(
                (e1 - e0).abs() <= 1e-12 * e0.abs().max(1.0),
                "{name} H = {h:e}: energy - work {e0} -> {e1}"
            );
            assert!(value(&m, &f, "system.constraint_residual") < 1e-9, "{name}");
        }
    }
}

/// A run of tiny steps followed by a normal one lands where one step over the whole span does
/// (the carried span is integrated, not dropped).
#[test]
fn carried_spans_are_integrated_not_dropped() {
    let m = TestModel::pendulum();
    let a = Fmu::initialised(&m);
    let b = Fmu::initialised(&m);
    let q = m.vr("joint.shoulder.q");
    let tiny = 2e-10; // four of them stay below 1e-6 max_step = 1e-9: all carried
    let mut t = 0.0;
    for _ in 0..4 {
        assert_eq!(a.step(t, tiny), fmi2OK);
        t += tiny;
    }
    assert_eq!(a.step(t, 0.01), fmi2OK);
    assert_eq!(b.step(0.0, t + 0.01), fmi2OK);
    let (qa, qb) = (a.get_real(&[q]).1[0], b.get_real(&[q]).1[0]);
    assert!((qa - qb).abs() < 1e-12, "{qa} vs {qb}");
}

#[test]
fn one_do_step_does_bounded_work_and_reports_its_progress() {
    let m = TestModel::pendulum();
    let f = Fmu::new(&m);
    let ms = m.vr("solver.max_step");
    assert_eq!(f.set_real(&[ms], &[1e-3]), fmi2OK);
    let bound = m.vr("solver.max_substeps");
    assert_eq!(
        unsafe { fmi2SetInteger(f.c, [bound].as_ptr(), 1, [5000].as_ptr()) },
        fmi2OK
    );
    assert_eq!(f.setup(0.0), fmi2OK);
    assert_eq!(unsafe { fmi2EnterInitializationMode(f.c) }, fmi2OK);
    assert_eq!(unsafe { fmi2ExitInitializationMode(f.c) }, fmi2OK);
    assert_eq!(f.step(0.0, 1e6), fmi2Discard);
    let msg = f.last_message();
    assert!(msg.contains("solver.max_substeps"), "{msg}");
    let reached = f.last_successful_time();
    // 5000 sub-steps of 1e6 / ceil(1e6 / max_step) s
    assert!((reached - 5.0).abs() < 1e-7, "{reached}");
    assert!(all_outputs(&m, &f).iter().all(|x| x.is_finite()));
    // the run stands at the progress made and goes on from there
    assert_eq!(f.step(reached, 0.01), fmi2OK, "{:?}", f.messages());
    assert!((f.last_successful_time() - (reached + 0.01)).abs() < 1e-12);
    // the default bound is met by a communication step of 1e5 max_step
    let g = Fmu::initialised(&m);
    assert_eq!(g.step(0.0, 1e6), fmi2Discard);
}

#[test]
fn parameters_outside_their_range_are_refused_and_change_nothing() {
    let m = TestModel::pendulum();
    let f = Fmu::new(&m);
    for (name, bad) in [
        ("solver.max_step", 1e-300),
        ("solver.max_step", 0.0),
        ("solver.max_step", 1e9),
        ("solver.tolerance", 0.0),
        ("solver.tolerance", 1e-20),
        ("solver.tolerance", 0.5),
        ("body.link1.mass", -1.0),
        ("joint.shoulder.damping", -0.1),
        ("joint.shoulder.stiffness", -2.0),
        ("gravity[3]", f64::INFINITY),
    ] {
        assert_eq!(
            f.set_real(&[m.vr(name)], &[bad]),
            fmi2Error,
            "{name} = {bad}"
        );
        let msg = f.last_message();
        assert!(msg.contains(name), "{msg}");
    }
    let (order, bound) = (m.vr("solver.order"), m.vr("solver.max_substeps"));
    for (vr, v) in [(order, 3), (bound, 0), (bound, -5)] {
        assert_eq!(
            unsafe { fmi2SetInteger(f.c, [vr].as_ptr(), 1, [v].as_ptr()) },
            fmi2Error
        );
    }
    // toleranceDefined with a tolerance that is not positive and finite
    for tol in [f64::NAN, -1.0, 0.0, f64::INFINITY] {
        assert_eq!(
            unsafe { fmi2SetupExperiment(f.c, fmi2True, tol, 0.0, fmi2False, 0.0) },
            fmi2Error
        );
    }
    assert_eq!(
        unsafe { fmi2SetupExperiment(f.c, fmi2True, 1e-6, 0.0, fmi2False, 0.0) },
        fmi2OK
    );
    assert_eq!(unsafe { fmi2EnterInitializationMode(f.c) }, fmi2OK);
    // nothing was changed by the refused sets
    let spec = &m.spec;
    assert_eq!(value(&m, &f, "solver.max_step"), spec.solver.max_step);
    assert_eq!(value(&m, &f, "solver.tolerance"), spec.solver.tolerance);
    assert_eq!(value(&m, &f, "body.link1.mass"), spec.body[0].mass);
    assert_eq!(value(&m, &f, "gravity[3]"), spec.gravity[2]);
}

/// Rewrites the CRC-32 at the end of a serialised state after an edit.
fn reseal(b: &mut [u8]) {
    let n = b.len() - 4;
    let crc = crc32fast::hash(&b[..n]);
    b[n..].copy_from_slice(&crc.to_le_bytes());
}

/// Offset of the mode byte: magic 8, version 4, GUID length 4 + GUID.
fn mode_at(b: &[u8]) -> usize {
    let n = u32::from_le_bytes([b[12], b[13], b[14], b[15]]) as usize;
    16 + n
}

#[test]
fn saved_states_are_verified_field_by_field() {
    let m = TestModel::pendulum();
    let f = Fmu::initialised(&m);
    assert_eq!(f.step(0.0, 0.01), fmi2OK);
    let good = f.serialize();
    let before = all_outputs(&m, &f);
    // every byte, one bit flipped: refused by the checksum
    for i in 0..good.len() {
        let mut b = good.clone();
        b[i] ^= 1 << (i % 8);
        assert_eq!(f.deserialize(&b), fmi2Error, "flip in byte {i} accepted");
    }
    // every mode value but the recorded ones, with a valid checksum
    let at = mode_at(&good);
    assert_eq!(good[at], 2, "stepComplete");
    for code in 0..=255u8 {
        let mut b = good.clone();
        b[at] = code;
        reseal(&mut b);
        let want = if matches!(code, 0 | 1 | 2 | 5) {
            // Instantiated carries no simulation state: refused as well; the others restore
            if code == 0 {
                fmi2Error
            } else {
                fmi2OK
            }
        } else {
            fmi2Error
        };
        assert_eq!(f.deserialize(&b), want, "mode code {code}");
        if want == fmi2OK {
            // back to the good state for the next round
            assert_eq!(f.deserialize(&good), fmi2OK);
        }
    }
    // a finite-looking but out-of-range parameter (max_step = 1e-300), resealed
    let params_at = at + 1 + 8 + 1 + 8 + 8 + 4;
    let ms_index = m
        .table
        .vars
        .iter()
        .filter(|v| v.causality == Causality::Parameter)
        .position(|v| v.name == "solver.max_step")
        .unwrap();
    let mut b = good.clone();
    let o = params_at + 8 * ms_index;
    b[o..o + 8].copy_from_slice(&1e-300f64.to_le_bytes());
    reseal(&mut b);
    assert_eq!(f.deserialize(&b), fmi2Error);
    assert!(
        f.last_message().contains("solver.max_step"),
        "{}",
        f.last_message()
    );
    // a NaN in the simulation state (the last 8 bytes before the checksum), resealed
    let mut b = good.clone();
    let n = b.len() - 12;
    b[n..n + 8].copy_from_slice(&f64::NAN.to_le_bytes());
    reseal(&mut b);
    assert_eq!(f.deserialize(&b), fmi2Error);
    // nothing changed, and the instance goes on
    assert_eq!(all_outputs(&m, &f), before);
    assert_eq!(f.step(0.01, 0.01), fmi2OK);
}
