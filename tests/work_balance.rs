//! Energy balance with inputs, springs and dampers (theory.md §3.4, B7): the discrete work of
//! every load is exact — motor `τ n̄·(θᴮ − θᴬ)`, slide force `F Δs`, body torque `m·θ`, body force
//! `f·Δφ`; springs use exact discrete gradients (angle: the `atan2` gradient of `turn`, which
//! releases `½k(ϑ₁² − ϑ₀²)`; slide: `−k s̄`); dampers dissipate `c Δϑ²/h`, `c Δs²/h` and, on a
//! spherical joint, `c |θᴮ − θᴬ|²/h` — so `E_n − E_0 = W_n` (inputs' work minus dissipation) to ≤ 1e-10 relative, and free-
//! floating systems keep `p` and `L`.

mod common;
use common::*;
use triad::math::{Mat3, Vec3};
use triad::mechanics::{step, BodyLoadDef, FreeBodyInitial, JointInitial, JointType, ModelDef};

/// B7: spatial double pendulum (ground spherical + revolute with motor and torsional spring).
fn b7(damping: f64) -> ModelDef {
    let mut sph = joint("s", JointType::Spherical, None, 0, Vec3::zeros(), Vec3::z());
    let r1 = triad::math::exp_so3(&Vec3::new(0.0, -0.6, 0.0))
        * triad::math::exp_so3(&Vec3::new(0.4, 0.0, 0.0));
    sph.initial = JointInitial::Spherical {
        quat: triad::math::matrix_to_quat(&r1),
        w: Vec3::new(0.5, 1.0, -0.3),
    };
    sph.damping = damping;
    let mut rev = joint(
        "r",
        JointType::Revolute,
        Some(0),
        1,
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::z(),
    );
    set_q(&mut rev, &[0.7], &[2.0]);
    rev.actuated = true;
    rev.stiffness = 5.0;
    rev.damping = damping;
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::new(0.0, 0.0, -9.81),
        bodies: vec![
            body(
                "b1",
                2.0,
                Vec3::new(0.5, 0.0, 0.0),
                box_inertia(2.0, 1.0, 0.1, 0.1),
            ),
            body(
                "b2",
                1.5,
                Vec3::new(0.4, 0.0, 0.0),
                box_inertia(1.5, 0.8, 0.1, 0.1),
            ),
        ],
        joints: vec![sph, rev],
        loads: vec![],
        free_bodies: vec![],
        sites: vec![],
    }
}

fn balance(
    def: &ModelDef,
    h: f64,
    order: u8,
    n: usize,
    input: impl Fn(f64, &mut [f64]),
) -> (f64, f64) {
    let (m, mut s) = build(def, settings(h, order));
    let e0 = s.outputs().energy;
    let mut scale = e0.abs();
    let mut worst = 0.0_f64;
    for k in 0..n {
        input((k as f64 + 0.5) * h, s.inputs_mut());
        step(&m, &mut s, h).expect("step");
        let o = s.outputs();
        scale = scale.max(o.energy.abs()).max(o.work.abs());
        worst = worst.max((o.energy - e0 - o.work).abs());
    }
    (worst / scale, s.outputs().work)
}

#[test]
fn b7_motor_spring_energy_balance() {
    for (order, c) in [(2, 0.0), (4, 0.0), (2, 0.3), (4, 0.3)] {
        let (err, w) = balance(&b7(c), 0.01, order, 1000, |t, u| {
            u[0] = 2.0 * (2.0 * t).sin()
        });
        eprintln!("b7 order {order} damping {c}: |E − E0 − W| rel {err:e} (W = {w})");
        assert!(err < tol(1e-10), "order {order}, c {c}: {err:e}");
        assert!(w.abs() > 1e-3, "the inputs must do work");
    }
}

