//! The cost of the FMI boundary: one communication step of the shipped double pendulum
//! (h = max_step = 1e-3, one EM sub-step) through the exported `fmi2DoStep`, called in process
//! as a C host would, against the same step through `Simulation::advance` (what `triad
//! simulate` runs) and the bare `mechanics::step`.
//! Run: `cargo bench --bench fmi_boundary -- --warm-up-time 1 --measurement-time 3`.
//!
//! Group `fmi3`: the same double-pendulum step through `fmi3DoStep` against `fmi2DoStep`, and
//! every output of the 6-joint robot_arm read by FMI 3 arrays (one `fmi3GetFloat64` of all
//! output variables) against the FMI 2 scalars (one `fmi2GetReal` of all output scalars).
//! Run: `cargo bench --bench fmi_boundary -- fmi3`.
//!
//! Group `hostile`: one `fmi2DoStep` of H = 1e6 after spinning the shipped space_arm and
//! robot_arm up under ±1000 N·m for 0.05 s, the call that the work bound ends
//! (`sim::WORK_PER_SUBSTEP`): its time in seconds is the bound's cost on this machine.
//! Run: `cargo bench --bench fmi_boundary -- hostile`.
use criterion::{criterion_group, criterion_main, Criterion};
use triad::mechanics::step;
use triad::sim::Simulation;
use triad::spec::{bundled, Format, Spec};

#[path = "../tests/fmu_support/mod.rs"]
#[allow(clippy::all)]
mod fmu_support;

const H: f64 = 1e-3;

fn spec_text() -> &'static str {
    bundled()
        .iter()
        .find(|(name, _)| *name == "double_pendulum")
        .map(|(_, text)| *text)
        .expect("double_pendulum is shipped")
}

fn bench(c: &mut Criterion) {
    let spec = Spec::from_str(spec_text(), Format::Toml, "spec.toml").expect("spec");
    let (def, settings) = spec.lower().expect("lower");
    let mut g = c.benchmark_group("double_pendulum_h1e-3");

    // bare step
    let mut sim = Simulation::new(&def, settings, 0.0).expect("sim");
    let model = sim.model().clone();
    let mut state = sim.state().clone();
    g.bench_function("step", |b| {
        b.iter(|| step(&model, &mut state, H).expect("step"))
    });

    // the simulate path
    g.bench_function("simulation_advance", |b| {
        b.iter(|| sim.advance(H).expect("advance"))
    });

    // the FMI path, called through the exported C functions
    let m = fmu_support::TestModel::new(spec_text());
    let fmu = fmu_support::Fmu::initialised(&m);
    let mut t = 0.0;
    g.bench_function("fmi2DoStep", |b| {
        b.iter(|| {
            assert_eq!(fmu.step(t, H), 0);
            t += H;
        })
    });
    g.finish();
}

/// One hostile `fmi2DoStep` (module docs) of the shipped model `name`.
fn hostile_call(text: &str) {
    let m = fmu_support::TestModel::new(text);
    let fmu = fmu_support::Fmu::initialised(&m);
    let taus = m.vrs(triad::variables::Causality::Input);
    let values: Vec<f64> = (0..taus.len())
        .map(|i| if i % 2 == 0 { 1e3 } else { -1e3 })
        .collect();
    assert_eq!(fmu.set_real(&taus, &values), 0);
    assert_eq!(fmu.step(0.0, 0.05), 0);
    assert_eq!(fmu.set_real(&taus, &vec![0.0; taus.len()]), 0);
    // fmi2Discard at the work bound
    assert_eq!(fmu.step(0.05, 1e6), 2);
}

fn hostile(c: &mut Criterion) {
    let mut g = c.benchmark_group("hostile");
    g.sample_size(10);
    for name in ["space_arm", "robot_arm"] {
        let text = bundled()
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, text)| *text)
            .expect("shipped");
        g.bench_function(name, |b| b.iter(|| hostile_call(text)));
    }
    g.finish();
}

fn fmi3(c: &mut Criterion) {
    use fmu_support::fmi3::{shipped, Fmu3};
    use triad::variables::Causality;
    let mut g = c.benchmark_group("fmi3");
    let m = fmu_support::TestModel::new(spec_text());
    let f2 = fmu_support::Fmu::initialised(&m);
    let f3 = Fmu3::initialised(&m);
    let (mut t2, mut t3) = (0.0, 0.0);
    g.bench_function("fmi2DoStep", |b| {
        b.iter(|| {
            assert_eq!(f2.step(t2, H), 0);
            t2 += H;
        })
    });
    g.bench_function("fmi3DoStep", |b| {
        b.iter(|| {
            assert_eq!(f3.step(t3, H).0, 0);
            t3 += H;
        })
    });
    let arm = shipped("robot_arm");
    let a2 = fmu_support::Fmu::initialised(&arm);
    let a3 = Fmu3::initialised(&arm);
    let scalars = arm.vrs(Causality::Output);
    let (arrays, n) = a3.vrs(&arm, Causality::Output);
    g.bench_function("robot_arm_outputs_fmi2_scalars", |b| {
        b.iter(|| assert_eq!(a2.get_real(&scalars).0, 0))
    });
    g.bench_function("robot_arm_outputs_fmi3_arrays", |b| {
        b.iter(|| assert_eq!(a3.get_f64(&arrays, n).0, 0))
    });
    g.finish();
}

criterion_group!(benches, bench, fmi3, hostile);
criterion_main!(benches);
