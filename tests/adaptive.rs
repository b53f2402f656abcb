//! Error-controlled internal steps (`solver.rtol > 0`, `mechanics::run::control`): every step
//! is still an energy–momentum step, so the invariants stay at round-off whatever sizes the
//! controller picks; communication points and input switches are landed on exactly; the error
//! falls with the tolerance and stays near it; a restored state continues bit for bit.

mod common;
use common::*;
use triad::math::Vec3;
use triad::mechanics::{InputSlot, ModelDef, SolverSettings};
use triad::sim::Simulation;

fn adaptive(order: u8, rtol: f64) -> SolverSettings {
    SolverSettings {
        max_step: 0.1,
        order,
        stages: if order == 4 { 5 } else { 3 },
        rtol,
        ..SolverSettings::default()
    }
}

/// Runs `def` to `t_end` in communication steps `h`, calling `inputs(t, sim)` before each;
/// asserts every step lands exactly on `k·h` (as floats: the sum the caller would form) and
/// returns the simulation and the largest |(energy − work) − (energy − work)₀|.
fn run(
    def: &ModelDef,
    s: SolverSettings,
    h: f64,
    t_end: f64,
    mut inputs: impl FnMut(f64, &mut Simulation),
) -> (Simulation, f64) {
    let mut sim = Simulation::new(def, s, 0.0).unwrap();
    let o = sim.state().outputs();
    let base = o.energy - o.work;
    let mut drift: f64 = 0.0;
    let n = (t_end / h).round() as usize;
    for k in 0..n {
        let t = k as f64 * h;
        assert_eq!(sim.time(), t, "communication point {k}");
        inputs(t, &mut sim);
        sim.advance((k + 1) as f64 * h - t).unwrap();
        assert_eq!(sim.time(), (k + 1) as f64 * h);
        assert_eq!(sim.state().lag(), 0.0);
        let o = sim.state().outputs();
        drift = drift.max(((o.energy - o.work) - base).abs());
        assert!(o.constraint_residual < 1e-10, "{}", o.constraint_residual);
    }
    (sim, drift)
}

fn torque_slots(sim: &Simulation) -> Vec<usize> {
    (0..3)
        .map(|i| {
            sim.model()
                .inputs()
                .iter()
                .position(|s| *s == InputSlot::BodyTorque { body: 0, i })
                .unwrap()
        })
        .collect()
}

/// A free body under a torque pulse on [0.3, 0.7) s, communication step 0.1 s, at orders 2
/// and 4: the angular momentum is `L₀ + τ·(time under torque)` and the linear momentum
/// constant to round-off, `energy − work` too, and the controller took steps of many sizes.
#[test]
fn free_body_torque_pulse_keeps_invariants() {
    let def = free_body(
        2.0,
        inertia6([1.0, 2.0, 3.0, 0.1, 0.0, -0.2]),
        rot([0.3, -0.2, 0.5]),
        Vec3::new(0.05, 2.0, 0.05),
        Vec3::new(0.3, 0.0, -0.1),
        true,
        false,
    );
    let tau = Vec3::new(0.5, -0.3, 0.2);
    for (order, rtol) in [(2, 1e-5), (4, 1e-8)] {
        let mut slots = Vec::new();
        let (sim, drift) = run(&def, adaptive(order, rtol), 0.1, 2.0, |t, sim| {
            if slots.is_empty() {
                slots = torque_slots(sim);
            }
            let on = (0.3 - 1e-9..0.7 - 1e-9).contains(&t);
            for (i, &s) in slots.iter().enumerate() {
                sim.state_mut().inputs_mut()[s] = if on { tau[i] } else { 0.0 };
            }
        });
        let sim0 = Simulation::new(&def, adaptive(order, rtol), 0.0).unwrap();
        let (l0, p0) = (sim0.state().outputs().l, sim0.state().outputs().p);
        let o = sim.state().outputs();
        let dl = (o.l - (l0 + tau * 0.4)).norm();
        let dp = (o.p - p0).norm();
        eprintln!("order {order}: |ΔL| {dl:.1e}, |Δp| {dp:.1e}, energy − work drift {drift:.1e}");
        assert!(dl < 1e-13 && dp < 1e-13, "{dl:e} {dp:e}");
        assert!(drift < 1e-12 * o.energy.abs().max(1.0), "{drift:e}");
    }
}

