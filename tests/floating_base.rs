//! Floating bases (theory.md §4.3, §4.6): a free body may be the root of a tree of joints. The
//! joints' forces and the actuator pairs `±τ n̄`, `±f ∇s` are internal, so with gravity off the
//! EM step keeps the total momenta exactly, whatever the joint torques:
//! `p_{n+1} = p_n`, `L_{n+1} = L_n` (about the world origin), and `E − W` is constant
//! (`W` = the actuators' work minus the dampers' dissipation). With gravity along `−z` only
//! `L_z` and `E − W` are first integrals. Checked over 10⁴ steps at h = 1e-3 and 5e-2, orders
//! 2 and 4, under piecewise-constant random torques: drift ≤ 1e-12 relative (with gravity, 10 s
//! of free fall at either step size). Without torques
//! the centre of mass moves uniformly, `c_n = c_0 + n h p/M` (the midpoint rule moves
//! `Σ m φ` by exactly `h p`). Both Newton forms (joint increments and multipliers) give the
//! same solution, and orders 2 and 4 are observed on the floating tree.

mod common;
use common::*;
use triad::math::{Mat3, Vec3};
use triad::mechanics::{step, FreeBodyInitial, JointType, Model, ModelDef, State};

/// A 40 kg base (general inertia) floating with a twist, carrying an arm of three revolute
/// links (axes z, y, y), a prismatic slider and a spherical wrist with a damped ball; all
/// revolute and prismatic joints actuated.
fn floating_tree(gravity: Vec3) -> ModelDef {
    let base_j = inertia6([2.1, 2.9, 3.4, 0.12, -0.05, 0.08]);
    let link = |name: &str, m: f64, l: f64| {
        body(
            name,
            m,
            Vec3::new(0.5 * l, 0.0, 0.0),
            box_inertia(m, l, 0.08, 0.06),
        )
    };
    let bodies = vec![
        body("base", 40.0, Vec3::new(0.02, -0.01, 0.03), base_j),
        link("l1", 3.0, 0.4),
        link("l2", 2.0, 0.35),
        link("l3", 2.0, 0.4),
        link("slider", 0.8, 0.2),
        link("hand", 1.0, 0.3),
    ];
    let mut j1 = joint(
        "j1",
        JointType::Revolute,
        Some(0),
        1,
        Vec3::new(0.3, 0.1, 0.2),
        Vec3::z(),
    );
    let mut j2 = joint(
        "j2",
        JointType::Revolute,
        Some(1),
        2,
        Vec3::new(0.4, 0.0, 0.0),
        Vec3::y(),
    );
    let mut j3 = joint(
        "j3",
        JointType::Revolute,
        Some(2),
        3,
        Vec3::new(0.35, 0.0, 0.0),
        Vec3::y(),
    );
    let mut js = joint(
        "js",
        JointType::Prismatic,
        Some(0),
        4,
        Vec3::new(-0.3, 0.0, -0.2),
        Vec3::new(1.0, 0.2, 0.0).normalize(),
    );
    let mut jw = joint(
        "jw",
        JointType::Spherical,
        Some(3),
        5,
        Vec3::new(0.4, 0.0, 0.0),
        Vec3::z(),
    );
    set_q(&mut j1, &[0.3], &[0.4]);
    set_q(&mut j2, &[-0.5], &[-0.2]);
    set_q(&mut j3, &[0.8], &[0.6]);
    set_q(&mut js, &[0.05], &[0.1]);
    // dampers keep random torques from pumping the motion up without bound over long runs;
    // a spring keeps the slider near its rest place
    // (time constants I/c ≥ 0.3 s: the order-4 composition's backward middle stage must not
    // meet a damper faster than its step)
    for j in [&mut j1, &mut j2, &mut j3, &mut js] {
        j.actuated = true;
        j.damping = 0.2;
    }
    js.damping = 0.3;
    js.stiffness = 40.0;
    jw.damping = 1e-3;
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity,
        bodies,
        joints: vec![j1, j2, j3, js, jw],
        loads: vec![],
        free_bodies: vec![FreeBodyInitial {
            body: 0,
            position: Vec3::new(0.1, -0.2, 1.0),
            orientation: rot([0.2, -0.1, 0.4]),
            velocity: Vec3::new(0.05, 0.02, -0.03),
            angular_velocity: Vec3::new(0.1, -0.2, 0.15),
        }],
        sites: vec![],
    }
}

