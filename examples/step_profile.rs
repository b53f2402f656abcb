//! Callgrind driver of the core step: `cargo build --profile profiling --example step_profile`,
//! then `valgrind --tool=callgrind target/profiling/examples/step_profile dp 2000` (or
//! `chain100 200`, `chainN` for any N, `top`, `free` (a free body near its unstable axis), `fourbar 2000`, `chain100_loop 50`,
//! `chain400_loop`, `chain1000_loop`, or a spec file `*.toml`/`*.json` (its solver settings
//! ignored); an optional third argument is the step size, default
//! 1e-3). Also prints the wall-clock time per step of the run (release build:
//! `cargo run --release --example step_profile chain1000 2000`, the whole 2 s run of the peers'
//! protocol), the iterations, the stages handed to the multiplier form, and on stderr the
//! energy balance `E − E₀ − work` at the end. Same settings as `benches/step.rs` (order 2,
//! h = 1e-3, tolerance 1e-10). Environment: `TRIAD_MULTIPLIERS=1` solves trees in the
//! multiplier form too, `TRIAD_REDUCED=1` every tree in the reduced form (the default); `TRIAD_ARMATURE=A` puts a rotor inertia A on every joint; `TRIAD_COUPLED=1` makes every second joint follow the one before it (ratio 0.5, as `benches/joint_space.rs`); `TRIAD_STEPMAP=1` times the exact Ad, Bd of one step of h (a motor on every joint) instead of stepping; `TRIAD_TRACE=1` prints the energy balance, iterations, stages handed back, energy, work, time and the largest body angular velocity after every step; `TRIAD_ORDER4=1` steps with the
//! order-4 composition (`TRIAD_STAGES5=1`: Suzuki's five stages instead of the triple jump).
use triad::mechanics::{step_state, Model, SolverSettings, State};

#[path = "../tests/common/mod.rs"]
#[allow(clippy::all, dead_code)]
mod common;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let which = args.get(1).map_or("dp", String::as_str);
    let n: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(2000);
    let def = match which {
        "chain10" => common::chain(10),
        "chain100" => common::chain(100),
        "chain1000" => common::chain(1000),
        c if c.starts_with("chain") && c[5..].parse::<usize>().is_ok() => {
            common::chain(c[5..].parse().unwrap())
        }
        "top" => common::heavy_top(),
        "free" => common::free_body(
            1.0,
            common::box_inertia(1.0, 0.1, 0.4, 0.9),
            common::rot([0.1, -0.2, 0.3]),
            triad::math::Vec3::new(0.3, 5.0, 0.2),
            triad::math::Vec3::new(0.1, 0.0, 0.0),
            false,
            false,
        ),
        "fourbar" => common::four_bar(1.0, 3.0),
        "chain100_loop" => common::chain_loop(100, None, 0.0, 0.0),
        "chain400_loop" => common::chain_loop(400, None, 0.0, 0.0),
        "chain1000_loop" => common::chain_loop(1000, None, 0.0, 0.0),
        p if p.ends_with(".toml") || p.ends_with(".json") => {
            let spec = triad::spec::Spec::from_path(std::path::Path::new(p)).expect("spec");
            spec.lower().expect("lower").0
        }
        _ => common::double_pendulum(),
    };
    let mut def = def;
    if let Some(a) = std::env::var("TRIAD_ARMATURE")
        .ok()
        .and_then(|x| x.parse::<f64>().ok())
    {
        for j in &mut def.joints {
            j.armature = a;
        }
    }
    if std::env::var_os("TRIAD_COUPLED").is_some() {
        // every second joint follows the one before it at half its angle (benches/joint_space.rs)
        for k in (0..def.joints.len().saturating_sub(1)).step_by(2) {
            let qa = match &def.joints[k].initial {
                triad::mechanics::JointInitial::Coords { q, .. } => {
                    q.first().copied().unwrap_or(0.0)
                }
                triad::mechanics::JointInitial::Spherical { .. } => 0.0,
            };
            common::set_q(&mut def.joints[k + 1], &[0.5 * qa], &[]);
            def.couplings.push(triad::mechanics::CouplingDef {
                a: k,
                b: k + 1,
                ratio: 0.5,
                offset: 0.0,
            });
        }
    }
    let h: f64 = args.get(3).and_then(|x| x.parse().ok()).unwrap_or(1e-3);
    let s = SolverSettings {
        max_step: h,
        order: if std::env::var_os("TRIAD_ORDER4").is_some() {
            4
        } else {
            2
        },
        stages: if std::env::var_os("TRIAD_STAGES5").is_some() {
            5
        } else {
            3
        },
        tolerance: 1e-10,
        max_iterations: 20,
        ..SolverSettings::default()
    };
    if std::env::var_os("TRIAD_STEPMAP").is_some() {
        // Ad, Bd of one communication step of h, a motor on every joint (benches/linearize.rs)
        for j in &mut def.joints {
            j.actuated = true;
        }
        let sim = triad::sim::Simulation::new(&def, s, 0.0).expect("sim");
        let t0 = std::time::Instant::now();
        for _ in 0..n {
            std::hint::black_box(sim.clone().step_map(h).expect("Ad, Bd"));
        }
        let ms = t0.elapsed().as_secs_f64() * 1e3 / n as f64;
        println!("{which}: {n} step maps, {ms:.3} ms each");
        return;
    }
    let t_build = std::time::Instant::now();
    let mut m = Model::new(&def, s).expect("model");
    if std::env::var_os("TRIAD_MULTIPLIERS").is_some() {
        m.set_reduced_solver(false);
    } else if std::env::var_os("TRIAD_REDUCED").is_some() {
        m.set_reduced_solver(true);
    }
    eprintln!("model built in {:.3} s", t_build.elapsed().as_secs_f64());
    let mut st = State::new(&m);
    let e0 = st.outputs().energy;
    let (mut it, mut fac, mut fb) = (0, 0, 0);
    let trace = std::env::var_os("TRIAD_TRACE").is_some();
    let t0 = std::time::Instant::now();
    for _ in 0..n {
        let s = step_state(&m, &mut st, h).expect("step");
        if trace {
            st.refresh_outputs(&m);
            let o = st.outputs();
            eprintln!(
                "trace {} {:.3e} {} fallbacks {} residual {:.1e} constraints {:.1e} E {:.6e} W {:.3e} t {:.3} max|w| {:.1}",
                it,
                o.energy - e0 - o.work,
                s.iterations,
                s.fallbacks,
                s.residual,
                o.constraint_residual,
                o.energy,
                o.work,
                st.time(),
                o.bodies.iter().map(|b| b.w.norm()).fold(0.0, f64::max)
            );
        }
        it += s.iterations;
        fac += s.factorizations;
        fb += s.fallbacks;
    }
    let us = t0.elapsed().as_secs_f64() * 1e6 / n as f64;
    st.refresh_outputs(&m);
    let o = st.outputs();
    eprintln!(
        "energy: E0 = {e0:.6e} J, E − E0 − work = {:.3e} J, constraint residual {:.1e}",
        o.energy - e0 - o.work,
        o.constraint_residual
    );
    println!(
        "{which}: {n} steps, {:.3} iterations ({:.3} with a fresh Jacobian) per step, {fb} fallbacks, {us:.2} µs per step",
        it as f64 / n as f64,
        fac as f64 / n as f64
    );
}
