//! Jointed systems against analytic references (theory.md §5.2), built as `ModelDef`s:
//!
//! * B4 rotor spin-up: ground revolute at the centre of mass, `τ = τ₀ sin²(πt/T_s)` on
//!   `[0, T_s]` sampled at step midpoints; final rate `ω_f = τ₀T_s/(2J) = 5.940594` rad/s exactly
//!   (consistent torque), and `J θ̇ = ∫τ dt` at every node (order 2 and 4);
//! * B6 physical pendulum: `T = 4√(J_O/(m g l_c)) K(sin²(α₀/2))` = 1.638499 s (α₀ = 0.02) and
//!   2.177355 s (α₀ = 2), period from zero crossings, EM errors ≈ 8.0e-4/1.48e-3 s (h = 0.02) and
//!   2.0e-4/3.7e-4 s (h = 0.01), second order; energy constant;
//! * B8 free-floating revolute motor and prismatic actuator: total `p` and `L` constant,
//!   `E − W` constant (W = work of the inputs), order 2 and 4;
//! * a Grashof crank-rocker four-bar (one loop-closing revolute, parallel axes, gravity in the
//!   plane) for 10 s: energy constant to 1e-10 relative, constraints below 1e-10.

mod common;

use triad::math::{exp_so3, Mat3, Vec3};
use triad::mechanics::{
    step, BodyDef, Frame, FreeBodyInitial, JointDef, JointInitial, JointType, Model, ModelDef,
    SolverSettings, State,
};

/// Scales a tolerance by the env knob `TRIAD_TOL_SCALE` (default 1), as `tests/common::tol`.
fn tol(x: f64) -> f64 {
    let s = std::env::var("TRIAD_TOL_SCALE")
        .ok()
        .and_then(|v| v.parse::<f64>().ok());
    x * s.unwrap_or(1.0)
}

fn settings(h: f64, order: u8) -> SolverSettings {
    SolverSettings {
        max_step: h,
        order,
        tolerance: 1e-12,
        max_iterations: 30,
        ..SolverSettings::default()
    }
}

fn box_inertia(m: f64, a: f64, b: f64, c: f64) -> Mat3 {
    Mat3::from_diagonal(&Vec3::new(b * b + c * c, a * a + c * c, a * a + b * b)) * (m / 12.0)
}

fn body(name: &str, mass: f64, com: Vec3, inertia: Mat3) -> BodyDef {
    BodyDef {
        name: name.into(),
        mass,
        com,
        inertia,
    }
}

fn joint(
    kind: JointType,
    parent: Option<usize>,
    child: usize,
    at: Vec3,
    q: Vec<f64>,
    qd: Vec<f64>,
) -> JointDef {
    JointDef {
        name: format!("j{child}"),
        kind,
        parent,
        child,
        parent_frame: Frame {
            translation: at,
            rotation: Mat3::identity(),
        },
        child_frame: Frame::identity(),
        axis: Vec3::z(),
        axis2: Vec3::x(),
        actuated: false,
        damping: 0.0,
        stiffness: 0.0,
        limits: Default::default(),
        armature: 0.0,
        friction: 0.0,

        loop_closing: false,
        initial: JointInitial::Coords { q, qd },
    }
}

fn model(bodies: Vec<BodyDef>, joints: Vec<JointDef>, gravity: Vec3) -> ModelDef {
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity,
        bodies,
        joints,
        loads: vec![],
        free_bodies: vec![],
        sites: vec![],
    }
}

fn build(def: &ModelDef, h: f64, order: u8) -> (Model, State) {
    let m = Model::new(def, settings(h, order)).unwrap();
    let s = State::new(&m);
    (m, s)
}

