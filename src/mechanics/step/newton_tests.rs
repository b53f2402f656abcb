//! Unit tests of the Newton Jacobian against finite differences of the residual, and of the
//! exact product error of `stage_rates` against a fused multiply-add.
use super::*;
use crate::math::{exp_so3, Mat3};
use crate::mechanics::model::def::{
    BodyDef, BodyLoadDef, Frame, FreeBodyInitial, JointDef, JointInitial, JointType, ModelDef,
    SolverSettings,
};

fn body(name: &str, m: f64, j: [f64; 3], com: Vec3) -> BodyDef {
    BodyDef {
        name: name.into(),
        mass: m,
        com,
        inertia: Mat3::from_diagonal(&Vec3::new(j[0], j[1], j[2])),
    }
}

fn joint(
    kind: JointType,
    parent: Option<usize>,
    child: usize,
    at: Vec3,
    axis: Vec3,
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
            rotation: exp_so3(&Vec3::new(0.1, 0.2, -0.1)),
        },
        child_frame: Frame::identity(),
        axis,
        axis2: Vec3::y(),
        actuated: true,
        damping: 0.0,
        stiffness: 0.0,
        limits: Default::default(),
        armature: 0.0,
        friction: 0.0,

        loop_closing: false,
        initial: JointInitial::Coords { q, qd },
    }
}

/// A free body carrying a revolute child (motor) and a prismatic grandchild (actuator), with
/// a spherical-jointed body on the free body, body torque and force loads, gravity.
pub(crate) fn sample() -> ModelDef {
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::new(0.0, 0.0, -9.81),
        bodies: vec![
            body("a", 2.0, [0.3, 0.4, 0.5], Vec3::zeros()),
            body("b", 1.5, [0.1, 0.2, 0.25], Vec3::new(0.2, 0.0, 0.1)),
            body("c", 1.0, [0.05, 0.06, 0.07], Vec3::new(0.0, 0.1, 0.0)),
            body("d", 0.7, [0.02, 0.03, 0.04], Vec3::new(0.0, 0.0, 0.2)),
        ],
        joints: vec![
            joint(
                JointType::Revolute,
                Some(0),
                1,
                Vec3::new(0.3, 0.1, 0.0),
                Vec3::new(0.0, 0.6, 0.8),
                vec![0.4],
                vec![1.5],
            ),
            joint(
                JointType::Prismatic,
                Some(1),
                2,
                Vec3::new(0.0, 0.2, 0.3),
                Vec3::x(),
                vec![0.3],
                vec![-0.4],
            ),
            JointDef {
                initial: JointInitial::Spherical {
                    quat: [0.9, 0.1, -0.2, 0.3],
                    w: Vec3::new(0.5, -1.0, 2.0),
                },
                ..joint(
                    JointType::Spherical,
                    Some(0),
                    3,
                    Vec3::new(-0.2, 0.0, 0.2),
                    Vec3::z(),
                    vec![],
                    vec![],
                )
            },
        ],
        loads: vec![BodyLoadDef {
            body: 0,
            torque: true,
            force: true,
        }],
        free_bodies: vec![FreeBodyInitial {
            body: 0,
            position: Vec3::new(0.1, 0.2, 0.3),
            orientation: exp_so3(&Vec3::new(0.3, -0.5, 0.2)),
            velocity: Vec3::new(0.3, -0.1, 0.2),
            angular_velocity: Vec3::new(1.0, -2.0, 0.5),
        }],
        sites: vec![],
    }
}

fn residual(model: &Model, ws: &mut Work, held: &Held, h: f64) -> Vec<f64> {
    // the Jacobian pass also assembles the full residual
    evaluate(model, ws, held, h, Mode::Full);
    ws.drhs.iter().map(|x| -x).collect()
}

/// The analytic Jacobian matches central differences of the residual (loads without
/// springs and dampers).
#[test]
fn jacobian_matches_finite_differences() {
    let zeros = vec![0.0; sample().joints.len()];
    assert_jacobian(&sample(), &zeros, &zeros, 0.02);
}

/// Also with stiff springs and dampers on the revolute and prismatic joints (the angle
/// spring/damper is the `atan2` discrete gradient of `turn`, whose Jacobian is exact) and a
/// damper on the spherical joint, with large increments and with the joints nearly at rest
/// (increment 1e-9 of the start).
#[test]
fn jacobian_matches_finite_differences_with_springs_and_dampers() {
    // spherical joint (index 2): no spring (refused by the model), a damper
    let stiffness = vec![270.0, 150.0, 0.0];
    let damping = vec![38.0, 20.0, 12.0];
    assert_jacobian(&sample(), &stiffness, &damping, 0.02);
    assert_jacobian(&sample(), &stiffness, &damping, 0.2);
    assert_jacobian(&sample(), &stiffness, &damping, 1e-9);
}