/// The heavy top and the ten-link chain keep `energy − work` at round-off under error control
/// (orders 2 and 4), with communication steps that are no multiple of any internal step.
#[test]
fn heavy_top_and_chain_keep_energy() {
    for (name, def, t_end) in [("heavy top", heavy_top(), 2.0), ("chain10", chain(10), 1.0)] {
        for (order, rtol) in [(2, 1e-4), (4, 1e-7)] {
            let (sim, drift) = run(&def, adaptive(order, rtol), 0.037, t_end, |_, _| {});
            let e = sim.state().outputs().energy.abs().max(1.0);
            eprintln!("{name} order {order}: energy − work drift {drift:.1e} (E {e:.2})");
            assert!(drift < 1e-11 * e, "{name} order {order}: {drift:e}");
        }
    }
}

/// Largest joint-coordinate or director difference at the communication points against a
/// fine fixed-step reference.
fn error_against(def: &ModelDef, s: SolverSettings, reference: &[Vec<f64>], h: f64) -> f64 {
    let mut sim = Simulation::new(def, s, 0.0).unwrap();
    let mut worst: f64 = 0.0;
    for (k, r) in reference.iter().enumerate() {
        sim.advance((k + 1) as f64 * h - sim.time()).unwrap();
        let q = sim.state().coordinates();
        worst = worst.max(
            q.iter()
                .zip(r)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max),
        );
    }
    worst
}

fn reference(def: &ModelDef, h: f64, t_end: f64) -> Vec<Vec<f64>> {
    let s = SolverSettings {
        max_step: 2e-4,
        order: 4,
        stages: 5,
        tolerance: 1e-12,
        ..SolverSettings::default()
    };
    let mut sim = Simulation::new(def, s, 0.0).unwrap();
    (1..=(t_end / h).round() as usize)
        .map(|k| {
            sim.advance(k as f64 * h - sim.time()).unwrap();
            sim.state().coordinates().to_vec()
        })
        .collect()
}

/// Tolerance proportionality on the heavy top (order 4) and the double pendulum (order 2):
/// over rtol = 1e-3 … 1e-7 (order 2: … 1e-6) the error falls as the tolerance falls (each
/// decade at least 3× smaller) and stays within a factor 10 of the tolerance (the double
/// pendulum is chaotic: its errors grow ≈ 30× over the 2 s, the bound there is 100×).
#[test]
fn error_is_proportional_to_tolerance() {
    let h = 0.1;
    for (name, def, order, rtols, t_end, bound) in [
        (
            "heavy top",
            heavy_top(),
            4,
            &[1e-3, 1e-4, 1e-5, 1e-6, 1e-7][..],
            2.0,
            10.0,
        ),
        (
            "double pendulum",
            double_pendulum(),
            2,
            &[1e-3, 1e-4, 1e-5, 1e-6][..],
            2.0,
            100.0,
        ),
    ] {
        let r = reference(&def, h, t_end);
        let errs: Vec<f64> = rtols
            .iter()
            .map(|&t| error_against(&def, adaptive(order, t), &r, h))
            .collect();
        eprintln!("{name}: rtol {rtols:?} error {errs:?}");
        for (w, &t) in errs.iter().zip(rtols) {
            assert!(
                *w < bound * t && *w > t / 1000.0,
                "{name} rtol {t:e}: error {w:e}"
            );
        }
        for pair in errs.windows(2) {
            assert!(pair[1] < pair[0] / 3.0, "{name}: {errs:?}");
        }
    }
}

/// A state saved mid-run (controller memory included) and restored into a fresh simulation
/// continues bit for bit.
#[test]
fn restored_state_continues_bit_identically() {
    let def = double_pendulum();
    let s = adaptive(4, 1e-6);
    let mut a = Simulation::new(&def, s, 0.0).unwrap();
    for k in 1..=7 {
        a.advance(k as f64 * 0.05 - a.time()).unwrap();
    }
    let snap = a.state().snapshot();
    let mut b = Simulation::new(&def, s, 0.0).unwrap();
    let model = b.model().clone();
    b.state_mut().restore(&model, &snap).unwrap();
    for k in 8..=40 {
        let t = k as f64 * 0.05;
        a.advance(t - a.time()).unwrap();
        b.advance(t - b.time()).unwrap();
        assert_eq!(a.state().snapshot(), b.state().snapshot(), "at {t}");
    }
    assert!(a.state().control().floor_steps() == 0);
    // the memory carried information: a fresh controller would start elsewhere
    let fresh = Simulation::new(&def, s, 0.0).unwrap();
    let proposal = |x: &Simulation| x.state().control().proposal(x.model());
    assert!(proposal(&a) > 10.0 * proposal(&fresh));
}

