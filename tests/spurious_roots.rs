//! Steps too large for the motion: a stage that turns a body by about π within it is refused
//! and redone as two half stages (`step/identity.rs`). At π the midpoint directors collapse,
//! the projected rows lose rank, and a root of them need not solve the equations: before the
//! refusal, the double pendulum at h = 0.08 s (its second link turned by exactly π within a
//! step) went from 10 J to 507 J with a converged residual, and the heavy top at h = 0.15 s
//! ended 1.1e8 J off. Now every step taken keeps `E − E₀ − W` at round-off, and a step that
//! cannot be resolved even halved is reported as an error instead of taken.
mod common;
use common::*;
use triad::mechanics::{step_state, ModelDef, SolverSettings};

fn solver(h: f64, order: u8, stages: u8) -> SolverSettings {
    SolverSettings {
        max_step: h,
        order,
        stages,
        tolerance: 1e-10,
        max_iterations: 20,
        ..SolverSettings::default()
    }
}

/// Steps `def` `n` times at `h` (the multiplier form throughout if `multipliers`) and returns
/// the steps taken and the largest `|E − E₀ − W|` after any of them, J.
fn run(def: &ModelDef, s: SolverSettings, multipliers: bool, n: usize) -> (usize, f64) {
    let (mut m, mut st) = build(def, s);
    if multipliers {
        m.set_reduced_solver(false);
    }
    let h = m.settings().max_step;
    let e0 = st.outputs().energy;
    let mut worst = 0.0_f64;
    for k in 0..n {
        if step_state(&m, &mut st, h).is_err() {
            return (k, worst);
        }
        st.refresh_outputs(&m);
        let o = st.outputs();
        worst = worst.max((o.energy - e0 - o.work).abs());
    }
    (n, worst)
}

#[test]
fn a_link_turned_by_pi_within_a_step_is_refused_not_taken() {
    for multipliers in [false, true] {
        for (order, stages) in [(2, 3), (4, 3), (4, 5)] {
            for h in [0.08, 0.15] {
                let (steps, worst) = run(
                    &double_pendulum(),
                    solver(h, order, stages),
                    multipliers,
                    1000,
                );
                eprintln!(
                    "double pendulum h = {h}, order {order}/{stages}, multipliers {multipliers}: \
                     {steps} steps, |E − E0 − W| ≤ {worst:.1e} J"
                );
                assert_eq!(
                    steps, 1000,
                    "h = {h}, order {order}/{stages}: a step failed"
                );
                assert!(
                    worst < 1e-10,
                    "h = {h}, order {order}/{stages}: {worst:e} J"
                );
            }
        }
    }
}

#[test]
fn a_step_that_cannot_be_resolved_fails_instead_of_breaking_the_balance() {
    // the top spins at 30 rad/s: 4.5–6 rad per step, beyond what three halvings resolve
    for h in [0.15, 0.2] {
        let (steps, worst) = run(&heavy_top(), solver(h, 2, 3), false, 1000);
        eprintln!("heavy top h = {h}: {steps} steps taken, |E − E0 − W| ≤ {worst:.1e} J");
        assert!(worst < 1e-10, "h = {h}: {worst:e} J");
    }
}
