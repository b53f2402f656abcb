//! Joint kinematics of every lower pair (theory.md §3.2–§3.3), on two bodies: a free body A
//! and a body B attached by the joint either to A or to the world, with random frames, axes and
//! joint states. Checked against independent references:
//!
//! * assembled configurations (forward kinematics) satisfy every row, `|g(q0)| ≤ 1e-14`;
//! * `24 − rank [G_int; G_joint](q0) = 6 + f` (SVD), f = degrees of freedom of the pair;
//! * `G(q̄)·(q1 − q0) = g(q1) − g(q0)` for two assembled configurations (also for slides);
//! * `coords(q0)` = the joint coordinates fed to forward kinematics (mod 2π, quaternion sign),
//!   `rates(q0, v0)` = the rates fed to it;
//! * `v0` = central finite difference of forward kinematics along `(q̇, twist)`;
//! * every constraint row has zero rate, `G(q0) v0 = 0`.

mod common;

use common::Rng;
use nalgebra::DMatrix;
use triad::math::{exp_so3, Mat3, Vec3};
use triad::mechanics::constraint::{nodes, Nodes, NODES};
use triad::mechanics::joint::{body_nodes, body_rates, Dof, JointGeom};
use triad::mechanics::kinematics::initial_configuration;
use triad::mechanics::{
    BodyDef, Frame, FreeBodyInitial, JointDef, JointInitial, JointType, ModelDef,
};

const KINDS: [JointType; 7] = [
    JointType::Revolute,
    JointType::Prismatic,
    JointType::Cylindrical,
    JointType::Universal,
    JointType::Spherical,
    JointType::Planar,
    JointType::Fixed,
];

fn body(name: &str, rng: &mut Rng) -> BodyDef {
    let e = Vec3::new(
        0.3 + 0.1 * rng.next(),
        0.2 + 0.1 * rng.next(),
        0.1 + 0.05 * rng.next(),
    );
    let rot = rng.rot();
    let euler = rot * Mat3::from_diagonal(&e) * rot.transpose();
    let inertia = Mat3::identity() * euler.trace() - euler;
    BodyDef {
        name: name.into(),
        mass: 1.0 + rng.next().abs(),
        com: rng.vec(0.3),
        inertia,
    }
}

/// Random joint coordinates and rates of `kind` (spherical: unit quaternion, w > 0).
fn random_state(kind: JointType, rng: &mut Rng) -> JointInitial {
    if kind == JointType::Spherical {
        let mut q = [
            0.5 + 0.5 * rng.next().abs(),
            rng.next(),
            rng.next(),
            rng.next(),
        ];
        let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        q.iter_mut().for_each(|x| *x /= n);
        return JointInitial::Spherical {
            quat: q,
            w: rng.vec(2.0),
        };
    }
    let q = (0..kind.nq()).map(|_| 3.0 * rng.next()).collect();
    let qd = (0..kind.dof()).map(|_| 2.0 * rng.next()).collect();
    JointInitial::Coords { q, qd }
}

/// Body 0 free, body 1 attached by `kind` to body 0 (or to the world).
fn setup(kind: JointType, world_parent: bool, seed: u64) -> ModelDef {
    let mut rng = Rng(seed);
    let bodies = vec![body("a", &mut rng), body("b", &mut rng)];
    let axis = rng.vec(1.0).normalize();
    let axis2 = axis.cross(&rng.vec(1.0)).normalize();
    let joint = JointDef {
        name: "j".into(),
        kind,
        parent: if world_parent { None } else { Some(0) },
        child: 1,
        parent_frame: Frame {
            translation: rng.vec(0.5),
            rotation: rng.rot(),
        },
        child_frame: Frame {
            translation: rng.vec(0.5),
            rotation: rng.rot(),
        },
        axis,
        axis2,
        actuated: false,
        damping: 0.0,
        stiffness: 0.0,
        limits: Default::default(),
        armature: 0.0,
        friction: 0.0,

        loop_closing: false,
        initial: random_state(kind, &mut rng),
    };
    let free = FreeBodyInitial {
        body: 0,
        position: rng.vec(1.0),
        orientation: rng.rot(),
        velocity: rng.vec(1.0),
        angular_velocity: rng.vec(1.5),
    };
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::zeros(),
        bodies,
        joints: vec![joint],
        loads: vec![],
        free_bodies: vec![free],
        sites: vec![],
    }
}

fn cases() -> impl Iterator<Item = (JointType, bool, u64)> {
    KINDS.into_iter().flat_map(|k| {
        [false, true]
            .into_iter()
            .flat_map(move |w| (1..=4).map(move |s| (k, w, s * 7919)))
    })
}

fn pair(g: &JointGeom, q: &[f64]) -> (Nodes, Nodes) {
    (body_nodes(q, g.parent), body_nodes(q, Some(g.child)))
}

