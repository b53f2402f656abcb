//! Criterion benches of the exact continuous-time linear model (`Operating::linearize`, A and B
//! without outputs) at the initial state: the robot arm (6 joints, UR5-like) and chainN
//! (N = 10, 100, 1000: 2N states, N inputs are none, so B is empty; the cost is that of A).
//! Expected growth (analytic path, `tree_partials`): one O(N·depth) sweep for the residual's
//! partial derivatives and one O(N) articulated-body solve per column: O(N²) on a chain.
//!
//! `step_map/*`: the exact discrete-time Ad, Bd of one communication step of 1 ms (one sub-step
//! at the default max_step, `Simulation::step_map`; the chains with a torque input on every
//! joint): per stage three Newton-matrix assemblies,
//! two factorisations, and one O(N) back-substitution per column (2n + inputs): O(N²).
//! `step_map/box`: a box resting on four of its corners (12 states, 8 bristle states, 6
//! inputs; `tests/common/contact_models.rs`), beside `step_map/box_step`, the same step without
//! its map.
//!
//! Run: `cargo bench --bench linearize -- --warm-up-time 1 --measurement-time 5`.
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use triad::mechanics::{Model, ModelDef, Operating, SolverSettings, State};

#[path = "../tests/common/mod.rs"]
#[allow(clippy::all)]
mod common;

fn operating(def: &ModelDef) -> Operating {
    let m = Model::new(def, SolverSettings::default()).expect("model");
    let s = State::new(&m);
    Operating::of(&m, &s).expect("a tree")
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("linearize");
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/modelDescription/robot_arm/spec.toml"
    ))
    .expect("robot_arm spec");
    let spec =
        triad::spec::Spec::from_str(&text, triad::spec::Format::Toml, "robot_arm").expect("spec");
    let (def, _) = spec.lower().expect("lower");
    let op = operating(&def);
    g.bench_function("robot_arm", |b| b.iter(|| op.linearize(&[]).expect("A, B")));
    for n in [10, 100, 1000] {
        let op = operating(&common::chain(n));
        if n == 1000 {
            g.sample_size(10);
        }
        g.bench_with_input(BenchmarkId::new("chain", n), &op, |b, op| {
            b.iter(|| op.linearize(&[]).expect("A, B"));
        });
    }
    g.finish();
    let mut g = c.benchmark_group("step_map");
    let robot = (def, "robot_arm".to_string());
    // a motor on every joint, as MuJoCo's chain in `bench/transition_mujoco.py`: 2N states,
    // N inputs
    let chains = [10, 100].map(|n| {
        let mut def = common::chain(n);
        for j in &mut def.joints {
            j.actuated = true;
        }
        (def, format!("chain{n}"))
    });
    let boxed = {
        let text = common::contact_models::resting_box();
        let spec =
            triad::spec::Spec::from_str(&text, triad::spec::Format::Toml, "box").expect("spec");
        (spec.lower().expect("lower").0, "box".to_string())
    };
    let sim = triad::sim::Simulation::new(&boxed.0, SolverSettings::default(), 0.0).expect("sim");
    g.bench_function("box_step", |b| {
        b.iter_batched(
            || sim.clone(),
            |mut s| s.advance(1e-3).expect("step"),
            criterion::BatchSize::SmallInput,
        );
    });
    for (def, name) in std::iter::once(robot).chain(chains).chain([boxed]) {
        let sim = triad::sim::Simulation::new(&def, SolverSettings::default(), 0.0).expect("sim");
        // a fresh copy of the run per map, outside the timing
        g.bench_function(name, |b| {
            b.iter_batched(
                || sim.clone(),
                |mut s| s.step_map(1e-3).expect("Ad, Bd"),
                criterion::BatchSize::SmallInput,
            );
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
