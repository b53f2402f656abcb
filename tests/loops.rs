//! Loop-closing joints at the start, on a parallelogram four-bar in the xy plane (crank and
//! rocker of length 1 on ground pivots (0,0,0) and (2,0,0), coupler of length 2; revolute axes z;
//! the rocker–ground joint closes the loop).
//!
//! * the assembled loop closes, `|g_loop(q0)| ≤ 1e-14`; a ground pivot moved by 1e-3 gives
//!   `LoopNotClosed` with residual 1e-3;
//! * rates that violate the loop (crank 1 rad/s, others 0) are projected: afterwards
//!   `G(q0) v0 = 0` for every row, and the change is kinetic-energy orthogonal to every admissible
//!   motion, `Nᵀ M_t Δt = 0` (N = null space of `G P`, the optimality condition of
//!   `min ½ Δtᵀ M_t Δt`); consistent rates (crank θ̇, coupler −θ̇, rocker +θ̇) are left alone.

use nalgebra::{DMatrix, DVector};
use triad::math::{Mat3, Vec3};
use triad::mechanics::body::{angular_velocity, rotation};
use triad::mechanics::joint::JointGeom;
use triad::mechanics::kinematics::initial_configuration;
use triad::mechanics::loops::{
    check_loops, loop_residuals, project_loop_velocities, twist_jacobian,
};
use triad::mechanics::{BodyDef, Frame, JointDef, JointInitial, JointType, ModelDef, ModelError};

fn link(name: &str, len: f64) -> BodyDef {
    let (m, w) = (len, 0.05);
    let inertia = Mat3::from_diagonal(&Vec3::new(
        2.0 * w * w,
        len * len + w * w,
        len * len + w * w,
    )) * (m / 12.0);
    BodyDef {
        name: name.into(),
        mass: m,
        com: Vec3::new(0.5 * len, 0.0, 0.0),
        inertia,
    }
}

fn revolute(
    name: &str,
    parent: Option<usize>,
    child: usize,
    at: Vec3,
    q: f64,
    qd: f64,
) -> JointDef {
    JointDef {
        name: name.into(),
        kind: JointType::Revolute,
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
        initial: JointInitial::Coords {
            q: vec![q],
            qd: vec![qd],
        },
    }
}

/// Parallelogram four-bar at crank angle `th` with joint rates `rates`.
fn four_bar(th: f64, rates: [f64; 3]) -> ModelDef {
    let pi = std::f64::consts::PI;
    let mut close = revolute("close", None, 2, Vec3::new(2.0, 0.0, 0.0), 0.0, 0.0);
    close.loop_closing = true;
    close.child_frame.translation = Vec3::new(1.0, 0.0, 0.0);
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::new(0.0, -9.81, 0.0),
        bodies: vec![
            link("crank", 1.0),
            link("coupler", 2.0),
            link("rocker", 1.0),
        ],
        joints: vec![
            revolute("j0", None, 0, Vec3::zeros(), th, rates[0]),
            revolute("j1", Some(0), 1, Vec3::new(1.0, 0.0, 0.0), -th, rates[1]),
            revolute(
                "j2",
                Some(1),
                2,
                Vec3::new(2.0, 0.0, 0.0),
                th + pi,
                rates[2],
            ),
            close,
        ],
        loads: vec![],
        free_bodies: vec![],
        sites: vec![],
    }
}

/// Twists `[φ̇, ω]` per body, and the twist mass matrix `diag(m I, R J Rᵀ)`.
fn twists(def: &ModelDef, q: &[f64], v: &[f64]) -> (DVector<f64>, DMatrix<f64>) {
    let n = def.bodies.len();
    let mut t = DVector::zeros(6 * n);
    let mut m = DMatrix::zeros(6 * n, 6 * n);
    for (b, body) in def.bodies.iter().enumerate() {
        let (qb, vb) = (&q[12 * b..12 * b + 12], &v[12 * b..12 * b + 12]);
        let w = angular_velocity(qb, vb);
        let r = rotation(qb);
        let js = r * body.inertia * r.transpose();
        for c in 0..3 {
            t[6 * b + c] = vb[c];
            t[6 * b + 3 + c] = w[c];
            m[(6 * b + c, 6 * b + c)] = body.mass;
        }
        m.view_mut((6 * b + 3, 6 * b + 3), (3, 3)).copy_from(&js);
    }
    (t, m)
}