/// Central differences of the residual at an iterate displaced by `scale` (rad, m) from the
/// start against the analytic Jacobian, relative mismatch ≤ 1e-7.
fn assert_jacobian(def: &ModelDef, stiffness: &[f64], damping: &[f64], scale: f64) {
    let mut model = Model::new(def, SolverSettings::default()).expect("model");
    model.dense = true;
    let mut ws = Work::new(&model);
    let inputs: Vec<f64> = (0..model.inputs().len())
        .map(|k| 0.3 + 0.7 * (k as f64).sin())
        .collect();
    let held = Held {
        inputs: &inputs,
        damping,
        stiffness,
        gains: &[],
    };
    let h = 0.05;
    // a nontrivial iterate: predictor-like increments and multipliers
    let nb = model.bodies.len();
    ws.qn.copy_from_slice(&model.q0);
    ws.vn.copy_from_slice(&model.v0);
    super::stage_rates(&mut ws, h);
    ws.q.copy_from_slice(&model.q0);
    ws.dq.fill(0.0);
    ws.drhs.fill(0.0);
    for b in 0..nb {
        for k in 0..6 {
            ws.drhs[6 * b + k] = scale * ((7 * b + k) as f64).cos();
        }
    }
    update(&model, &mut ws);
    for (k, m) in ws.mu.iter_mut().enumerate() {
        *m = 0.01 * (k as f64 + 1.0).sin();
    }
    let base_q = ws.q.clone();
    let base_dq = ws.dq.clone();
    let base_mu = ws.mu.clone();
    evaluate(&model, &mut ws, &held, h, Mode::Full);
    let jac = ws.dense.clone();
    let n = ws.drhs.len();
    let eps = 1e-6;
    let mut worst = 0.0_f64;
    for c in 0..n {
        let mut col = [vec![0.0; n], vec![0.0; n]];
        for (s, sign) in [1.0, -1.0].iter().enumerate() {
            ws.q.copy_from_slice(&base_q);
            ws.dq.copy_from_slice(&base_dq);
            ws.mu.copy_from_slice(&base_mu);
            ws.drhs.fill(0.0);
            ws.drhs[c] = sign * eps;
            update(&model, &mut ws);
            col[s] = residual(&model, &mut ws, &held, h);
        }
        for r in 0..n {
            let fd = (col[0][r] - col[1][r]) / (2.0 * eps);
            let an = jac[r * n + c];
            worst = worst.max((fd - an).abs() / (1.0 + an.abs()));
        }
    }
    assert!(worst < 1e-7, "largest Jacobian mismatch {worst:e}");
}

/// `Mode::Residual` gives bit-identical right-hand sides, norm and work to `Mode::Full` at the
/// same iterate, and leaves the matrices (which may hold factors) untouched.
#[test]
fn residual_mode_matches_full_and_keeps_matrices() {
    const SENTINEL: f64 = 1234.5;
    for dense in [false, true] {
        let mut model = Model::new(&sample(), SolverSettings::default()).expect("model");
        model.dense = dense;
        let mut ws = Work::new(&model);
        let inputs: Vec<f64> = (0..model.inputs().len())
            .map(|k| 0.3 + 0.7 * (k as f64).sin())
            .collect();
        let nj = model.def().joints.len();
        let damping = vec![0.2; nj];
        let stiffness = vec![1.5; nj];
        let held = Held {
            inputs: &inputs,
            damping: &damping,
            stiffness: &stiffness,
            gains: &[],
        };
        let h = 0.05;
        super::stage_rates(&mut ws, h);
        // a nontrivial iterate: a first Newton update from the start, multipliers
        evaluate(&model, &mut ws, &held, h, Mode::Full);
        assert!(solve(&model, &mut ws));
        update(&model, &mut ws);
        for (k, m) in ws.mu.iter_mut().enumerate() {
            *m = 0.01 * (k as f64 + 1.0).sin();
        }
        let full = evaluate(&model, &mut ws, &held, h, Mode::Full);
        let r_full: Vec<Vec<f64>> = ws.blocks.iter().map(|b| b.r.to_vec()).collect();
        let d_full = ws.drhs.clone();
        for b in &mut ws.blocks {
            b.d.fill(SENTINEL);
            b.u.fill(SENTINEL);
            b.l.fill(SENTINEL);
            b.r.fill(-SENTINEL);
        }
        ws.dense.fill(SENTINEL);
        ws.drhs.fill(-SENTINEL);
        let res = evaluate(&model, &mut ws, &held, h, Mode::Residual);
        assert_eq!(res.res.to_bits(), full.res.to_bits(), "dense {dense}");
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        if dense {
            assert_eq!(bits(&ws.drhs), bits(&d_full));
        } else {
            for (b, r) in ws.blocks.iter().zip(&r_full) {
                assert_eq!(bits(&b.r), bits(r));
            }
        }
        for b in &ws.blocks {
            let all = b.d.iter().chain(b.u.iter()).chain(b.l.iter());
            assert!(
                all.into_iter().all(|x| *x == SENTINEL),
                "block matrix touched"
            );
        }
        assert!(
            ws.dense.iter().all(|x| *x == SENTINEL),
            "dense matrix touched"
        );
    }
}

/// `product_error` is the exact rounding error of a product, `a b − fl(a b)`, the value of a
/// fused multiply-add: bit for bit over magnitudes from 1e-12 to 1e12 and both signs (the step
/// sizes and velocities of `stage_rates`).
#[test]
fn product_error_is_exact() {
    let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = || {
        // xorshift64*
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        let r = x.wrapping_mul(0x2545_f491_4f6c_dd1d);
        let u = (r >> 11) as f64 / (1u64 << 53) as f64;
        let e = ((r % 25) as i32) - 12;
        let s = if r & 1 == 0 { 1.0 } else { -1.0 };
        s * (0.5 + u) * 10f64.powi(e)
    };
    let mut nonzero = 0;
    for _ in 0..100_000 {
        let (a, b) = (next(), next());
        let p = a * b;
        let e = super::product_error(super::split(a), super::split(b), p);
        assert_eq!(e.to_bits(), a.mul_add(b, -p).to_bits(), "{a:e} × {b:e}");
        nonzero += usize::from(e != 0.0);
    }
    assert!(nonzero > 90_000, "only {nonzero} inexact products");
}