/// Centre of mass of the whole model from the body outputs (world frame).
fn centre_of_mass(def: &ModelDef, s: &State) -> Vec3 {
    let (mut c, mut m) = (Vec3::zeros(), 0.0);
    for (b, out) in def.bodies.iter().zip(&s.outputs().bodies) {
        c += (out.r + out.rot * b.com) * b.mass;
        m += b.mass;
    }
    c / m
}

/// Largest drifts over `n` steps with torques redrawn every 50 steps (amplitude `amp`):
/// `(|Δp|/|p₀|, |ΔL∘mask|/|L₀∘mask|, |Δ(E − W)| / scale)`, the scale being the largest of
/// `|E|`, `|W|` and the centre of mass's kinetic energy `|p|²/2M` met in the run (a base
/// falling under gravity turns hundreds of joules of potential energy into motion).
fn drifts(def: &ModelDef, h: f64, order: u8, n: usize, amp: f64, mask: Vec3) -> (f64, f64, f64) {
    let (m, mut s) = build(def, settings(h, order));
    let mass: f64 = def.bodies.iter().map(|b| b.mass).sum();
    let out = s.outputs();
    let (p0, l0) = (out.p, out.l.component_mul(&mask));
    let b0 = out.energy - out.work;
    let mut scale = out.energy.abs().max(1e-3);
    let (mut dp, mut dl, mut de) = (0.0_f64, 0.0_f64, 0.0_f64);
    let mut rng = Rng(0x5eed_u64 + (order as u64) * 7 + (h * 1e4) as u64);
    for k in 0..n {
        if k % 50 == 0 {
            for u in s.inputs_mut() {
                *u = amp * rng.next();
            }
        }
        step(&m, &mut s, h).expect("step converges");
        let out = s.outputs();
        scale = scale
            .max(out.energy.abs())
            .max(out.work.abs())
            .max(out.p.norm_squared() / (2.0 * mass));
        dp = dp.max((out.p - p0).norm() / p0.norm());
        dl = dl.max((out.l.component_mul(&mask) - l0).norm() / l0.norm());
        de = de.max((out.energy - out.work - b0).abs() / scale);
    }
    (dp, dl, de)
}

#[test]
fn momenta_and_energy_balance_exact_under_joint_torques_without_gravity() {
    let def = floating_tree(Vec3::zeros());
    for (h, n) in [(1e-3, 10_000), (5e-2, 10_000)] {
        for order in [2, 4] {
            let (dp, dl, de) = drifts(&def, h, order, n, 1.0, Vec3::new(1.0, 1.0, 1.0));
            eprintln!(
                "h = {h}, order {order}: |Δp|/|p| {dp:.1e}, |ΔL|/|L| {dl:.1e}, Δ(E−W) {de:.1e}"
            );
            assert!(
                dp <= tol(1e-12),
                "h = {h}, order {order}: p drifts by {dp:e}"
            );
            assert!(
                dl <= tol(1e-12),
                "h = {h}, order {order}: L drifts by {dl:e}"
            );
            assert!(
                de <= tol(1e-12),
                "h = {h}, order {order}: E − W drifts by {de:e}"
            );
        }
    }
}

#[test]
fn with_gravity_vertical_angular_momentum_and_energy_balance_are_kept() {
    // 10 s of free fall at both step sizes (the base falls 490 m; much longer runs leave the
    // coordinates so far from the origin that their round-off exceeds the Newton tolerance)
    let def = floating_tree(Vec3::new(0.0, 0.0, -9.81));
    for (h, n) in [(1e-3, 10_000), (5e-2, 200)] {
        for order in [2, 4] {
            let (_, dl, de) = drifts(&def, h, order, n, 1.0, Vec3::z());
            eprintln!("gravity, h = {h}, order {order}: |ΔL_z|/|L_z| {dl:.1e}, Δ(E−W) {de:.1e}");
            assert!(
                dl <= tol(1e-12),
                "h = {h}, order {order}: L_z drifts by {dl:e}"
            );
            assert!(
                de <= tol(1e-12),
                "h = {h}, order {order}: E − W drifts by {de:e}"
            );
        }
    }
}

