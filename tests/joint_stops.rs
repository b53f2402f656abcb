//! Joint limits: a pendulum falling onto its stop rebounds with `energy − work` constant to
//! round-off (the stop is an exact discrete gradient), reaching back to its release height when
//! the stop is elastic; with stop damping the lost energy appears in `system.work`; a slider
//! hits both of its stops; an actuator input beyond `effort` acts as `±effort` and is reported
//! once; the limits are FMU parameters and bad limits are refused by name.

mod common;
use common::triad;
use triad::mechanics::{step, Model, State};
use triad::sim::Simulation;
use triad::spec::{Format, Spec};

/// A 1 m pendulum on a revolute joint about y (q = 0 hangs down), released at q = −1 rad,
/// with stops at `lower`, `upper` and the given extra joint lines.
fn pendulum(extra: &str) -> Spec {
    let text = format!(
        "name = \"P\"\n[[body]]\nname = \"rod\"\nmass = 2.0\ncom = [0.0, 0.0, -1.0]\ninertia = [0.02, 0.02, 0.001]\n\
         [[joint]]\nname = \"hinge\"\ntype = \"revolute\"\nparent = \"world\"\nchild = \"rod\"\naxis = [0.0, 1.0, 0.0]\n\
         actuated = true\ninitial = {{ q = -1.0 }}\n{extra}\n"
    );
    Spec::from_str(&text, Format::Toml, "p.toml").unwrap()
}

struct Run {
    /// Largest |(E − W) − (E₀ − W₀)| / E-scale over the run.
    drift: f64,
    /// Largest q reached.
    q_max: f64,
    /// Smallest q after the first contact (the rebound).
    q_back: f64,
    /// Final work, J.
    work: f64,
    /// Energy lost from the start (E₀ − E at the end), J.
    lost: f64,
}

fn run(spec: &Spec, h: f64, order: u8, seconds: f64) -> Run {
    let (def, mut settings) = spec.lower().unwrap();
    settings.order = order;
    settings.max_step = h;
    let model = Model::new(&def, settings).unwrap();
    let mut s = State::new(&model);
    let e0 = s.outputs().energy;
    let scale = 2.0 * 9.81 * 1.0;
    let (mut drift, mut q_max, mut q_back, mut touched) = (0.0_f64, f64::MIN, f64::MAX, false);
    for _ in 0..(seconds / h).round() as usize {
        step(&model, &mut s, h).unwrap();
        let o = s.outputs();
        drift = drift.max((o.energy - o.work - e0).abs() / scale);
        let q = o.joints[0].q[0];
        q_max = q_max.max(q);
        touched |= q > 0.5;
        if touched {
            q_back = q_back.min(q);
        }
    }
    let o = s.outputs();
    Run {
        drift,
        q_max,
        q_back,
        work: o.work,
        lost: e0 - o.energy,
    }
}

#[test]
fn an_elastic_stop_returns_the_pendulum_with_exact_energy() {
    let spec = pendulum("upper = 0.5\nlower = -2.0\nstop_stiffness = 2000.0");
    for order in [2, 4] {
        for h in [1e-3, 1e-2] {
            let r = run(&spec, h, order, 3.0);
            eprintln!(
                "order {order} h {h}: drift {:.1e}, q max {:.4}, rebound to {:.4}",
                r.drift, r.q_max, r.q_back
            );
            assert!(r.drift <= 1e-10, "energy - work drifted by {:e}", r.drift);
            // it entered the stop, but not far, and came back to its release angle
            assert!(r.q_max > 0.5 && r.q_max < 0.7, "{}", r.q_max);
            assert!((r.q_back + 1.0).abs() < 1e-3, "{}", r.q_back);
            assert_eq!(r.work, 0.0);
        }
    }
}

#[test]
fn stop_damping_is_counted_in_the_work() {
    let spec = pendulum("upper = 0.5\nstop_stiffness = 2000.0\nstop_damping = 400.0");
    let r = run(&spec, 1e-3, 2, 3.0);
    eprintln!(
        "damped stop: drift {:.1e}, lost {:.4} J, work {:.4} J, rebound to {:.4}",
        r.drift, r.lost, r.work, r.q_back
    );
    assert!(r.drift <= 1e-10, "{:e}", r.drift);
    assert!(r.work < -0.5, "the stop dissipated {} J", -r.work);
    assert!(
        (r.lost + r.work).abs() <= 1e-9 * r.lost,
        "{} {}",
        r.lost,
        r.work
    );
    assert!(
        r.q_back > -0.9,
        "an inelastic stop sends it back less far: {}",
        r.q_back
    );
}