/// Free-floating pair: prismatic with actuator, spring and damper on a free body that also
/// carries a body torque and force; a spherical-jointed third body with damping.
fn floating() -> ModelDef {
    let mut pri = joint(
        "p",
        JointType::Prismatic,
        Some(0),
        1,
        Vec3::new(0.3, -0.1, 0.2),
        Vec3::new(0.0, 0.6, 0.8),
    );
    set_q(&mut pri, &[0.4], &[0.5]);
    pri.actuated = true;
    pri.stiffness = 20.0;
    pri.damping = 0.5;
    let mut sph = joint(
        "s",
        JointType::Spherical,
        Some(0),
        2,
        Vec3::new(-0.3, 0.2, 0.0),
        Vec3::z(),
    );
    sph.initial = JointInitial::Spherical {
        quat: [0.9, 0.2, -0.1, 0.3],
        w: Vec3::new(1.0, -2.0, 0.5),
    };
    sph.actuated = true;
    sph.damping = 0.2;
    let mut cyl = joint(
        "c",
        JointType::Cylindrical,
        Some(1),
        3,
        Vec3::new(0.1, 0.1, 0.1),
        Vec3::x(),
    );
    set_q(&mut cyl, &[0.2, 0.5], &[0.3, -1.0]);
    cyl.actuated = true;
    cyl.stiffness = 3.0;
    cyl.damping = 0.1;
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::zeros(),
        bodies: vec![
            body(
                "a",
                3.0,
                Vec3::zeros(),
                Mat3::from_diagonal(&Vec3::new(0.2, 0.3, 0.4)),
            ),
            body(
                "b",
                2.0,
                Vec3::new(0.1, 0.0, 0.05),
                Mat3::from_diagonal(&Vec3::new(0.15, 0.1, 0.12)),
            ),
            body(
                "c",
                1.0,
                Vec3::new(0.0, 0.0, 0.2),
                Mat3::from_diagonal(&Vec3::new(0.05, 0.06, 0.07)),
            ),
            body(
                "d",
                0.5,
                Vec3::new(0.0, 0.1, 0.0),
                Mat3::from_diagonal(&Vec3::new(0.02, 0.03, 0.04)),
            ),
        ],
        joints: vec![pri, sph, cyl],
        loads: vec![BodyLoadDef {
            body: 0,
            torque: true,
            force: true,
        }],
        free_bodies: vec![FreeBodyInitial {
            body: 0,
            position: Vec3::zeros(),
            orientation: rot([0.2, 0.1, -0.3]),
            velocity: Vec3::new(0.1, -0.2, 0.05),
            angular_velocity: Vec3::new(0.5, -0.3, 1.2),
        }],
        sites: vec![],
    }
}

#[test]
fn actuators_springs_dampers_energy_balance_and_momenta() {
    let def = floating();
    for order in [2, 4] {
        // inputs: prismatic f, spherical τ1..3, cylindrical f, τ, body torque, body force
        let (err, w) = balance(&def, 0.02, order, 500, |t, u| {
            u[0] = 3.0 * (2.0 * t).sin();
            u[1] = 0.5 * t.cos();
            u[2] = -0.2;
            u[3] = 0.3 * (3.0 * t).sin();
            u[4] = 1.0 - t.sin();
            u[5] = 0.4 * (1.5 * t).cos();
            for i in 0..3 {
                u[6 + i] = 0.0;
                u[9 + i] = 0.0;
            }
        });
        eprintln!("floating order {order}: |E − E0 − W| rel {err:e} (W = {w})");
        assert!(err < tol(1e-10), "order {order}: {err:e}");
        // without body loads the internal actuators keep p and L
        let (m, mut s) = build(&def, settings(0.02, order));
        let (p0, l0) = (s.outputs().p, s.outputs().l);
        for k in 0..500 {
            let t = (k as f64 + 0.5) * 0.02;
            let u = s.inputs_mut();
            u[0] = 3.0 * (2.0 * t).sin();
            u[1] = 0.5;
            u[4] = -1.0;
            u[5] = 0.4;
            step(&m, &mut s, 0.02).unwrap();
        }
        let dp = (s.outputs().p - p0).norm() / p0.norm();
        let dl = (s.outputs().l - l0).norm() / l0.norm();
        eprintln!("floating order {order}: dp {dp:e} dL {dl:e}");
        assert!(dp < tol(1e-12) && dl < tol(1e-12), "{dp:e} {dl:e}");
    }
    // body force and torque: work f·Δφ + m·θ
    let (err, _) = balance(&def, 0.02, 2, 300, |t, u| {
        u.fill(0.0);
        u[6] = 0.3;
        u[7] = -0.2 * t;
        u[8] = 0.1;
        u[9] = 1.0;
        u[10] = 0.5 * t.sin();
        u[11] = -0.7;
    });
    eprintln!("body loads: |E − E0 − W| rel {err:e}");
    assert!(err < tol(1e-10), "{err:e}");
}
