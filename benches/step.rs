//! Criterion benches of one EM step (order 2, h = 1e-3): the peers' double pendulum, heavy top
//! and chainN (N = 10, 100, 1000); with loop-closing joints the four-bar and chain100_loop
//! (chain100 closed to the world, bordered tree solve). `step/*` is the integrator step alone (`step_state`, what
//! every sub-step of a communication step costs); `outputs/*` is one refresh of the outputs
//! (velocity projection, energy, momenta, joint coordinates; once per communication step). Run: `cargo bench --bench step -- --warm-up-time 1
//! --measurement-time 3`.
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use triad::mechanics::{step_state, Model, ModelDef, SolverSettings, State};

#[path = "../tests/common/mod.rs"]
#[allow(clippy::all)]
mod common;

fn setup(def: &ModelDef) -> (Model, State) {
    let s = SolverSettings {
        max_step: 1e-3,
        order: 2,
        tolerance: 1e-10,
        max_iterations: 20,
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
        ("fourbar".into(), common::four_bar(1.0, 3.0)),
        (
            "chain100_loop".into(),
            common::chain_loop(100, None, 0.0, 0.0),
        ),
    ];
    for (name, def) in cases {
        let (m, mut s) = setup(&def);
        // a short run-in so that the state is generic (moving, multipliers warm)
        for _ in 0..20 {
            step_state(&m, &mut s, 1e-3).expect("step");
        }
        g.bench_with_input(BenchmarkId::new("step", &name), &name, |b, _| {
            b.iter(|| step_state(&m, &mut s, 1e-3).expect("step"));
        });
        g.bench_with_input(BenchmarkId::new("outputs", &name), &name, |b, _| {
            b.iter(|| s.refresh_outputs(&m));
        });
        let mut it = 0;
        for _ in 0..100 {
            it += step_state(&m, &mut s, 1e-3).expect("step").iterations;
        }
        eprintln!(
            "{name}: {:.2} Newton iterations per step",
            it as f64 / 100.0
        );
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