/// B4: the spin-up ends at exactly τ₀T_s/(2J) with the consistent joint torque.
#[test]
fn b4_rotor_spin_up_reaches_exact_rate() {
    let j = box_inertia(5.0, 2.0, 0.2, 0.05);
    let (tau0, ts) = (10.0, 2.0);
    let exact = tau0 * ts / (2.0 * j[(2, 2)]);
    assert!((exact - 5.940594).abs() < 1e-6);
    for (h, order) in [(0.05, 2), (0.025, 2), (0.05, 4)] {
        let mut jd = joint(JointType::Revolute, None, 0, Vec3::zeros(), vec![], vec![]);
        jd.actuated = true;
        let def = model(
            vec![body("rotor", 5.0, Vec3::zeros(), j)],
            vec![jd],
            Vec3::zeros(),
        );
        let (m, mut s) = build(&def, h, order);
        let n = (4.0 / h).round() as usize;
        let mut impulse = 0.0;
        for k in 0..n {
            let tm = (k as f64 + 0.5) * h;
            let tau = if tm < ts {
                tau0 * (std::f64::consts::PI * tm / ts).sin().powi(2)
            } else {
                0.0
            };
            s.inputs_mut()[0] = tau;
            step(&m, &mut s, h).unwrap();
            impulse += tau * h;
            let rate = s.outputs().joints[0].qd[0];
            assert!(
                (j[(2, 2)] * rate - impulse).abs() < tol(1e-12),
                "L3 at node {k}: {} vs {impulse}",
                j[(2, 2)] * rate
            );
        }
        let rate = s.outputs().joints[0].qd[0];
        eprintln!(
            "B4 h={h} order {order}: final rate {rate:.15} (exact {exact:.15}), rel error {:e}",
            rate / exact - 1.0
        );
        assert!((rate / exact - 1.0).abs() < tol(1e-12));
    }
}

/// Period of the first full oscillations from upward zero crossings of the joint angle.
fn pendulum_period(alpha0: f64, h: f64) -> (f64, f64) {
    let bar = body(
        "bar",
        1.0,
        Vec3::new(0.5, 0.0, 0.0),
        box_inertia(1.0, 1.0, 0.05, 0.05),
    );
    let mut jd = joint(
        JointType::Revolute,
        None,
        0,
        Vec3::zeros(),
        vec![alpha0],
        vec![0.0],
    );
    // q = 0 hangs straight down (bar along −e2)
    jd.parent_frame.rotation = exp_so3(&(Vec3::z() * -std::f64::consts::FRAC_PI_2));
    let def = model(vec![bar], vec![jd], Vec3::new(0.0, -9.81, 0.0));
    let (m, mut s) = build(&def, h, 2);
    let e0 = s.outputs().energy;
    let (mut crossings, mut prev, mut drift) = (Vec::new(), alpha0, 0.0_f64);
    while crossings.len() < 3 {
        step(&m, &mut s, h).unwrap();
        let q = s.outputs().joints[0].q[0];
        if prev < 0.0 && q >= 0.0 {
            crossings.push(s.time() - h * q / (q - prev));
        }
        prev = q;
        drift = drift.max((s.outputs().energy - e0).abs());
        assert!(s.time() < 20.0, "no oscillation");
    }
    ((crossings[2] - crossings[0]) / 2.0, drift)
}

/// B6: periods at small and large amplitude, second-order errors of the theory's size.
#[test]
fn b6_physical_pendulum_periods() {
    for (alpha0, exact, err) in [
        (0.02, 1.638499, [8.0e-4, 2.0e-4]),
        (2.0, 2.177355, [1.48e-3, 3.7e-4]),
    ] {
        let (t1, d1) = pendulum_period(alpha0, 0.02);
        let (t2, d2) = pendulum_period(alpha0, 0.01);
        let (e1, e2) = ((t1 - exact).abs(), (t2 - exact).abs());
        eprintln!("B6 α0={alpha0}: T={t1:.7} ({e1:.2e}), T={t2:.7} ({e2:.2e}); energy drift {d1:.1e} {d2:.1e}");
        assert!(
            e1 < tol(1.5) * err[0] && e2 < tol(1.5) * err[1],
            "period errors {e1:e} {e2:e}"
        );
        assert!(e1 / e2 > 3.0 && e1 / e2 < 5.0, "order: ratio {}", e1 / e2);
        assert!(
            d1 < tol(1e-10) && d2 < tol(1e-10),
            "energy drift {d1:e} {d2:e}"
        );
    }
}

