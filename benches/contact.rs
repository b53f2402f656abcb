//! Criterion bench of what ground contact costs a legged robot (issue 31): one EM step (order 2,
//! h = 1e-3, the step of `examples/quadruped_stand.py`) of Unitree's Go1 from example-robot-data
//! with its four foot spheres on the ground, against the same model without contact.
//!
//! Both are imported as the example imports them (`--floating-base --contacts`; the foot
//! spheres kept, the other shapes dropped), start in the stand pose with the lowest foot 0.1 m
//! above the ground, and step under the example's joint PD loop (the torques set before every
//! step from the outputs, refreshed outside the timing). With contact the robot drops, lands and
//! stands; without, it falls with its legs held. Each run is 2 s from the initial state (the
//! restore is not timed), as in `benches/step.rs`; the mean Newton iterations per step are
//! printed.
//!
//! The URDF is found in the venv's example-robot-data (`bash scripts/setup.sh`), or at
//! `$TRIAD_GO1_URDF`; without it the bench says so and does nothing.
//!
//! A second group, `plate`, shows that ground contact costs O(number of shapes): one free plate
//! (1 kg) resting on n = 4, 16, 64, 256 small spheres on a square grid, against the same plate
//! without a ground (falling). The cost per shape is (step with n − step without) / n; the
//! Newton iterations per step are printed, as the number of iterations can differ with n.
//!
//! Run: `cargo bench --bench contact -- --warm-up-time 1 --measurement-time 5`.
use criterion::measurement::WallTime;
use criterion::{criterion_group, criterion_main, BenchmarkGroup, BenchmarkId, Criterion};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use triad::mechanics::{step_state, InputSlot, Model, State};
use triad::spec::{Coords, Format, InitialSpec, Spec};
use triad::urdf::{import, Base, ImportOptions};

/// Step size, s.
const H: f64 = 1e-3;
/// Steps of one run (2 s).
const WINDOW: u64 = 2000;
/// The stand pose (hip, thigh, calf) and the PD gains of the example.
const STAND: [f64; 3] = [0.0, 0.8, -1.5];
const KP: f64 = 60.0;
const KD: f64 = 3.0;

/// Go1's URDF: `$TRIAD_GO1_URDF`, or the venv's example-robot-data.
fn go1() -> Option<PathBuf> {
    if let Ok(p) = std::env::var("TRIAD_GO1_URDF") {
        return Some(PathBuf::from(p));
    }
    let lib = Path::new(env!("CARGO_MANIFEST_DIR")).join(".venv/lib");
    std::fs::read_dir(lib).ok()?.flatten().find_map(|py| {
        let p = py.path().join(
            "site-packages/cmeel.prefix/share/example-robot-data/robots/go1_description/urdf/go1.urdf",
        );
        p.is_file().then_some(p)
    })
}

/// The target angle of joint `name` (`FR_thigh_joint` → the thigh's).
fn target(name: &str) -> f64 {
    match name.split('_').nth(1) {
        Some("hip") => STAND[0],
        Some("thigh") => STAND[1],
        _ => STAND[2],
    }
}

/// Go1 in the stand pose, the lowest foot 0.1 m above the ground; with the four foot spheres
/// and the ground, or without contact.
fn spec(urdf: &Path, contacts: bool) -> Spec {
    let opts = ImportOptions {
        base: Base::Floating,
        contacts: true,
        ..ImportOptions::default()
    };
    let text = std::fs::read_to_string(urdf).expect("go1.urdf");
    let (mut spec, _) = import(&text, "go1.urdf", &opts).expect("import");
    spec.collision
        .retain(|c| c.name.as_deref().is_some_and(|n| n.ends_with("_foot")));
    assert_eq!(spec.collision.len(), 4, "four feet");
    spec.solver.max_step = H;
    for j in &mut spec.joint {
        j.initial = Some(InitialSpec {
            q: Some(Coords::Scalar(target(&j.name))),
            qd: Some(Coords::Scalar(0.0)),
            ..InitialSpec::default()
        });
    }
    // a translation of the free base moves every foot by as much
    let (m, mut s) = build(&spec);
    s.refresh_outputs(&m);
    let lowest = s
        .outputs()
        .contacts
        .iter()
        .map(|c| c.gap)
        .fold(f64::INFINITY, f64::min);
    let base = spec.body.iter_mut().find(|b| b.position.is_some()).unwrap();
    base.position.as_mut().unwrap()[2] += 0.1 - lowest;
    if !contacts {
        spec.collision.clear();
        spec.ground = None;
    }
    spec
}

fn build(spec: &Spec) -> (Model, State) {
    let (def, settings) = spec.lower().expect("lower");
    let m = Model::new(&def, settings).expect("model");
    let s = State::new(&m);
    (m, s)
}

