//! Unit tests of `kinematics`.
use super::*;
use crate::mechanics::model::def::{BodyDef, FreeBodyInitial};

fn model(joints: &[(Option<usize>, usize, bool)], free: &[usize]) -> ModelDef {
    let body = |k: usize| BodyDef {
        name: format!("b{k}"),
        mass: 1.0,
        com: Vec3::zeros(),
        inertia: Mat3::identity(),
    };
    let joint =
        |(k, &(parent, child, loop_closing)): (usize, &(Option<usize>, usize, bool))| JointDef {
            name: format!("j{k}"),
            kind: JointType::Revolute,
            parent,
            child,
            parent_frame: Default::default(),
            child_frame: Default::default(),
            axis: Vec3::z(),
            axis2: Vec3::x(),
            actuated: false,
            damping: 0.0,
            stiffness: 0.0,
            limits: Default::default(),
            armature: 0.0,
            friction: 0.0,

            loop_closing,
            initial: Default::default(),
        };
    let fb = |&b: &usize| FreeBodyInitial {
        body: b,
        position: Vec3::zeros(),
        orientation: Mat3::identity(),
        velocity: Vec3::zeros(),
        angular_velocity: Vec3::zeros(),
    };
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::zeros(),
        bodies: (0..4).map(body).collect(),
        joints: joints.iter().enumerate().map(joint).collect(),
        loads: vec![],
        free_bodies: free.iter().map(fb).collect(),
        sites: vec![],
    }
}

#[test]
fn parents_come_before_children() {
    let def = model(
        &[
            (Some(2), 0, false),
            (Some(3), 2, false),
            (None, 3, false),
            (Some(1), 0, true),
        ],
        &[1],
    );
    let t = tree_order(&def).unwrap();
    let pos = |b: usize| t.order.iter().position(|&x| x == b).unwrap();
    assert!(pos(3) < pos(2) && pos(2) < pos(0));
    assert_eq!(t.order.len(), 4);
    assert_eq!(t.loop_joints, vec![3]);
    assert_eq!(t.tree_joint, vec![Some(0), None, Some(1), Some(2)]);
    assert_eq!(t.free[1], Some(0));
}

#[test]
fn bad_trees_are_rejected() {
    let no_pose = model(
        &[(None, 0, false), (Some(0), 1, false), (None, 2, false)],
        &[],
    );
    let e = tree_order(&no_pose).unwrap_err().to_string();
    assert!(e.contains("'b3' has no pose"), "{e}");
    let two = model(
        &[
            (None, 0, false),
            (None, 1, false),
            (Some(0), 1, false),
            (None, 2, false),
            (None, 3, false),
        ],
        &[],
    );
    assert!(tree_order(&two)
        .unwrap_err()
        .to_string()
        .contains("two tree joints"));
    let cycle = model(
        &[
            (Some(1), 0, false),
            (Some(0), 1, false),
            (None, 2, false),
            (None, 3, false),
        ],
        &[],
    );
    assert!(tree_order(&cycle)
        .unwrap_err()
        .to_string()
        .contains("cycle"));
    let both = model(&[(None, 0, false)], &[0, 1, 2, 3]);
    assert!(tree_order(&both).is_err());
}

#[test]
fn wrong_initial_lengths_are_rejected() {
    let mut def = model(&[(None, 0, false)], &[1, 2, 3]);
    def.joints[0].initial = JointInitial::Coords {
        q: vec![0.1, 0.2],
        qd: vec![],
    };
    assert!(initial_configuration(&def).is_err());
    def.joints[0].initial = JointInitial::Spherical {
        quat: [1.0, 0.0, 0.0, 0.0],
        w: Vec3::zeros(),
    };
    assert!(initial_configuration(&def).is_err());
}
