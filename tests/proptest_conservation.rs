//! Property tests (theory.md §4.3): for random inertias (positive definite, triangle
//! inequality), random rotations, angular velocities, step sizes and constant torques, every
//! EM step satisfies `L_{n+1} − L_n = h m` and `E_n − E_0 = W_n` (W the discrete torque work
//! `m·θ`) to round-off; for a random free-floating revolute pair with a motor, total `p` and
//! `L` stay constant and `E − W` too.

mod common;
use common::*;
use proptest::prelude::*;
use triad::math::{Mat3, Vec3};
use triad::mechanics::{step, FreeBodyInitial, JointType, ModelDef};

fn inertia(j: [f64; 3], r: [f64; 3]) -> Mat3 {
    let q = rot(r);
    q * Mat3::from_diagonal(&Vec3::new(j[0], j[1], j[2])) * q.transpose()
}

/// Principal moments from Euler values e > 0: J₁ = e₂ + e₃, … (triangle inequality holds).
fn moments(e: [f64; 3]) -> [f64; 3] {
    [e[1] + e[2], e[0] + e[2], e[0] + e[1]]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn free_body_balances(
        e in prop::array::uniform3(0.05f64..2.0),
        axes in prop::array::uniform3(-3.0f64..3.0),
        r0 in prop::array::uniform3(-3.0f64..3.0),
        w in prop::array::uniform3(-4.0f64..4.0),
        torque in prop::array::uniform3(-2.0f64..2.0),
        h in 0.005f64..0.08,
        order in prop::sample::select(vec![2u8, 4]),
    ) {
        let j = inertia(moments(e), axes);
        let def = free_body(1.5, j, rot(r0), Vec3::from(w), Vec3::new(0.1, -0.2, 0.3), true, false);
        let (m, mut s) = build(&def, settings(h, order));
        let tq = Vec3::from(torque);
        s.inputs_mut().copy_from_slice(tq.as_slice());
        let e0 = s.outputs().energy;
        let lscale = s.outputs().l.norm() + tq.norm() * h * 60.0 + 1.0;
        let mut escale = e0.abs();
        for _ in 0..60 {
            let l_before = s.outputs().l;
            step(&m, &mut s, h).unwrap();
            let o = s.outputs();
            prop_assert!((o.l - l_before - tq * h).norm() <= tol(1e-12) * lscale);
            escale = escale.max(o.energy.abs());
            prop_assert!((o.energy - e0 - o.work).abs() <= tol(1e-11) * escale);
        }
    }

    #[test]
    fn floating_revolute_pair_keeps_momenta(
        e1 in prop::array::uniform3(0.05f64..1.0),
        e2 in prop::array::uniform3(0.05f64..1.0),
        at in prop::array::uniform3(-0.4f64..0.4),
        axis in prop::array::uniform3(-1.0f64..1.0),
        w in prop::array::uniform3(-2.0f64..2.0),
        q0 in -3.0f64..3.0,
        qd in -3.0f64..3.0,
        tau in -2.0f64..2.0,
    ) {
        prop_assume!(Vec3::from(axis).norm() > 0.2);
        let mut j = joint("r", JointType::Revolute, Some(0), 1, Vec3::from(at), Vec3::from(axis).normalize());
        set_q(&mut j, &[q0], &[qd]);
        j.actuated = true;
        let m1 = moments(e1);
        let m2 = moments(e2);
        let def = ModelDef {
            couplings: Vec::new(),
            actuators: Vec::new(),
            contact: Default::default(),
            gravity: Vec3::zeros(),
            bodies: vec![
                body("a", 2.0, Vec3::zeros(), Mat3::from_diagonal(&Vec3::from(m1))),
                body("b", 1.0, Vec3::new(0.2, 0.1, 0.0), Mat3::from_diagonal(&Vec3::from(m2))),
            ],
            joints: vec![j],
            loads: vec![],
            free_bodies: vec![FreeBodyInitial {
                body: 0,
                position: Vec3::zeros(),
                orientation: rot([0.3, 0.2, -0.1]),
                velocity: Vec3::new(0.2, 0.0, -0.1),
                angular_velocity: Vec3::from(w),
            }],
            sites: vec![],
        };
        let (m, mut s) = build(&def, settings(0.02, 2));
        s.inputs_mut()[0] = tau;
        let (p0, l0, e0) = (s.outputs().p, s.outputs().l, s.outputs().energy);
        let mut escale = e0.abs().max(1e-3);
        for _ in 0..100 {
            step(&m, &mut s, 0.02).unwrap();
            let o = s.outputs();
            escale = escale.max(o.energy.abs());
            prop_assert!((o.p - p0).norm() <= tol(1e-12) * (p0.norm() + 1.0));
            prop_assert!((o.l - l0).norm() <= tol(1e-12) * (l0.norm() + 1.0));
            prop_assert!((o.energy - e0 - o.work).abs() <= tol(1e-11) * escale);
        }
    }
}
