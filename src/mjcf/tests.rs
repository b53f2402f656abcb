//! MJCF import on small inline models: each orientation form against a rotation computed by
//! hand, angle units and `eulerseq`, default classes, includes, inertia from geoms, the joint
//! types, keyframes, and bad inputs refused with file, line and element.

use std::path::Path;

use super::{import, ImportOptions};
use crate::math::{rpy_to_matrix, Mat3, Vec3};
use crate::spec::{Coords, InertiaSpec, JointKind, OrientationSpec, Spec, SpecErrors};

fn read(text: &str) -> Result<Spec, SpecErrors> {
    read_with(text, &ImportOptions::default())
}

fn read_with(text: &str, opts: &ImportOptions) -> Result<Spec, SpecErrors> {
    import(text, Path::new("model.xml"), opts).map(|(s, _)| s)
}

fn model(body_attrs: &str, compiler: &str) -> String {
    format!(
        r#"<mujoco>{compiler}<worldbody><body name="b" {body_attrs}><joint name="j"/>
        <geom size="0.1"/></body></worldbody></mujoco>"#
    )
}

/// The rotation of the joint frame of a one-body model whose body has `attrs`.
fn rotation(attrs: &str, compiler: &str) -> Mat3 {
    let s = read(&model(attrs, compiler)).unwrap();
    rpy_to_matrix(&Vec3::from(s.joint[0].origin.rpy))
}

fn rot(axis: Vec3, angle: f64) -> Mat3 {
    crate::math::exp_so3(&(axis.normalize() * angle))
}

fn close(a: &Mat3, b: &Mat3) {
    assert!((a - b).amax() < 1e-12, "{a} vs {b}");
}

#[test]
fn every_orientation_form() {
    let (x, y, z) = (Vec3::x(), Vec3::y(), Vec3::z());
    let half = std::f64::consts::FRAC_1_SQRT_2;
    close(
        &rotation(&format!("quat=\"{half} 0 0 {half}\""), ""),
        &rot(z, 90f64.to_radians()),
    );
    close(&rotation("quat=\"2 0 0 0\"", ""), &Mat3::identity());
    close(
        &rotation("axisangle=\"1 1 0 60\"", ""),
        &rot(Vec3::new(1.0, 1.0, 0.0), 60f64.to_radians()),
    );
    // euler in degrees (MuJoCo's default unit), intrinsic x, then y', then z''
    let e = rot(x, 0.3f64.to_degrees().to_radians())
        * rot(y, 20f64.to_radians())
        * rot(z, 45f64.to_radians());
    close(&rotation("euler=\"17.188733853924695 20 45\"", ""), &e);
    // xyaxes: x along (0 1 0), y along (-1 0 0): a quarter turn about z
    close(
        &rotation("xyaxes=\"0 2 0 -1 0.5 0\"", ""),
        &rot(z, 90f64.to_radians()),
    );
    // zaxis: the shortest rotation taking z to (1 0 0): a quarter turn about y
    close(
        &rotation("zaxis=\"3 0 0\"", ""),
        &rot(y, 90f64.to_radians()),
    );
}