fn geoms(def: &ModelDef) -> Vec<JointGeom> {
    def.joints
        .iter()
        .map(|j| JointGeom::new(j, &def.bodies).unwrap())
        .collect()
}

#[test]
fn assembled_loop_closes_and_a_moved_pivot_is_reported() {
    let def = four_bar(1.0, [0.0; 3]);
    let (q0, _) = initial_configuration(&def).unwrap();
    let res = loop_residuals(&def, &q0).unwrap();
    assert_eq!(res.len(), 1);
    assert!(res[0].1 < 1e-14, "loop residual {:e}", res[0].1);
    check_loops(&def, &q0).unwrap();
    let mut moved = def.clone();
    moved.joints[3].parent_frame.translation.x += 1e-3;
    match check_loops(&moved, &q0) {
        Err(ModelError::LoopNotClosed { joint, residual }) => {
            assert_eq!(joint, "close");
            assert!((residual - 1e-3).abs() < 1e-12, "{residual}");
        }
        other => panic!("expected LoopNotClosed, got {other:?}"),
    }
}

#[test]
fn consistent_rates_are_left_alone() {
    let def = four_bar(1.0, [0.7, -0.7, 0.7]);
    let (q0, mut v0) = initial_configuration(&def).unwrap();
    let before = v0.clone();
    assert!(!project_loop_velocities(&def, &q0, &mut v0).unwrap());
    assert_eq!(v0, before);
}

#[test]
fn violating_rates_are_projected_with_least_kinetic_energy_change() {
    let def = four_bar(1.0, [1.0, 0.0, 0.0]);
    let (q0, mut v0) = initial_configuration(&def).unwrap();
    let (t0, mt) = twists(&def, &q0, &v0);
    assert!(project_loop_velocities(&def, &q0, &mut v0).unwrap());
    let (t1, _) = twists(&def, &q0, &v0);
    let a = twist_jacobian(&geoms(&def), &q0, 3);
    let viol = (&a * &t1).amax();
    assert!(
        viol < 1e-12,
        "velocity constraint violation after projection {viol:e}"
    );
    // rigid director velocities after the projection
    for b in 0..3 {
        let w = Vec3::new(t1[6 * b + 3], t1[6 * b + 4], t1[6 * b + 5]);
        for k in 0..3 {
            let d = Vec3::from_column_slice(&q0[12 * b + 3 + 3 * k..12 * b + 6 + 3 * k]);
            let vd = Vec3::from_column_slice(&v0[12 * b + 3 + 3 * k..12 * b + 6 + 3 * k]);
            assert!((vd - w.cross(&d)).norm() < 1e-15);
        }
    }
    // optimality: the change is M_t-orthogonal to the admissible twists (null space of A)
    let svd = a.clone().svd(false, true);
    let vt = svd.v_t.unwrap();
    let tol = 1e-10 * svd.singular_values.max();
    let rank = svd.singular_values.iter().filter(|&&s| s > tol).count();
    assert_eq!(18 - rank, 1, "a four-bar has one degree of freedom");
    let dt = &t1 - &t0;
    let g = &mt * &dt;
    for i in 0..vt.nrows() {
        if svd.singular_values.get(i).copied().unwrap_or(0.0) <= tol {
            let proj = vt.row(i).dot(&g.transpose());
            assert!(proj.abs() < 1e-12, "not KE-minimal: {proj:e}");
        }
    }
    assert!(dt.amax() > 0.1);
}