/// Gradient of a row as a dense 24-vector over both bodies' coordinates.
fn dense_gradient(
    row: &triad::mechanics::constraint::DotRow,
    g: &JointGeom,
    q: &[f64],
) -> Vec<f64> {
    let (qa, qb) = pair(g, q);
    let mut grad = [Vec3::zeros(); 2 * NODES];
    row.gradient(&qa, &qb, &mut grad);
    let mut out = vec![0.0; 24];
    for k in 0..NODES {
        if let Some(p) = g.parent {
            for c in 0..3 {
                out[12 * p + 3 * k + c] += grad[k][c];
            }
        }
        for c in 0..3 {
            out[12 * g.child + 3 * k + c] += grad[NODES + k][c];
        }
    }
    out
}

/// Internal-constraint Jacobian rows of one body (theory §1.4), dense over 24 columns.
fn internal_rows(q: &[f64], b: usize) -> Vec<Vec<f64>> {
    let d = nodes(&q[12 * b..12 * b + 12]);
    let pairs = [(1, 1), (2, 2), (3, 3), (1, 2), (1, 3), (2, 3)];
    pairs
        .iter()
        .map(|&(i, j)| {
            let mut row = vec![0.0; 24];
            for c in 0..3 {
                row[12 * b + 3 * i + c] += d[j][c];
                row[12 * b + 3 * j + c] += d[i][c];
            }
            row
        })
        .collect()
}

#[test]
fn assembled_configurations_satisfy_every_row() {
    let mut worst: f64 = 0.0;
    for (kind, world, seed) in cases() {
        let def = setup(kind, world, seed);
        let (q0, _) = initial_configuration(&def).unwrap();
        let g = JointGeom::new(&def.joints[0], &def.bodies).unwrap();
        assert_eq!(g.rows.len(), 6 - kind.dof(), "{kind:?}");
        assert_eq!(g.dofs.len(), kind.dof());
        let (qa, qb) = pair(&g, &q0);
        let r = g.residual(&qa, &qb);
        assert!(r <= 1e-14, "{kind:?} world={world}: residual {r:e}");
        worst = worst.max(r);
    }
    println!("largest assembled residual {worst:e}");
}

#[test]
fn rank_counts_degrees_of_freedom() {
    for (kind, world, seed) in cases() {
        let def = setup(kind, world, seed);
        let (q0, _) = initial_configuration(&def).unwrap();
        let g = JointGeom::new(&def.joints[0], &def.bodies).unwrap();
        let mut rows = internal_rows(&q0, 0);
        rows.extend(internal_rows(&q0, 1));
        rows.extend(g.rows.iter().map(|row| dense_gradient(row, &g, &q0)));
        let m = DMatrix::from_fn(rows.len(), 24, |i, j| rows[i][j]);
        let sv = m.singular_values();
        let rank = sv.iter().filter(|&&s| s > 1e-9 * sv.max()).count();
        assert_eq!(
            24 - rank,
            6 + kind.dof(),
            "{kind:?} world={world} singular values {sv}"
        );
    }
}

#[test]
fn midpoint_gradient_is_exact_between_assembled_configurations() {
    for (kind, world, seed) in cases() {
        let def0 = setup(kind, world, seed);
        let mut def1 = setup(kind, world, seed + 1);
        def1.bodies.clone_from(&def0.bodies);
        let keep = def1.joints[0].initial.clone();
        def1.joints[0] = def0.joints[0].clone();
        def1.joints[0].initial = keep;
        let (q0, _) = initial_configuration(&def0).unwrap();
        let (q1, _) = initial_configuration(&def1).unwrap();
        let mid: Vec<f64> = q0.iter().zip(&q1).map(|(a, b)| 0.5 * (a + b)).collect();
        let g = JointGeom::new(&def0.joints[0], &def0.bodies).unwrap();
        let slides = g.dofs.iter().filter_map(|d| {
            if let Dof::Slide(r) = d {
                Some(*r)
            } else {
                None
            }
        });
        for row in g.rows.iter().copied().chain(slides) {
            let grad = dense_gradient(&row, &g, &mid);
            let lin: f64 = grad
                .iter()
                .zip(q1.iter().zip(&q0))
                .map(|(g, (a, b))| g * (a - b))
                .sum();
            let (qa0, qb0) = pair(&g, &q0);
            let (qa1, qb1) = pair(&g, &q1);
            let diff = row.eval(&qa1, &qb1) - row.eval(&qa0, &qb0);
            assert!((lin - diff).abs() < 2e-14, "{kind:?}: {lin:e} vs {diff:e}");
        }
    }
}

fn given(def: &ModelDef) -> (Vec<f64>, Vec<f64>) {
    triad::mechanics::kinematics::joint_initial(&def.joints[0]).unwrap()
}

