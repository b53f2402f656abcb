//! Criterion benches of the exact continuous-time linear model (`Operating::linearize`, A and B
//! without outputs) at the initial state: the robot arm (6 joints, UR5-like) and chainN
//! (N = 10, 100, 1000: 2N states, N inputs are none, so B is empty; the cost is that of A).
//! Expected growth: 2N dual passes of O(N) and one O(N³) LU: O(N²) + O(N³).
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
}

criterion_group!(benches, bench);
criterion_main!(benches);
