//! Unit tests of `joint`.
use super::*;

#[test]
fn axis_frames_are_rotations() {
    let axes = [
        Vec3::x(),
        -Vec3::y(),
        Vec3::z(),
        -Vec3::z(),
        Vec3::new(0.3, -0.4, 0.5).normalize(),
        Vec3::new(0.3, 0.4, -0.86).normalize(),
        // tilted by less than the spacing of doubles at 1: a component normalises to ±1
        Vec3::new(-1.3e-8, -1.000_000_3, 0.0).normalize(),
        Vec3::new(1.0, 0.0, 1e-13).normalize(),
        Vec3::new(0.0, 1e-15, -1.0).normalize(),
    ];
    for n in &axes {
        let s = axis_frame(n);
        assert!((s.transpose() * s - Mat3::identity()).amax() < 1e-15, "{n}");
        assert!((s.determinant() - 1.0).abs() < 1e-15);
        assert!((s.column(2) - n).norm() < 1e-15);
    }
    assert_eq!(axis_frame(&Vec3::z()), Mat3::identity());
}

#[test]
fn degenerate_axes_are_rejected() {
    let mut def = JointDef {
        name: "j".into(),
        kind: JointType::Universal,
        parent: None,
        child: 0,
        parent_frame: Default::default(),
        child_frame: Default::default(),
        axis: Vec3::x(),
        axis2: Vec3::new(0.5, 1.0, 0.0),
        actuated: false,
        damping: 0.0,
        stiffness: 0.0,
        limits: Default::default(),
        armature: 0.0,
        friction: 0.0,

        loop_closing: false,
        initial: Default::default(),
    };
    assert!(joint_frame(&def).is_err());
    def.kind = JointType::Revolute;
    def.axis = Vec3::zeros();
    assert!(joint_frame(&def).is_err());
    def.axis = Vec3::z();
    let body = BodyDef {
        name: "b".into(),
        mass: 1.0,
        com: Vec3::zeros(),
        inertia: Mat3::identity(),
    };
    assert!(JointGeom::new(&def, std::slice::from_ref(&body)).is_ok());
    def.parent_frame.rotation[(0, 1)] = 0.1;
    let e = JointGeom::new(&def, &[body]).unwrap_err().to_string();
    assert!(e.contains("parent frame"), "{e}");
}