/// B8 two-body system: A free (COM at the origin), B on a joint at `Xᴬ`, `Xᴮ` along `d₃ᴬ`.
fn b8_model(kind: JointType, q: f64, rates: [f64; 7]) -> ModelDef {
    let (xa, xb) = (Vec3::new(0.3, -0.1, 0.2), Vec3::new(-0.25, 0.05, -0.1));
    let a = body(
        "a",
        3.0,
        Vec3::zeros(),
        Mat3::from_diagonal(&Vec3::new(0.2, 0.3, 0.4)),
    );
    // B's frame is its joint frame: the centre of mass sits at −Xᴮ
    let b = body(
        "b",
        2.0,
        -xb,
        Mat3::from_diagonal(&Vec3::new(0.15, 0.1, 0.12)),
    );
    let mut jd = joint(kind, Some(0), 1, xa, vec![q], vec![rates[6]]);
    jd.actuated = true;
    let mut def = model(vec![a, b], vec![jd], Vec3::zeros());
    def.free_bodies.push(FreeBodyInitial {
        body: 0,
        position: Vec3::zeros(),
        orientation: exp_so3(&Vec3::new(0.2, 0.1, -0.3)),
        velocity: Vec3::new(rates[0], rates[1], rates[2]),
        angular_velocity: Vec3::new(rates[3], rates[4], rates[5]),
    });
    def
}

/// B8: actuated free-floating pairs keep total momentum and angular momentum, E − W constant.
#[test]
fn b8_free_floating_actuators_conserve_momenta() {
    let cases = [
        (
            JointType::Revolute,
            0.3,
            [0.1, -0.2, 0.05, 0.5, -0.3, 1.2, 2.0],
            0.8,
            3.0,
        ),
        (
            JointType::Prismatic,
            0.5,
            [0.1, -0.2, 0.05, 1.5, -0.8, 1.0, 0.3],
            3.0,
            2.0,
        ),
    ];
    for ((kind, q, rates, amp, freq), order) in cases.into_iter().flat_map(|c| [(c, 2), (c, 4)]) {
        let h = 0.02;
        let (m, mut s) = build(&b8_model(kind, q, rates), h, order);
        let (p0, l0) = (s.outputs().p, s.outputs().l);
        let b0 = s.outputs().energy - s.outputs().work;
        let (mut dp, mut dl, mut db) = (0.0_f64, 0.0_f64, 0.0_f64);
        for k in 0..200 {
            s.inputs_mut()[0] = amp * (freq * (k as f64 + 0.5) * h).sin();
            step(&m, &mut s, h).unwrap();
            let o = s.outputs();
            dp = dp.max((o.p - p0).norm());
            dl = dl.max((o.l - l0).norm());
            db = db.max((o.energy - o.work - b0).abs());
        }
        eprintln!(
            "B8 {kind:?} order {order}: |Δp| {dp:.1e}, |ΔL| {dl:.1e} (|L| {:.3}), |Δ(E−W)| {db:.1e}",
            l0.norm()
        );
        assert!(
            dp < tol(1e-12) && dl < tol(1e-12),
            "{kind:?}: momentum drift {dp:e}, {dl:e}"
        );
        assert!(
            db < tol(1e-10) * (1.0 + b0.abs()),
            "{kind:?}: energy balance {db:e}"
        );
    }
}

#[test]
fn four_bar_keeps_energy_and_constraints() {
    let h = 0.005;
    let (m, mut s) = build(&common::four_bar(1.0, 3.0), h, 2);
    eprintln!("four-bar notes: {:?}", m.notes());
    let e0 = s.outputs().energy;
    let (mut de, mut cr) = (0.0_f64, s.outputs().constraint_residual);
    let crank0 = s.outputs().joints[0].q[0];
    for _ in 0..(10.0 / h).round() as usize {
        step(&m, &mut s, h).unwrap();
        de = de.max((s.outputs().energy - e0).abs() / e0.abs());
        cr = cr.max(s.outputs().constraint_residual);
    }
    let turns = (s.outputs().joints[0].q[0] - crank0) / std::f64::consts::TAU;
    eprintln!("four-bar: relative energy drift {de:.1e}, constraint residual {cr:.1e}, crank turns {turns:.2}");
    assert!(de < tol(1e-10), "energy drift {de:e}");
    assert!(cr < tol(1e-10), "constraint residual {cr:e}");
}