#[test]
fn coords_and_rates_reproduce_forward_kinematics() {
    let mut worst: f64 = 0.0;
    for (kind, world, seed) in cases() {
        let def = setup(kind, world, seed);
        let (q0, v0) = initial_configuration(&def).unwrap();
        let g = JointGeom::new(&def.joints[0], &def.bodies).unwrap();
        let (want_q, want_qd) = given(&def);
        let (qa, qb) = pair(&g, &q0);
        let (va, vb) = (body_rates(&v0, g.parent), body_rates(&v0, Some(g.child)));
        let mut q = vec![0.0; kind.nq()];
        let mut qd = vec![0.0; kind.dof()];
        g.coords(&qa, &qb, &mut q);
        g.rates(&qa, &qb, &va, &vb, &mut qd);
        let sign = if kind == JointType::Spherical && q[0] * want_q[0] < 0.0 {
            -1.0
        } else {
            1.0
        };
        let tau = std::f64::consts::TAU;
        for (k, (got, want)) in q.iter().zip(&want_q).enumerate() {
            let mut e = sign * got - want;
            let angle = matches!(
                (kind, k),
                (JointType::Revolute, 0)
                    | (JointType::Cylindrical, 1)
                    | (JointType::Universal, _)
                    | (JointType::Planar, 2)
            );
            if angle {
                e -= tau * (e / tau).round();
            }
            assert!(
                e.abs() < 1e-12,
                "{kind:?} world={world} q[{k}]: {got} vs {want}"
            );
            worst = worst.max(e.abs());
        }
        for (k, (got, want)) in qd.iter().zip(&want_qd).enumerate() {
            assert!(
                (got - want).abs() < 1e-12,
                "{kind:?} world={world} qd[{k}]: {got} vs {want}"
            );
            worst = worst.max((got - want).abs());
        }
        // slide handles evaluate to the slide coordinates
        for (k, dof) in g.dofs.iter().enumerate() {
            if let Dof::Slide(row) = dof {
                let idx = if kind == JointType::Planar { k } else { 0 };
                assert!((row.eval(&qa, &qb) - want_q[idx]).abs() < 1e-12);
            }
        }
    }
    println!("largest coordinate/rate error {worst:e}");
}

/// Moves the joint state and the free body along their rates by `eps`.
fn advance(def: &ModelDef, eps: f64) -> ModelDef {
    let mut out = def.clone();
    let (q, qd) = given(def);
    out.joints[0].initial = if def.joints[0].kind == JointType::Spherical {
        // q̇ = ½ q ⊗ (0, w), w in the child frame
        let (w, x, y, z) = (q[0], q[1], q[2], q[3]);
        let (a, b, c) = (qd[0], qd[1], qd[2]);
        let dq = [
            -x * a - y * b - z * c,
            w * a + y * c - z * b,
            w * b + z * a - x * c,
            w * c + x * b - y * a,
        ];
        let quat = std::array::from_fn(|k| q[k] + 0.5 * eps * dq[k]);
        JointInitial::Spherical {
            quat,
            w: Vec3::new(qd[0], qd[1], qd[2]),
        }
    } else {
        JointInitial::Coords {
            q: q.iter().zip(&qd).map(|(a, b)| a + eps * b).collect(),
            qd,
        }
    };
    let f = &mut out.free_bodies[0];
    f.position += f.velocity * eps;
    f.orientation = exp_so3(&(f.angular_velocity * eps)) * f.orientation;
    out
}

#[test]
fn velocities_match_finite_differences_of_forward_kinematics() {
    let eps = 1e-6;
    for (kind, world, seed) in cases() {
        let def = setup(kind, world, seed);
        let (_, v0) = initial_configuration(&def).unwrap();
        let (qp, _) = initial_configuration(&advance(&def, eps)).unwrap();
        let (qm, _) = initial_configuration(&advance(&def, -eps)).unwrap();
        for k in 0..24 {
            let fd = (qp[k] - qm[k]) / (2.0 * eps);
            assert!(
                (fd - v0[k]).abs() < 1e-7 * (1.0 + v0[k].abs()),
                "{kind:?} world={world} v[{k}]: {fd} vs {}",
                v0[k]
            );
        }
    }
}

#[test]
fn constrained_relative_motions_have_zero_rate() {
    let mut worst: f64 = 0.0;
    for (kind, world, seed) in cases() {
        let def = setup(kind, world, seed);
        let (q0, v0) = initial_configuration(&def).unwrap();
        let g = JointGeom::new(&def.joints[0], &def.bodies).unwrap();
        for row in &g.rows {
            let rate: f64 = dense_gradient(row, &g, &q0)
                .iter()
                .zip(&v0)
                .map(|(a, b)| a * b)
                .sum();
            assert!(
                rate.abs() < 1e-13,
                "{kind:?} world={world}: row rate {rate:e}"
            );
            worst = worst.max(rate.abs());
        }
    }
    println!("largest constrained rate {worst:e}");
}
