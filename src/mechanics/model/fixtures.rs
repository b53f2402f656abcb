//! Test models shared by the unit tests of several layers: the four-bar, a hanging chain and
//! chains closed to the world or to an earlier body (thin rods, exact initial states).

use super::body::BodyInertia;
use super::def::{BodyDef, Frame, JointDef, JointInitial, JointType, ModelDef};
use super::kinematics::initial_configuration;
use crate::math::{Mat3, Vec3};

/// Axial moment of inertia of the test rods, kg·m² (the peers' thin rods have 3.1e-6: the
/// Newton matrix is then ill-conditioned enough that the tree solve alone, without loops,
/// differs from the dense LU by ~5e-11; see `thin_rods_as_accurate_as_the_tree_solve`).
pub(crate) const AX: f64 = 3e-4;
fn body(mass: f64, com: Vec3, j: [f64; 3]) -> BodyDef {
    BodyDef {
        name: format!("b{mass}"),
        mass,
        com,
        inertia: Mat3::from_diagonal(&Vec3::new(j[0], j[1], j[2])),
    }
}

fn revolute(parent: Option<usize>, child: usize, at: Vec3, axis: Vec3, q: f64) -> JointDef {
    JointDef {
        name: format!("j{child}"),
        kind: JointType::Revolute,
        parent,
        child,
        parent_frame: Frame {
            translation: at,
            rotation: Mat3::identity(),
        },
        child_frame: Frame::identity(),
        axis,
        axis2: Vec3::y(),
        actuated: false,
        damping: 0.0,
        stiffness: 0.0,
        limits: Default::default(),
        armature: 0.0,
        friction: 0.0,

        loop_closing: false,
        initial: JointInitial::Coords {
            q: vec![q],
            qd: vec![0.7 * q],
        },
    }
}

/// Crank-rocker four-bar in the xy plane (as `tests/common::four_bar(1, 3)`), closed at the
/// rocker end by a loop revolute to the world (initial rates projected onto the loop).
pub(crate) fn four_bar() -> ModelDef {
    let (g, a, b, c, th) = (2.0, 0.6, 2.2, 1.5, 1.0_f64);
    let link = |len: f64| {
        body(
            len,
            Vec3::new(0.5 * len, 0.0, 0.0),
            [0.002, 0.1 * len, 0.1 * len],
        )
    };
    let pa = Vec3::new(a * th.cos(), a * th.sin(), 0.0);
    let o2 = Vec3::new(g, 0.0, 0.0);
    let dist = (o2 - pa).norm();
    let along = (b * b - c * c + dist * dist) / (2.0 * dist);
    let u = (o2 - pa) / dist;
    let pb = pa + u * along + Vec3::z().cross(&u) * (b * b - along * along).sqrt();
    let th2 = (pb - pa).y.atan2((pb - pa).x);
    let th3 = (o2 - pb).y.atan2((o2 - pb).x);
    let mut close = revolute(None, 2, o2, Vec3::z(), 0.0);
    close.loop_closing = true;
    close.child_frame.translation = Vec3::new(c, 0.0, 0.0);
    let mut j0 = revolute(None, 0, Vec3::zeros(), Vec3::z(), th);
    j0.initial = JointInitial::Coords {
        q: vec![th],
        qd: vec![3.0],
    };
    let j1 = revolute(Some(0), 1, Vec3::new(a, 0.0, 0.0), Vec3::z(), th2 - th);
    let j2 = revolute(Some(1), 2, Vec3::new(b, 0.0, 0.0), Vec3::z(), th3 - th2);
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::new(0.0, -9.81, 0.0),
        bodies: vec![link(a), link(b), link(c)],
        joints: vec![j0, j1, j2, close],
        loads: vec![],
        free_bodies: vec![],
        sites: vec![],
    }
}

/// An open `n`-link chain hanging from the world under gravity (0.25 m, 0.25 kg rods along −z,
/// axes alternating x, y, axial inertia `axial`), bent and turning.
pub(crate) fn hanging_chain(n: usize, axial: f64) -> ModelDef {
    let mut bodies = Vec::new();
    let mut joints = Vec::new();
    for k in 0..n {
        bodies.push(body(
            0.25,
            Vec3::new(0.0, 0.0, -0.125),
            [1.3e-3, 1.3e-3, axial],
        ));
        let axis = if k % 2 == 0 { Vec3::x() } else { Vec3::y() };
        let (parent, at) = if k == 0 {
            (None, Vec3::zeros())
        } else {
            (Some(k - 1), Vec3::new(0.0, 0.0, -0.25))
        };
        joints.push(revolute(
            parent,
            k,
            at,
            axis,
            0.3 * (0.7 * k as f64 + 0.4).sin(),
        ));
    }
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::new(0.0, 0.0, -9.81),
        bodies,
        joints,
        loads: vec![],
        free_bodies: vec![],
        sites: vec![],
    }
}

/// [`hanging_chain`] closed by a loop revolute from the end of the last link to the world or to
/// body `to`, with a spring and a damper on the loop joint.
pub(crate) fn chain_loop(n: usize, to: Option<usize>, axial: f64) -> ModelDef {
    let mut def = hanging_chain(n, axial);
    let (q0, _) = initial_configuration(&def).expect("chain");
    let pose = |b: usize| {
        BodyInertia::new(&def.bodies[b])
            .expect("body")
            .frame_from_coords(&q0[12 * b..12 * b + 12])
    };
    let end = Vec3::new(0.0, 0.0, -0.25);
    let (oe, re) = pose(n - 1);
    let (ot, rt) = to.map_or((Vec3::zeros(), Mat3::identity()), pose);
    let mut close = revolute(to, n - 1, Vec3::zeros(), Vec3::x(), 0.0);
    close.parent_frame = Frame {
        translation: rt.transpose() * (oe + re * end - ot),
        rotation: rt.transpose() * re,
    };
    close.child_frame.translation = end;
    close.loop_closing = true;
    close.stiffness = 40.0;
    close.damping = 0.5;
    def.joints.push(close);
    def
}