/// The PD torques into the state's inputs, from its outputs.
fn control(m: &Model, s: &mut State, targets: &[f64]) {
    s.refresh_outputs(m);
    let tau: Vec<f64> = m
        .inputs()
        .iter()
        .map(|slot| match slot {
            InputSlot::JointTorque { joint, .. } => {
                let j = &s.outputs().joints[*joint];
                KP * (targets[*joint] - j.q[0]) - KD * j.qd[0]
            }
            _ => 0.0,
        })
        .collect();
    s.inputs_mut().copy_from_slice(&tau);
}

/// Benchmarks `step` of `name` in group `g`: runs of `WINDOW` steps of `H` from `s0` (the
/// restore is not timed), `before` called before every step outside the timing; prints the
/// mean Newton iterations per step.
fn run(
    g: &mut BenchmarkGroup<'_, WallTime>,
    group: &str,
    name: &str,
    m: &Model,
    s0: &State,
    mut before: impl FnMut(&Model, &mut State),
) {
    let mut s = s0.clone();
    let (mut k, mut steps, mut iters) = (0_u64, 0_u64, 0_usize);
    g.bench_with_input(BenchmarkId::new("step", name), &name, |b, _| {
        b.iter_custom(|n| {
            let mut elapsed = Duration::ZERO;
            for _ in 0..n {
                if k == WINDOW {
                    s.clone_from(s0);
                    k = 0;
                }
                before(m, &mut s);
                let t = Instant::now();
                iters += step_state(m, &mut s, H).expect("step").iterations;
                elapsed += t.elapsed();
                k += 1;
            }
            steps += n;
            elapsed
        });
    });
    if steps > 0 {
        eprintln!(
            "{group}/{name}: {:.2} Newton iterations per step over {steps} steps",
            iters as f64 / steps as f64
        );
    }
}

fn bench(c: &mut Criterion) {
    let Some(urdf) = go1() else {
        eprintln!("contact bench: no go1.urdf (bash scripts/setup.sh, or set TRIAD_GO1_URDF)");
        return;
    };
    let mut g = c.benchmark_group("go1");
    for (name, contacts) in [("feet_on_ground", true), ("no_contact", false)] {
        let sp = spec(&urdf, contacts);
        let targets: Vec<f64> = sp.joint.iter().map(|j| target(&j.name)).collect();
        let (m, s0) = build(&sp);
        run(&mut g, "go1", name, &m, &s0, |m, s| control(m, s, &targets));
    }
    g.finish();
}

/// A 1 kg plate of 0.4 m × 0.4 m resting on an n × n grid of spheres of radius 0.01 m (the
/// ground with stiffness 1e5 · 16 / n² N/m per sphere, so the plate sinks alike for every n), or
/// without a ground.
fn plate(n: usize, ground: bool) -> Spec {
    let k = 1e5 * 16.0 / (n * n) as f64;
    // the static sink under 9.81 N, so the plate starts near rest
    let sink = 9.81 / (k * (n * n) as f64);
    let mut text = format!(
        "name = \"Plate\"\ngravity = [0.0, 0.0, -9.81]\n[solver]\nmax_step = {H}\n\
         [[body]]\nname = \"plate\"\nmass = 1.0\ninertia = [0.0134, 0.0134, 0.0267]\n\
         position = [0.0, 0.0, {}]\n",
        0.01 - sink
    );
    if ground {
        text += &format!("[ground]\nstiffness = {k}\ndamping = 1.0\nfriction = 0.5\n");
    }
    for i in 0..n {
        for j in 0..n {
            let x = -0.2 + 0.4 * (i as f64 + 0.5) / n as f64;
            let y = -0.2 + 0.4 * (j as f64 + 0.5) / n as f64;
            text += &format!(
                "[[collision]]\nbody = \"plate\"\nsphere = {{ radius = 0.01 }}\n\
                 origin = {{ xyz = [{x}, {y}, 0.0] }}\n"
            );
        }
    }
    Spec::from_str(&text, Format::Toml, "plate.toml").expect("plate spec")
}

fn bench_plate(c: &mut Criterion) {
    let mut g = c.benchmark_group("plate");
    for n in [0_usize, 2, 4, 8, 16] {
        let shapes = n * n;
        let sp = if n == 0 {
            plate(2, false)
        } else {
            plate(n, true)
        };
        let (m, s0) = build(&sp);
        let name = if n == 0 {
            "no_ground".to_string()
        } else {
            format!("{shapes}_spheres")
        };
        run(&mut g, "plate", &name, &m, &s0, |_, _| {});
    }
    g.finish();
}

criterion_group!(benches, bench, bench_plate);
criterion_main!(benches);
