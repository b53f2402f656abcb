//! The work of one communication step is bounded in Newton work, not only in sub-steps
//! (`sim`: at most `WORK_PER_SUBSTEP × max_substeps` body-iterations, iterations × the model's
//! size, a factorisation counting three): a hostile call (bodies spun up by huge torques to
//! 1000–3000 rad/s, then `fmi2DoStep` with H = 1e6) stops after the sub-step that crossed the
//! bound, at the time reached, and the run goes on from there; ordinary long calls are not cut
//! by it (they meet the sub-step bound first). What such a call costs in seconds is measured by
//! `cargo bench --bench fmi_boundary -- hostile` (BENCHMARKS.md "FMI boundary"), not here.
//!
//! ```text
//! spun-up space_arm, robot_arm, four_bar, H = 1e6:  Failure::EffortBound, work ≤ bound + one
//!                                                   sub-step's, time reached < 1e6, usable
//! the same models at rest, H = 1e6:                 Failure::WorkBound (100 000 sub-steps)
//! the FMU: fmi2Discard naming the bound, lastSuccessfulTime = the time reached, goes on
//! ```

mod fmu_support;

use fmu_support::*;
use triad::ffi::types::*;
use triad::sim::{Failure, Simulation, WORK_PER_SUBSTEP};
use triad::spec::Spec;

fn shipped(name: &str) -> Simulation {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("modelDescription")
        .join(name)
        .join("spec.toml");
    let spec = Spec::from_path(&path).unwrap_or_else(|e| panic!("{e}"));
    let (def, settings) = spec.lower().unwrap();
    Simulation::new(&def, settings, 0.0).unwrap()
}

/// Spins the model up under torques ±1000 N·m for 0.05 s, then releases them.
fn spun_up(name: &str) -> Simulation {
    let mut sim = shipped(name);
    for (i, x) in sim.state_mut().inputs_mut().iter_mut().enumerate() {
        *x = if i % 2 == 0 { 1e3 } else { -1e3 };
    }
    sim.advance(0.05).unwrap();
    for x in sim.state_mut().inputs_mut() {
        *x = 0.0;
    }
    sim
}

#[test]
fn a_hostile_call_stops_at_its_work_bound_and_the_run_goes_on() {
    for name in ["space_arm", "robot_arm", "four_bar"] {
        let mut sim = spun_up(name);
        let (t0, e0) = (sim.time(), sim.state().effort());
        let err = sim.advance(1e6).unwrap_err();
        let work = (sim.state().effort() - e0) as f64 * sim.work_size();
        let bound = sim.work_bound();
        eprintln!(
            "{name}: {}; work {work:.3e} of {bound:.3e} body-iterations, t {t0} → {}",
            err.error, err.last_good_time
        );
        assert!(
            matches!(err.error, Failure::EffortBound { .. }),
            "{name}: {}",
            err.error
        );
        assert_eq!(bound, WORK_PER_SUBSTEP * 100_000.0);
        // at most one sub-step past the bound (a sub-step's work is itself bounded: 12
        // iterations, two starts, three halvings)
        assert!(
            work > bound && work <= bound * 1.01,
            "{name}: {work} of {bound}"
        );
        assert!(err.last_good_time > t0 && err.last_good_time < 1e6);
        assert_eq!(sim.time(), err.last_good_time);
        assert!(sim.state().outputs().first_non_finite().is_none());
        // the run goes on from the time reached
        let t = sim.time();
        sim.advance(0.01).unwrap();
        assert!((sim.time() - (t + 0.01)).abs() <= 1e-12 * t.max(1.0));
    }
}

#[test]
fn ordinary_long_calls_meet_the_sub_step_bound_first() {
    for name in ["space_arm", "robot_arm", "four_bar", "double_pendulum"] {
        let mut sim = shipped(name);
        let e0 = sim.state().effort();
        let err = sim.advance(1e6).unwrap_err();
        let work = (sim.state().effort() - e0) as f64 * sim.work_size();
        eprintln!(
            "{name} at rest: {}; work {work:.3e} of {:.3e}",
            err.error,
            sim.work_bound()
        );
        assert!(
            matches!(err.error, Failure::WorkBound { .. }),
            "{name}: {}",
            err.error
        );
        assert!(work < 0.75 * sim.work_bound(), "{name}: {work}");
    }
}

#[test]
fn the_fmu_returns_discard_at_the_work_bound_and_goes_on() {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("modelDescription/space_arm/spec.toml"),
    )
    .unwrap();
    let m = TestModel::new(&text);
    let f = Fmu::initialised(&m);
    let taus: Vec<u32> = m.vrs(triad::variables::Causality::Input);
    let values: Vec<f64> = (0..taus.len())
        .map(|i| if i % 2 == 0 { 1e3 } else { -1e3 })
        .collect();
    assert_eq!(f.set_real(&taus, &values), fmi2OK);
    assert_eq!(f.step(0.0, 0.05), fmi2OK, "{:?}", f.messages());
    assert_eq!(f.set_real(&taus, &vec![0.0; taus.len()]), fmi2OK);
    assert_eq!(f.step(0.05, 1e6), fmi2Discard);
    let msg = f.last_message();
    assert!(
        msg.contains("Newton work") && msg.contains("solver.max_substeps"),
        "{msg}"
    );
    let reached = f.last_successful_time();
    assert!(reached > 0.05 && reached < 1e6, "{reached}");
    assert_eq!(f.step(reached, 0.01), fmi2OK, "{:?}", f.messages());
}
