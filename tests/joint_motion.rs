//! Every lower pair in motion (theory.md §3.2, §4.3): a free-floating parent and a child joined
//! by each joint type with non-zero initial rates, 500 EM steps at h = 0.01 (order 2 and 4). The
//! constrained relative motions stay closed, `max |g| ≤ 1e-10` (all joint rows and the internal
//! orthonormality rows), while every free joint coordinate moves, and `E`, `p`, `L` are constant
//! to 1e-12 relative.

mod common;
use common::*;
use triad::math::{Mat3, Vec3};
use triad::mechanics::{step, FreeBodyInitial, JointInitial, JointType, ModelDef};

fn pair(kind: JointType) -> ModelDef {
    let mut j = joint(
        "j",
        kind,
        Some(0),
        1,
        Vec3::new(0.3, -0.1, 0.2),
        Vec3::new(0.0, 0.6, 0.8),
    );
    j.axis2 = Vec3::x();
    j.parent_frame.rotation = rot([0.2, -0.1, 0.3]);
    let (q, qd): (Vec<f64>, Vec<f64>) = match kind {
        JointType::Revolute => (vec![0.3], vec![2.0]),
        JointType::Prismatic => (vec![0.4], vec![0.5]),
        JointType::Cylindrical => (vec![0.2, 0.4], vec![0.5, -1.5]),
        JointType::Universal => (vec![0.2, -0.3], vec![1.5, -1.0]),
        JointType::Planar => (vec![0.1, -0.2, 0.3], vec![0.4, -0.3, 1.2]),
        JointType::Spherical | JointType::Fixed => (vec![], vec![]),
    };
    j.initial = if kind == JointType::Spherical {
        JointInitial::Spherical {
            quat: [0.9, 0.2, -0.1, 0.3],
            w: Vec3::new(1.0, -2.0, 0.5),
        }
    } else {
        JointInitial::Coords { q, qd }
    };
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
                Vec3::new(0.1, 0.05, 0.2),
                Mat3::from_diagonal(&Vec3::new(0.15, 0.1, 0.12)),
            ),
        ],
        joints: vec![j],
        loads: vec![],
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
fn every_joint_type_holds_its_constraints_and_moves() {
    for kind in KINDS {
        for order in [2, 4] {
            let (m, mut s) = build(&pair(kind), settings(0.01, order));
            let q0 = s.outputs().joints[0].q.clone();
            let (e0, p0, l0) = (s.outputs().energy, s.outputs().p, s.outputs().l);
            let mut res = s.outputs().constraint_residual;
            for _ in 0..500 {
                step(&m, &mut s, 0.01).unwrap();
                res = res.max(s.outputs().constraint_residual);
            }
            let o = s.outputs();
            let de = rel(o.energy, e0, 1e-300);
            let dp = (o.p - p0).norm() / p0.norm();
            let dl = (o.l - l0).norm() / l0.norm();
            let moved = o.joints[0]
                .q
                .iter()
                .zip(&q0)
                .map(|(a, b)| (a - b).abs())
                .fold(f64::INFINITY, f64::min);
            eprintln!("{} order {order}: residual {res:e}, least coordinate change {moved:e}, dE {de:e}, dp {dp:e}, dL {dl:e}", kind.name());
            assert!(
                res < tol(1e-10),
                "{}: constraint residual {res:e}",
                kind.name()
            );
            assert!(
                de < tol(1e-12) && dp < tol(1e-12) && dl < tol(1e-12),
                "{}: {de:e} {dp:e} {dl:e}",
                kind.name()
            );
            if kind != JointType::Fixed {
                assert!(
                    moved > 1e-3,
                    "{}: a free coordinate did not move ({moved:e})",
                    kind.name()
                );
            }
        }
    }
}

/// Joint angles are unwrapped from the given initial value: q₀ = 4.0 rad reads 4.0 (not
/// 4.0 − 2π), and a rotor spinning at 10 rad/s for 200 steps of 0.01 s reads
/// 4.0 + 200 · 2 atan(0.05) rad (the EM step rotates by 2 atan(hω/2) per step) — past 3 turns.
#[test]
fn angles_unwrap_from_the_given_initial_value() {
    let mut j = joint("r", JointType::Revolute, None, 0, Vec3::zeros(), Vec3::z());
    set_q(&mut j, &[4.0], &[10.0]);
    let def = ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::zeros(),
        bodies: vec![body(
            "rotor",
            1.0,
            Vec3::zeros(),
            Mat3::from_diagonal(&Vec3::new(0.1, 0.1, 0.2)),
        )],
        joints: vec![j],
        loads: vec![],
        free_bodies: vec![],
        sites: vec![],
    };
    let (m, mut s) = build(&def, settings(0.01, 2));
    assert!(
        (s.outputs().joints[0].q[0] - 4.0).abs() < 1e-12,
        "{}",
        s.outputs().joints[0].q[0]
    );
    for _ in 0..200 {
        step(&m, &mut s, 0.01).unwrap();
    }
    let q = s.outputs().joints[0].q[0];
    let expected = 4.0 + 200.0 * 2.0 * 0.05_f64.atan();
    assert!((q - expected).abs() < 1e-9, "{q} vs {expected}");
    assert!(
        (s.outputs().joints[0].qd[0] - 10.0).abs() < 1e-6,
        "{}",
        s.outputs().joints[0].qd[0]
    );
}