#[test]
fn radians_and_euler_sequences() {
    let (x, y, z) = (Vec3::x(), Vec3::y(), Vec3::z());
    let radian = r#"<compiler angle="radian"/>"#;
    close(&rotation("axisangle=\"0 0 1 0.5\"", radian), &rot(z, 0.5));
    close(
        &rotation("euler=\"0.1 0.2 0.3\"", radian),
        &(rot(x, 0.1) * rot(y, 0.2) * rot(z, 0.3)),
    );
    // extrinsic (upper case): about the fixed axes, the first rotation applied first
    let fixed = r#"<compiler angle="radian" eulerseq="XYZ"/>"#;
    close(
        &rotation("euler=\"0.1 0.2 0.3\"", fixed),
        &(rot(z, 0.3) * rot(y, 0.2) * rot(x, 0.1)),
    );
    let zyx = r#"<compiler angle="radian" eulerseq="zyx"/>"#;
    close(
        &rotation("euler=\"0.1 0.2 0.3\"", zyx),
        &(rot(z, 0.1) * rot(y, 0.2) * rot(x, 0.3)),
    );
    // ranges and ref follow the unit
    let text = |c: &str| {
        format!(
            r#"<mujoco>{c}<worldbody><body><joint name="j" range="-90 45" ref="30"/><geom size="0.1"/></body></worldbody></mujoco>"#
        )
    };
    let deg = read(&text("")).unwrap();
    assert!((deg.joint[0].lower.unwrap() + std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    let initial = deg.joint[0].initial.as_ref().and_then(|i| i.q.clone());
    assert_eq!(initial, Some(Coords::Scalar(30f64.to_radians())));
    let rad = read(&text(radian)).unwrap();
    assert_eq!(
        (rad.joint[0].lower, rad.joint[0].upper),
        (Some(-90.0), Some(45.0))
    );
    // autolimits off: a range without limited="true" is no limit
    let off = read(&text(r#"<compiler autolimits="false"/>"#)).unwrap();
    assert_eq!(off.joint[0].lower, None);
}

#[test]
fn default_classes_inherit_and_childclass() {
    let s = read(
        r#"<mujoco>
        <default>
          <joint damping="1" stiffness="2"/>
          <default class="arm"><joint damping="3"/>
            <default class="wrist"><joint axis="1 0 0"/></default>
          </default>
        </default>
        <worldbody>
          <body name="a" childclass="arm"><joint name="shoulder"/><geom size="0.1"/>
            <body name="b"><joint name="elbow" class="main"/><geom size="0.1"/>
              <body name="c"><joint name="wrist" class="wrist"/><geom size="0.1"/></body>
            </body>
          </body>
        </worldbody></mujoco>"#,
    )
    .unwrap();
    let j = |n: &str| &s.joint[s.joint_index(n).unwrap()];
    assert_eq!((j("shoulder").damping, j("shoulder").stiffness), (3.0, 2.0));
    assert_eq!((j("elbow").damping, j("elbow").stiffness), (1.0, 2.0));
    assert_eq!(j("wrist").damping, 3.0);
    assert_eq!(j("wrist").axis, Some([1.0, 0.0, 0.0]));
    assert_eq!(j("shoulder").axis, Some([0.0, 0.0, 1.0]));
}

#[test]
fn include_relative_to_the_including_file() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("parts")).unwrap();
    std::fs::write(
        dir.path().join("parts/arm.xml"),
        r#"<mujoco><body name="arm"><joint name="j"/><geom size="0.1"/><include file="hand.xml"/></body></mujoco>"#,
    )
    .unwrap();
    std::fs::write(
        dir.path().join("parts/hand.xml"),
        r#"<mujoco><site name="tool"/></mujoco>"#,
    )
    .unwrap();
    let main = dir.path().join("robot.xml");
    let text = r#"<mujoco><worldbody><include file="parts/arm.xml"/></worldbody></mujoco>"#;
    let (s, _) = import(text, &main, &ImportOptions::default()).unwrap();
    assert_eq!(s.body[0].name, "arm");
    assert_eq!(s.site[0].name, "tool");
    // a missing include is named
    let bad = r#"<mujoco><worldbody>
      <include file="nowhere.xml"/></worldbody></mujoco>"#;
    let e = import(bad, &main, &ImportOptions::default()).unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.contains("line 2: <include>") && msg.contains("nowhere.xml"),
        "{msg}"
    );
}

#[test]
fn inertia_from_geoms_with_the_parallel_axis_term() {
    // two spheres of 1 kg at x = ±0.5 (mass given) and a box given by density
    let s = read(
        r#"<mujoco><worldbody><body><joint name="j"/>
        <geom size="0.1" pos="0.5 0 0" mass="1"/><geom size="0.1" pos="-0.5 0 0" mass="1"/>
        <geom type="box" size="0.1 0.1 0.1" density="500"/></body></worldbody></mujoco>"#,
    )
    .unwrap();
    let b = &s.body[0];
    let mb = 500.0 * 0.008;
    assert!((b.mass - (2.0 + mb)).abs() < 1e-12);
    let InertiaSpec::Full(j) = b.inertia else {
        panic!()
    };
    let sphere = 0.4 * 0.01;
    let cube = mb * 0.02 / 3.0;
    assert!((j[0] - (2.0 * sphere + cube)).abs() < 1e-12);
    assert!((j[1] - (2.0 * sphere + 2.0 * 0.25 + cube)).abs() < 1e-12);
    // an <inertial> wins (inertiafromgeom auto); boundmass and settotalmass as MuJoCo applies them
    let t = |c: &str| {
        read(&format!(
            r#"<mujoco>{c}<worldbody><body><joint name="j"/><inertial mass="2" diaginertia="1 2 3" pos="0 0 1"/>
            <geom size="1"/><body><joint name="k"/></body></body></worldbody></mujoco>"#
        ))
        .unwrap()
    };
    assert_eq!(
        (t("").body[0].mass, t("").body[0].com),
        (2.0, [0.0, 0.0, 1.0])
    );
    let bounded = t(r#"<compiler boundmass="0.5" boundinertia="0.01" settotalmass="5"/>"#);
    assert!((bounded.body[1].mass - 5.0 * 0.5 / 2.5).abs() < 1e-12);
    assert!((bounded.body[0].mass - 5.0 * 2.0 / 2.5).abs() < 1e-12);
}

#[test]
fn joint_types() {
    let s = read(
        r#"<mujoco><worldbody>
        <body name="base" pos="0 0 1"><freejoint/><geom size="0.1"/>
          <body name="cart"><joint name="s" type="slide" axis="1 0 0"/><geom size="0.1"/>
            <body name="pole"><joint name="h"/><geom size="0.1"/>
              <body name="tip" pos="0 0 1"><geom size="0.1"/></body>
            </body>
            <body name="ball"><joint name="b" type="ball"/><geom size="0.1"/></body>
          </body>
        </body></worldbody></mujoco>"#,
    )
    .unwrap();
    let names: Vec<&str> = s.body.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(names, ["base", "cart", "pole", "ball"]);
    assert_eq!(s.body[0].position, Some([0.0, 0.0, 1.0]));
    let kinds: Vec<JointKind> = s.joint.iter().map(|j| j.kind).collect();
    assert_eq!(
        kinds,
        [
            JointKind::Prismatic,
            JointKind::Revolute,
            JointKind::Spherical
        ]
    );
    // the jointless tip is merged into the pole (its mass at z = 1) and is a site
    assert_eq!(s.site[0].name, "tip");
    assert!((s.body[2].com[2] - 0.5).abs() < 1e-12);
    // two joints in one body: a massless body between them
    let two = read(
        r#"<mujoco><worldbody><body name="u"><joint name="x" axis="1 0 0"/><joint name="y" axis="0 1 0"/>
        <geom size="0.1"/></body></worldbody></mujoco>"#,
    )
    .unwrap();
    assert_eq!(two.body.len(), 2);
    assert_eq!(
        (two.body[0].mass, two.joint[1].parent.as_str()),
        (0.0, "u_x")
    );
}

#[test]
fn keyframes_set_the_initial_state() {
    let text = r#"<mujoco><worldbody>
      <body name="f" pos="0 0 1"><freejoint/><geom size="0.1"/></body>
      <body><joint name="h"/><geom size="0.1"/></body>
      <body><joint name="b" type="ball"/><geom size="0.1"/></body></worldbody>
      <keyframe><key name="k" qpos="1 2 3 0 1 0 0 0.5 1 0 0 0" qvel="1 0 0 0 0 2 3 4 5 6"/></keyframe></mujoco>"#;
    let opts = ImportOptions {
        keyframe: Some("k".into()),
        ..ImportOptions::default()
    };
    let s = read_with(text, &opts).unwrap();
    assert_eq!(s.body[0].position, Some([1.0, 2.0, 3.0]));
    assert_eq!(
        s.body[0].orientation,
        Some(OrientationSpec::Quat([0.0, 1.0, 0.0, 0.0]))
    );
    // the angular velocity is given in the body frame: turned by a half turn about x
    let w = s.body[0].angular_velocity.unwrap();
    assert!((w[2] + 2.0).abs() < 1e-12, "{w:?}");
    let h = s.joint[0].initial.as_ref().unwrap();
    assert_eq!(
        (h.q.clone(), h.qd.clone()),
        (Some(Coords::Scalar(0.5)), Some(Coords::Scalar(3.0)))
    );
    assert_eq!(
        s.joint[1].initial.as_ref().unwrap().w,
        Some([4.0, 5.0, 6.0])
    );
    let e = read_with(
        text,
        &ImportOptions {
            keyframe: Some("kk".into()),
            ..opts
        },
    )
    .unwrap_err();
    assert!(e.to_string().contains("did you mean \"k\""), "{e}");
}

/// The one problem of `text`, as printed.
fn refused(text: &str) -> String {
    let e = read(text).unwrap_err();
    assert_eq!(e.problems.len(), 1, "{e}");
    e.to_string()
}

#[test]
fn bad_inputs_name_file_line_and_element() {
    let m = refused("<mujoco><worldbody>\n<body>\n</worldbody></mujoco>");
    assert!(
        m.starts_with("model.xml: line 3") && m.contains("malformed XML"),
        "{m}"
    );
    let m = refused("<mujoco><worldbody>\n<body><joint name=\"j\" class=\"armm\"/></body></worldbody>\n<default><default class=\"arm\"/></default></mujoco>");
    assert!(
        m.contains("line 2: <joint name=\"j\">")
            && m.contains("class \"armm\"")
            && m.contains("did you mean \"arm\""),
        "{m}"
    );
    let m = refused("<mujoco>\n<tendon/></mujoco>");
    assert!(
        m.contains("line 2: <tendon>") && m.contains("tendons"),
        "{m}"
    );
    let m = refused(
        "<mujoco><worldbody>\n<body><joint/><geom size=\"0.1 x\"/></body></worldbody></mujoco>",
    );
    assert!(
        m.contains("line 2: <geom>") && m.contains("\"x\" is not a finite number"),
        "{m}"
    );
    let m = refused(
        "<mujoco><worldbody><body>\n<composite type=\"grid\"/></body></worldbody></mujoco>",
    );
    assert!(m.contains("line 2: <composite>"), "{m}");
    let m =
        refused("<mujoco><worldbody><body>\n<joint type=\"hing\"/></body></worldbody></mujoco>");
    assert!(m.contains("line 2: <joint>") && m.contains("hinge"), "{m}");
    let m = refused("<robot/>");
    assert!(m.contains("<mujoco>"), "{m}");
}

#[test]
fn a_ball_frictionloss_is_its_friction_cone() {
    let text = r#"<mujoco><worldbody>
      <body><joint name="b" type="ball" frictionloss="0.3" armature="0.1"/><geom size="0.1"/></body>
      </worldbody></mujoco>"#;
    let (s, outcome) = import(text, Path::new("model.xml"), &ImportOptions::default()).unwrap();
    assert_eq!(s.joint[0].kind, JointKind::Spherical);
    assert_eq!(s.joint[0].friction, 0.3);
    assert_eq!(s.joint[0].armature, 0.0);
    let notes = outcome.notes.join("\n");
    assert!(notes.contains("|τ| ≤ 0.3"), "{notes}");
    assert!(
        notes.contains("armature=\"0.1\" of a ball joint is not modelled"),
        "{notes}"
    );
}