/// Fixed steps are untouched by the new settings: rtol = 0 gives the same bits as before
/// (the golden CSVs check the CLI), and an adaptive run takes far fewer steps than a fixed one
/// of the same accuracy on the heavy top.
#[test]
fn rtol_zero_is_fixed_stepping() {
    let def = heavy_top();
    let fixed = SolverSettings {
        max_step: 1e-3,
        ..SolverSettings::default()
    };
    let mut a = Simulation::new(&def, fixed, 0.0).unwrap();
    let mut b = Simulation::new(
        &def,
        SolverSettings {
            atol: 1e-3,
            min_step: 1e-4,
            ..fixed
        },
        0.0,
    )
    .unwrap();
    for k in 1..=20 {
        a.advance(k as f64 * 0.01 - a.time()).unwrap();
        b.advance(k as f64 * 0.01 - b.time()).unwrap();
    }
    assert_eq!(a.state().coordinates(), b.state().coordinates());
}

/// A pendulum released onto its stops (spec of `tests/joint_stops.rs`), stepped by the
/// controlled step itself so that every internal step is seen: each step that enters or leaves
/// a stop contact ends on it (the crossing lies within `events::LANDED` of the step's end),
/// landing retries are asked for, and `energy − work` stays at round-off.
#[test]
fn steps_end_on_joint_stop_contacts() {
    use triad::mechanics::{controlled_step, Model, State, Verdict};
    use triad::spec::{Format, Spec};
    let text = "name = \"P\"\n[[body]]\nname = \"rod\"\nmass = 2.0\ncom = [0.0, 0.0, -1.0]\n\
        inertia = [0.02, 0.02, 0.001]\n[[joint]]\nname = \"hinge\"\ntype = \"revolute\"\n\
        parent = \"world\"\nchild = \"rod\"\naxis = [0.0, 1.0, 0.0]\ninitial = { q = -1.0 }\n\
        upper = 0.5\nlower = -1.2\nstop_stiffness = 2000.0\n";
    let spec = Spec::from_str(text, Format::Toml, "p.toml").unwrap();
    let (def, lowered) = spec.lower().unwrap();
    for order in [2, 4] {
        let a = adaptive(order, 1e-6);
        let settings = SolverSettings {
            max_step: a.max_step,
            order,
            stages: a.stages,
            rtol: a.rtol,
            ..lowered
        };
        let model = Model::new(&def, settings).unwrap();
        let mut s = State::new(&model);
        let e0 = s.outputs().energy;
        let (mut crossings, mut landings, mut drift) = (0, 0, 0.0_f64);
        let mut forced = None;
        let mut q0 = s.outputs().joints[0].q[0];
        while s.time() < 3.0 {
            let h = forced
                .take()
                .unwrap_or_else(|| s.control().proposal(&model).min(3.0 - s.time()));
            match controlled_step(&model, &mut s, h).unwrap() {
                Verdict::Accept => {
                    s.refresh_outputs(&model);
                    let o = s.outputs();
                    let q1 = o.joints[0].q[0];
                    for limit in [0.5, -1.2] {
                        let (x0, x1) = (q0 - limit, q1 - limit);
                        if (x0 <= 0.0) != (x1 <= 0.0) {
                            crossings += 1;
                            let theta = x0 / (x0 - x1);
                            assert!(
                                theta <= 1e-3 || theta >= 1.0 - 1e-3,
                                "order {order}: a step crossed limit {limit} at {theta} of \
                                 its length (t = {})",
                                s.time()
                            );
                        }
                    }
                    drift = drift.max((o.energy - o.work - e0).abs());
                    q0 = q1;
                }
                Verdict::Reject => {}
                Verdict::Land(h_land) => {
                    assert!(h_land > 0.0 && h_land < h);
                    landings += 1;
                    forced = Some(h_land);
                }
            }
        }
        eprintln!(
            "order {order}: {crossings} crossings, {landings} landing retries, drift {drift:.1e} J"
        );
        // the pendulum enters and leaves each stop at least once in 3 s
        assert!(crossings >= 4, "{crossings}");
        assert!(landings >= crossings / 2, "{landings}");
        assert!(drift < 1e-10, "{drift:e}");
    }
}

/// A tight tolerance at order 2 starts with steps so short that the third difference is all
/// the coordinates' noise: the controller doubles them until the estimate means something,
/// instead of holding them (it used to stay at 4e-7 s and exhaust `max_substeps` within
/// 0.04 s), and the error then follows the tolerance.
#[test]
fn tight_tolerances_grow_out_of_the_noise() {
    let def = heavy_top();
    let h = 0.1;
    let r = reference(&def, h, 0.2);
    for rtol in [1e-7, 1e-8] {
        let err = error_against(&def, adaptive(2, rtol), &r, h);
        eprintln!("heavy top order 2, rtol {rtol:e}: error {err:.2e}");
        assert!(err < 10.0 * rtol && err > 0.0, "{err:e}");
    }
}
