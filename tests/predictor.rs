//! The Newton start of a stage (the bodies' mean rates extrapolated from the previous stages')
//! changes the work, not the answer:
//!
//! ```text
//! m̂ = Σᵢ cₚᵢ mᵢ₋₁ (degree p chosen per body by how well it extrapolated the newest mean),
//! q_{n+1} solves the same EM equations whatever the start:  |q − q_fresh| ≤ 1e-10
//! ```
//!
//! A run whose history is forgotten mid-way reaches the same states as the uninterrupted run,
//! and the history saves iterations on a smooth motion (the counts are deterministic).
//! Every tree uses the reduced form by default. The solver's memory (the
//! history, the stages left in the eager and the multiplier modes) is in the snapshot, so a
//! restored state repeats a run bit for bit.

mod common;
use common::*;
use triad::mechanics::{step, Model, SolverSettings, State, StepStats};

fn run(m: &Model, s: &mut State, n: usize, h: f64) -> (usize, usize) {
    let (mut it, mut fb) = (0, 0);
    for _ in 0..n {
        let StepStats {
            iterations,
            fallbacks,
            ..
        } = step(m, s, h).unwrap();
        it += iterations;
        fb += fallbacks;
    }
    (it, fb)
}

/// Largest componentwise difference.
fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Steps a copy of `start` with its history and one without it `n` times: (with, without,
/// iterations with, iterations without); neither may hand a stage back.
fn with_and_without_history(
    m: &Model,
    start: &State,
    n: usize,
    h: f64,
) -> (State, State, usize, usize) {
    let (mut a, mut b) = (start.clone(), start.clone());
    b.forget_history();
    let (it_a, fb_a) = run(m, &mut a, n, h);
    let (it_b, fb_b) = run(m, &mut b, n, h);
    assert_eq!((fb_a, fb_b), (0, 0));
    (a, b, it_a, it_b)
}

#[test]
fn forgetting_the_history_changes_iterations_not_states() {
    let h = 1e-3;
    let (m, mut s) = build(&chain(30), settings(h, 2));
    run(&m, &mut s, 400, h);
    let (a, b, it_a, it_b) = with_and_without_history(&m, &s, 200, h);
    let dq = max_diff(a.coordinates(), b.coordinates());
    let dv = max_diff(a.velocities(), b.velocities());
    assert!(dq <= 1e-12 && dv <= 1e-11, "Δq {dq:.2e}, Δv {dv:.2e}");
    // the extrapolated start saves iterations against the restart's linear one at first
    let mut c = a.clone();
    let mut d = a.clone();
    d.forget_history();
    let (it_c, _) = run(&m, &mut c, 3, h);
    let (it_d, _) = run(&m, &mut d, 3, h);
    assert!(it_c < it_d, "{it_c} with history, {it_d} without");
    assert!(
        it_a <= it_b,
        "{it_a} with history, {it_b} after forgetting it"
    );
}

/// Iterations per step of `n` steps of the reduced form from `s`; no stage may be handed back.
fn reduced_iterations(m: &Model, s: &mut State, n: usize, h: f64) -> f64 {
    assert!(m.uses_reduced_solver());
    let (it, fb) = run(m, s, n, h);
    assert_eq!(fb, 0, "stages handed to the multiplier form");
    it as f64 / n as f64
}

#[test]
fn a_smooth_chain_converges_in_two_iterations_per_step() {
    // chain100 at h = 1e-3 over its first second: 4.0 iterations per step with the linear
    // start (mean rate from the nodal one and the last stage's), 2.0 with the extrapolation
    let h = 1e-3;
    let (m, mut s) = build(&chain(100), settings(h, 2));
    let per_step = reduced_iterations(&m, &mut s, 1000, h);
    assert!(per_step <= 2.05, "{per_step} iterations per step");
}

#[test]
fn a_smooth_double_pendulum_converges_in_one_newton_iteration() {
    // h = 1e-3, first 2 s: the extrapolated start is mostly within 2e-11, so the first Newton
    // update (exact Jacobian) leaves an error of ~1e-21 and is accepted without a second
    // residual (1.15 iterations per step, 2.0 otherwise); the energy balance stays at round-off
    // (the default settings: tolerance 1e-10, h = 1e-3)
    let h = 1e-3;
    let (m, mut s) = build(&double_pendulum(), SolverSettings::default());
    let e0 = s.outputs().energy;
    let per_step = reduced_iterations(&m, &mut s, 2000, h);
    assert!(per_step <= 1.2, "{per_step} iterations per step");
    let o = s.outputs();
    let bal = (o.energy - e0 - o.work).abs() / e0.abs();
    assert!(bal < 1e-12, "energy balance {bal:e}");
}

#[test]
fn a_deep_chain_iterates_on_its_bodies() {
    // chain500 over its first second: the iterate is the bodies' own and each linear solve
    // corrects their joint defects (2.02 iterations per step); placed on the joint rows from
    // the joint increments at every iterate, its far bodies turned along arcs and the
    // iteration needed 2.59
    let h = 1e-3;
    let (m, mut s) = build(&chain(500), SolverSettings::default());
    let per_step = reduced_iterations(&m, &mut s, 1000, h);
    assert!(per_step <= 2.1, "{per_step} iterations per step");
}

#[test]
fn every_tree_uses_the_reduced_form() {
    let s = settings(1e-3, 2);
    assert!(Model::new(&chain(1000), s).unwrap().uses_reduced_solver());
    let looped = chain_loop(10, None, 0.0, 0.0);
    assert!(!Model::new(&looped, s).unwrap().uses_reduced_solver());
}

/// Large steps on a long chain: the reduced iteration hands some stages back, and the stages
/// after one go to the multiplier form straight away. That memory and the predictor's history
/// are part of the snapshot: a state restored mid-run repeats the original run bit for bit.
#[test]
fn a_restored_state_repeats_the_run_bit_for_bit() {
    let h = 0.02;
    let (m, mut a) = build(&chain(100), settings(h, 2));
    let (_, fb) = run(&m, &mut a, 30, h);
    assert!(fb > 0, "no stage was handed back: the test needs one");
    let mut b = State::new(&m);
    b.restore(&m, &a.snapshot()).unwrap();
    for _ in 0..30 {
        let sa = step(&m, &mut a, h).unwrap();
        let sb = step(&m, &mut b, h).unwrap();
        assert_eq!(sa, sb);
    }
    let bits = |x: Vec<f64>| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(a.snapshot()), bits(b.snapshot()));
}

/// The order-4 composition's stages (γ₁h, γ₂h, γ₁h) extrapolate from the same stage of the
/// previous steps: two iterations per stage on a smooth motion (chain100: 10.3 iterations per
/// step when they extrapolated linearly from the neighbouring stage), and the same states
/// whatever the start.
#[test]
fn order_four_stages_extrapolate_from_their_own_table() {
    let h = 1e-3;
    let (m, mut s) = build(&chain(60), settings(h, 4));
    run(&m, &mut s, 100, h);
    let (a, b, it_a, it_b) = with_and_without_history(&m, &s, 300, h);
    let per_step = it_a as f64 / 300.0;
    assert!(per_step <= 6.05, "{per_step} iterations per step");
    assert!(
        it_a <= it_b,
        "{it_a} with history, {it_b} after forgetting it"
    );
    let dq = max_diff(a.coordinates(), b.coordinates());
    assert!(dq <= 1e-12, "Δq {dq:.2e}");
}
