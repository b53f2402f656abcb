//! Criterion benches of one EM step (order 2, h = 1e-3): the peers' double pendulum, heavy top
//! and chainN (N = 10, 100, 1000); chain100_floating (the same chain with its first link a
//! floating base, gravity off, every joint turning); with loop-closing joints the four-bar and chain100_loop
//! (chain100 closed to the world, bordered tree solve). `step/*` is the integrator step alone (`step_state`, what
//! every sub-step of a communication step costs); `outputs/*` is one refresh of the outputs
//! (velocity projection, energy, momenta, joint coordinates; once per communication step).
//!
//! Protocol of the peers harness (`../shared/peers`, "cost"): runs of 2 s of simulated time
//! from the model's initial state. The step bench steps from t = 0 and restores the initial
//! state every 2000 steps (the restore is not timed), so that every model is timed over the
//! motion the peers were timed on rather than over whatever state a long bench drifts into
//! (a double pendulum after 500 s of chaotic motion needs more Newton iterations than in its
//! first 2 s). The mean Newton iterations per step over the timed steps are printed.
//!
//! Run: `cargo bench --bench step -- --warm-up-time 1 --measurement-time 5`.
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::time::{Duration, Instant};
use triad::mechanics::{step_state, Model, ModelDef, SolverSettings, State};

#[path = "../tests/common/mod.rs"]
#[allow(clippy::all)]
mod common;

/// Step size, s.
const H: f64 = 1e-3;

/// Steps of one run of the protocol (2 s of simulated time).
const WINDOW: u64 = 2000;

fn setup(def: &ModelDef) -> (Model, State) {
    let s = SolverSettings {
        max_step: H,
        order: 2,
        tolerance: 1e-10,
        max_iterations: 20,
        ..SolverSettings::default()
    };
    let m = Model::new(def, s).expect("model");
    let st = State::new(&m);
    (m, st)
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("em");
    let cases: Vec<(String, ModelDef)> = vec![
        ("double_pendulum".into(), common::double_pendulum()),
        ("heavy_top".into(), common::heavy_top()),
        ("chain10".into(), common::chain(10)),
        ("chain100".into(), common::chain(100)),
        ("chain1000".into(), common::chain(1000)),
        ("chain100_floating".into(), common::floating_chain(100)),
        ("fourbar".into(), common::four_bar(1.0, 3.0)),
        (
            "chain100_loop".into(),
            common::chain_loop(100, None, 0.0, 0.0),
        ),
    ];
    for (name, def) in cases {
        let (m, s0) = setup(&def);
        let mut s = s0.clone();
        // position in the current 2 s run, and the timed steps and their Newton iterations
        let (mut k, mut steps, mut iters) = (0_u64, 0_u64, 0_usize);
        g.bench_with_input(BenchmarkId::new("step", &name), &name, |b, _| {
            b.iter_custom(|n| {
                let mut elapsed = Duration::ZERO;
                let mut done = 0;
                while done < n {
                    if k == WINDOW {
                        s.clone_from(&s0);
                        k = 0;
                    }
                    let run = (n - done).min(WINDOW - k);
                    let t = Instant::now();
                    for _ in 0..run {
                        iters += step_state(&m, &mut s, H).expect("step").iterations;
                    }
                    elapsed += t.elapsed();
                    done += run;
                    k += run;
                }
                steps += n;
                elapsed
            });
        });
        if steps > 0 {
            eprintln!(
                "{name}: {:.3} Newton iterations per step over the {steps} steps run",
                iters as f64 / steps as f64
            );
        }
        g.bench_with_input(BenchmarkId::new("outputs", &name), &name, |b, _| {
            b.iter(|| s.refresh_outputs(&m));
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
