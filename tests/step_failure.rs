//! Failed steps are values, not corruption (style rule 7): a step that cannot converge
//! (`max_iterations = 1`, a huge step, a huge input) or meets a non-finite input returns
//! `Err` and leaves the state bit-identical: `snapshot()` before == after, and the next good step
//! gives the same result as from an untouched state.

mod common;
use common::*;
use triad::mechanics::{step, Model, SolverSettings, StepError};

fn bits(x: &[f64]) -> Vec<u64> {
    x.iter().map(|v| v.to_bits()).collect()
}

#[test]
fn no_convergence_leaves_state_bit_identical() {
    let def = double_pendulum();
    let st = SolverSettings {
        max_step: 0.5,
        order: 2,
        tolerance: 1e-12,
        max_iterations: 1,
        ..SolverSettings::default()
    };
    let (m, mut s) = build(&def, st);
    // advance a little with a normal model so that multipliers and velocities are non-trivial
    let good = Model::new(&def, settings(0.01, 2)).unwrap();
    for _ in 0..10 {
        step(&good, &mut s, 0.01).unwrap();
    }
    let before = bits(&s.snapshot());
    let out_before = s.outputs().clone();
    let r = step(&m, &mut s, 0.5);
    assert!(matches!(r, Err(StepError::NoConvergence { .. })), "{r:?}");
    assert_eq!(before, bits(&s.snapshot()));
    assert_eq!(out_before, *s.outputs());
    // the state still steps exactly like an untouched copy
    let mut fresh = s.clone();
    step(&good, &mut s, 0.01).unwrap();
    step(&good, &mut fresh, 0.01).unwrap();
    assert_eq!(bits(&s.snapshot()), bits(&fresh.snapshot()));
}

#[test]
fn huge_input_and_non_finite_input_leave_state_bit_identical() {
    let mut def = double_pendulum();
    def.joints[0].actuated = true;
    let (m, mut s) = build(
        &def,
        SolverSettings {
            max_iterations: 3,
            ..settings(0.05, 4)
        },
    );
    for _ in 0..5 {
        step(&m, &mut s, 0.05).unwrap();
    }
    let before = bits(&s.snapshot());
    s.inputs_mut()[0] = 1e12;
    let with_input = bits(&s.snapshot());
    let r = step(&m, &mut s, 0.05);
    assert!(
        r.is_err(),
        "a 1e12 N·m motor torque must not converge in 3 iterations: {r:?}"
    );
    assert_eq!(with_input, bits(&s.snapshot()));
    s.inputs_mut()[0] = f64::NAN;
    let with_nan = bits(&s.snapshot());
    assert_eq!(step(&m, &mut s, 0.05), Err(StepError::NonFinite("inputs")));
    assert_eq!(with_nan, bits(&s.snapshot()));
    s.inputs_mut()[0] = 0.0;
    assert_eq!(before, bits(&s.snapshot()));
    assert!(matches!(step(&m, &mut s, -1.0), Err(StepError::BadStep(_))));
    assert_eq!(before, bits(&s.snapshot()));
}

#[test]
fn snapshot_restore_round_trip() {
    let (m, mut s) = build(&heavy_top(), settings(0.01, 2));
    for _ in 0..20 {
        step(&m, &mut s, 0.01).unwrap();
    }
    let snap = s.snapshot();
    let mut other = triad::mechanics::State::new(&m);
    other.restore(&m, &snap).unwrap();
    assert_eq!(bits(&other.snapshot()), bits(&snap));
    assert_eq!(other.outputs(), s.outputs());
    step(&m, &mut s, 0.01).unwrap();
    step(&m, &mut other, 0.01).unwrap();
    assert_eq!(bits(&other.snapshot()), bits(&s.snapshot()));
    assert!(other.restore(&m, &snap[1..]).is_err());
}