#[test]
fn a_slider_hits_both_stops() {
    let text = "name = \"S\"\ngravity = [0.0, 0.0, 0.0]\n[[body]]\nname = \"cart\"\nmass = 3.0\ninertia = [0.1, 0.1, 0.1]\n\
                [[joint]]\nname = \"rail\"\ntype = \"prismatic\"\nparent = \"world\"\nchild = \"cart\"\naxis = [1.0, 0.0, 0.0]\n\
                lower = -0.2\nupper = 0.3\nstop_stiffness = 5e4\nstop_damping = 100.0\ninitial = { q = 0.0, qd = 1.5 }\n";
    let spec = Spec::from_str(text, Format::Toml, "s.toml").unwrap();
    let (def, settings) = spec.lower().unwrap();
    let model = Model::new(&def, settings).unwrap();
    let mut s = State::new(&model);
    let e0 = s.outputs().energy;
    let (mut lo, mut hi, mut drift) = (0.0_f64, 0.0_f64, 0.0_f64);
    for _ in 0..3000 {
        step(&model, &mut s, 1e-3).unwrap();
        let o = s.outputs();
        lo = lo.min(o.joints[0].q[0]);
        hi = hi.max(o.joints[0].q[0]);
        drift = drift.max((o.energy - o.work - e0).abs() / e0);
    }
    eprintln!("slider: range [{lo:.4}, {hi:.4}], drift {drift:.1e}");
    assert!(
        hi > 0.3 && hi < 0.32 && lo < -0.2 && lo > -0.22,
        "[{lo}, {hi}]"
    );
    assert!(drift <= 1e-10, "{drift:e}");
    assert!(
        s.outputs().energy < 0.99 * e0,
        "the damped stops took energy"
    );
}

#[test]
fn inputs_beyond_effort_are_clamped_and_reported_once() {
    let limited = pendulum("effort = 3.0");
    let trajectory = |spec: &Spec, tau: f64| {
        let (def, settings) = spec.lower().unwrap();
        let mut sim = Simulation::new(&def, settings, 0.0).unwrap();
        let mut notices = Vec::new();
        let mut q = Vec::new();
        for _ in 0..50 {
            sim.state_mut().inputs_mut()[0] = tau;
            notices.extend(sim.clamp_notice());
            sim.advance(1e-2).unwrap();
            q.push(sim.state().outputs().joints[0].q[0]);
        }
        (q, notices)
    };
    let (clamped, notices) = trajectory(&limited, 50.0);
    let (at_effort, none) = trajectory(&pendulum(""), 3.0);
    assert_eq!(clamped, at_effort, "50 N·m beyond effort 3 acts as 3");
    assert!(none.is_empty());
    assert_eq!(notices.len(), 1, "{notices:?}");
    assert!(
        notices[0].contains("joint 'hinge'") && notices[0].contains("±3"),
        "{}",
        notices[0]
    );
}

#[test]
fn limits_are_parameters_and_bad_limits_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let spec = pendulum("lower = -2.0\nupper = 0.5\neffort = 3.0\nstop_damping = 10.0");
    std::fs::write(tmp.path().join("p.json"), spec.canonical_json()).unwrap();
    let out = triad(&["describe", "p.json"], tmp.path());
    let table = String::from_utf8_lossy(&out.stdout);
    for name in [
        "joint.hinge.lower",
        "joint.hinge.upper",
        "joint.hinge.effort",
        "joint.hinge.stop_stiffness",
        "joint.hinge.stop_damping",
    ] {
        assert!(
            table
                .lines()
                .any(|l| l.starts_with(name) && l.contains("parameter")),
            "{name} in\n{table}"
        );
    }
    let bad = "name = \"B\"\n[[body]]\nname = \"b\"\nmass = 1.0\ninertia = [1.0, 1.0, 1.0]\n\
               [[joint]]\nname = \"j\"\ntype = \"revolute\"\nparent = \"world\"\nchild = \"b\"\naxis = [0.0, 0.0, 1.0]\n\
               lower = 1.0\nupper = -1.0\neffort = 0.0\nstop_damping = -1.0\n\
               [[body]]\nname = \"c\"\nmass = 1.0\ninertia = [1.0, 1.0, 1.0]\n\
               [[joint]]\nname = \"k\"\ntype = \"spherical\"\nparent = \"b\"\nchild = \"c\"\nupper = 1.0\n";
    let err = Spec::from_str(bad, Format::Toml, "b.toml")
        .unwrap_err()
        .to_string();
    for want in [
        "b.toml: joint[0].upper: must be greater than lower (-1 <= 1)",
        "b.toml: joint[0].effort: must be > 0 (got 0)",
        "b.toml: joint[0].stop_damping: must be >= 0 (got -1)",
        "b.toml: joint[1].upper: only revolute and prismatic joints take limits, not a spherical joint",
    ] {
        assert!(err.contains(want), "missing {want:?} in\n{err}");
    }
}