#[test]
fn without_torques_the_centre_of_mass_moves_uniformly() {
    let def = floating_tree(Vec3::zeros());
    let mass: f64 = def.bodies.iter().map(|b| b.mass).sum();
    for order in [2, 4] {
        let h = 1e-2;
        let (m, mut s) = build(&def, settings(h, order));
        let c0 = centre_of_mass(&def, &s);
        let vc = s.outputs().p / mass;
        let mut worst = 0.0_f64;
        for k in 1..=2000 {
            step(&m, &mut s, h).expect("step converges");
            let expect = c0 + vc * (k as f64 * h);
            worst = worst.max((centre_of_mass(&def, &s) - expect).norm() / expect.norm());
        }
        eprintln!("order {order}: centre of mass off the uniform motion by {worst:.1e}");
        assert!(worst <= tol(1e-13), "order {order}: {worst:e}");
    }
}

#[test]
fn both_newton_forms_give_the_same_floating_motion() {
    let def = floating_tree(Vec3::new(0.0, 0.0, -9.81));
    let s0 = settings(1e-2, 2);
    let reduced = Model::new(&def, s0).unwrap();
    assert!(
        reduced.uses_reduced_solver(),
        "a floating tree takes the reduced form"
    );
    let mut multipliers = Model::new(&def, s0).unwrap();
    multipliers.set_reduced_solver(false);
    let (mut a, mut b) = (State::new(&reduced), State::new(&multipliers));
    let mut rng = Rng(7);
    let mut worst = 0.0_f64;
    for k in 0..300 {
        if k % 20 == 0 {
            let u: Vec<f64> = (0..a.inputs().len()).map(|_| 2.0 * rng.next()).collect();
            a.inputs_mut().copy_from_slice(&u);
            b.inputs_mut().copy_from_slice(&u);
        }
        let sa = step(&reduced, &mut a, 1e-2).unwrap();
        step(&multipliers, &mut b, 1e-2).unwrap();
        assert_eq!(
            sa.fallbacks, 0,
            "step {k} handed back to the multiplier form"
        );
        for (x, y) in a.outputs().bodies.iter().zip(&b.outputs().bodies) {
            worst = worst.max((x.r - y.r).norm()).max((x.rot - y.rot).amax());
        }
    }
    assert!(worst <= tol(1e-11), "forms differ by {worst:e}");
}

/// The base pose and the joint coordinates.
fn snapshot(s: &State) -> (Vec3, Mat3, Vec<f64>) {
    let out = s.outputs();
    let q = out.joints.iter().flat_map(|j| j.q.clone()).collect();
    (out.bodies[0].r, out.bodies[0].rot, q)
}

#[test]
fn orders_two_and_four_are_observed_on_a_floating_tree() {
    let def = floating_tree(Vec3::zeros());
    // constant torques (inputs are held), so the solution is smooth; the reference is an
    // order-4 run at h = 2.5e-4
    let (m, mut s) = build(&def, settings(2.5e-4, 4));
    let u = [0.8, -0.5, 0.3, 0.6];
    s.inputs_mut().copy_from_slice(&u);
    for _ in 0..1600 {
        step(&m, &mut s, 2.5e-4).unwrap();
    }
    let reference = snapshot(&s);
    // error of the base pose and the joint coordinates at t = 0.4 s
    let err = |h: f64, order: u8| {
        let (m, mut s) = build(&def, settings(h, order));
        s.inputs_mut().copy_from_slice(&u);
        let n = (0.4 / h).round() as usize;
        for _ in 0..n {
            step(&m, &mut s, h).unwrap();
        }
        let (r, rot, q) = snapshot(&s);
        let dq = q
            .iter()
            .zip(&reference.2)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        (r - reference.0)
            .norm()
            .max((rot - reference.1).amax())
            .max(dq)
    };
    let p2 = (err(0.02, 2) / err(0.01, 2)).log2();
    let p4 = (err(0.02, 4) / err(0.01, 4)).log2();
    eprintln!("observed orders: {p2:.3}, {p4:.3}");
    assert!((p2 - 2.0).abs() < 0.15, "order 2 observed as {p2}");
    assert!((p4 - 4.0).abs() < 0.3, "order 4 observed as {p4}");
}
