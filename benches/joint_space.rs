//! Criterion benches of the joint-space terms' cost: one EM step (order 2, h = 1e-3) of the same
//! model with and without them. `armature/*`: the peers' chain10 and chain100 plain and with a
//! rotor (armature 0.01 kg·m²) on every joint; `coupling/*`: chain10 plain and with every
//! second joint following the one before it (5 couplings, ratio 0.5); the example gripper with
//! and without its coupling (`examples/specs/gripper.toml`).
//!
//! Run: `cargo bench --bench joint_space -- --warm-up-time 1 --measurement-time 5`.
use criterion::{criterion_group, criterion_main, Criterion};
use triad::mechanics::{step_state, CouplingDef, Model, ModelDef, SolverSettings, State};

#[path = "../tests/common/mod.rs"]
#[allow(clippy::all)]
mod common;

/// Step size, s.
const H: f64 = 1e-3;

fn timed(c: &mut Criterion, group: &str, cases: Vec<(&str, ModelDef)>) {
    let mut g = c.benchmark_group(group);
    for (name, def) in cases {
        let s = SolverSettings {
            max_step: H,
            ..SolverSettings::default()
        };
        let m = Model::new(&def, s).expect("model");
        let s0 = State::new(&m);
        let mut st = s0.clone();
        let mut n = 0;
        g.bench_function(name, |b| {
            b.iter(|| {
                // restart every 2 s of simulated time: the motion the peers are timed on
                n += 1;
                if n % 2000 == 0 {
                    st = s0.clone();
                }
                step_state(&m, &mut st, H).expect("step");
            });
        });
    }
    g.finish();
}

fn with_armature(mut def: ModelDef) -> ModelDef {
    for j in &mut def.joints {
        j.armature = 0.01;
    }
    def
}

fn with_couplings(mut def: ModelDef) -> ModelDef {
    for k in (0..def.joints.len() - 1).step_by(2) {
        // the follower starts where the coupling puts it (at rest)
        let qa = match &def.joints[k].initial {
            triad::mechanics::JointInitial::Coords { q, .. } => q.first().copied().unwrap_or(0.0),
            triad::mechanics::JointInitial::Spherical { .. } => 0.0,
        };
        common::set_q(&mut def.joints[k + 1], &[0.5 * qa], &[]);
        def.couplings.push(CouplingDef {
            a: k,
            b: k + 1,
            ratio: 0.5,
            offset: 0.0,
        });
    }
    def
}

fn gripper(coupled: bool) -> ModelDef {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/specs/gripper.toml");
    let text = std::fs::read_to_string(path).expect("gripper");
    let spec = triad::spec::Spec::from_str(&text, triad::spec::Format::Toml, "gripper.toml")
        .expect("spec");
    let (mut def, _) = spec.lower().expect("lower");
    if !coupled {
        def.couplings.clear();
    }
    def
}

fn bench(c: &mut Criterion) {
    timed(
        c,
        "armature",
        vec![
            ("chain10", common::chain(10)),
            ("chain10_armature", with_armature(common::chain(10))),
            ("chain100", common::chain(100)),
            ("chain100_armature", with_armature(common::chain(100))),
        ],
    );
    let plain = common::chain(10);
    let mut uncoupled = with_couplings(common::chain(10));
    uncoupled.couplings.clear();
    timed(
        c,
        "coupling",
        vec![
            ("chain10", uncoupled),
            ("chain10_coupled", with_couplings(plain)),
            ("gripper", gripper(false)),
            ("gripper_coupled", gripper(true)),
        ],
    );
}

criterion_group!(benches, bench);
criterion_main!(benches);
