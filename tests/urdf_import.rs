//! URDF import: every command takes the URDF; `triad import` writes a spec that builds the
//! same FMU byte for byte; fixed links merged into their parents move exactly as when kept as
//! bodies on fixed joints; inertials are rotated into the link frame; malformed URDFs are
//! answered with the file, the line and the element, a non-zero exit and no file written.

mod common;
use common::{settings, triad};
use std::path::Path;
use triad::math::{rpy_to_matrix, Mat3, Vec3};
use triad::mechanics::{step, Model, State};
use triad::urdf::{import, Base, ImportOptions};

fn arm_path() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/urdf/arm.urdf")
}

fn arm_text() -> String {
    std::fs::read_to_string(arm_path()).unwrap()
}

#[test]
fn import_then_build_gives_the_same_fmu() {
    let tmp = tempfile::tempdir().unwrap();
    let urdf = arm_path();
    let urdf = urdf.to_str().unwrap();
    for args in [
        vec!["import", urdf, "-o", "arm.toml"],
        vec!["build", urdf, "-o", "from_urdf.fmu"],
        vec!["build", "arm.toml", "-o", "from_toml.fmu"],
        vec!["check", urdf],
        vec!["describe", urdf],
        vec!["simulate", urdf, "--stop", "0.1", "-o", "out.csv"],
    ] {
        let out = triad(&args, tmp.path());
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let a = std::fs::read(tmp.path().join("from_urdf.fmu")).unwrap();
    let b = std::fs::read(tmp.path().join("from_toml.fmu")).unwrap();
    assert!(a == b, "the FMUs differ");
    let toml = std::fs::read_to_string(tmp.path().join("arm.toml")).unwrap();
    assert!(toml.contains("# URDF link \"upper arm\""), "{toml}");
    assert!(
        toml.contains("merged into it by fixed joints: \"tool0\""),
        "{toml}"
    );
    // sites for merged links; original names in the variables' descriptions
    assert!(
        toml.contains("[[site]]\nname = \"tool0\"\nbody = \"forearm\""),
        "{toml}"
    );
    let table = String::from_utf8(triad(&["describe", urdf], tmp.path()).stdout).unwrap();
    let line = |name: &str| {
        table
            .lines()
            .find(|l| l.starts_with(name))
            .unwrap_or_default()
            .to_string()
    };
    assert!(
        line("body.upper_arm.r[1] ").ends_with("(URDF link \"upper arm\")"),
        "{table}"
    );
    assert!(line("site.tool0.R[1,1] ").contains("site tool0"), "{table}");
    let check = String::from_utf8(triad(&["check", urdf], tmp.path()).stdout).unwrap();
    assert!(
        check.contains("note: root link 'base_link' is welded to the world"),
        "{check}"
    );
}

/// The upper arm's inertial: `rpy = (0.3, 0, 0.2)` rotates the written tensor into the link
/// axes, `J = R J_urdf Rᵀ`.
#[test]
fn inertials_are_rotated_into_the_link_frame() {
    let (spec, _) = import(&arm_text(), "arm.urdf", &ImportOptions::default()).unwrap();
    let upper = spec.body.iter().find(|b| b.name == "upper_arm").unwrap();
    let r = rpy_to_matrix(&Vec3::new(0.3, 0.0, 0.2));
    let j = Mat3::new(0.042, 0.001, 0.0, 0.001, 0.041, 0.0, 0.0, 0.0, 0.004);
    let want = r * j * r.transpose();
    let got = upper.inertia.matrix();
    assert!((got - want).amax() <= 1e-17, "{got} vs {want}");
    assert_eq!(upper.com, [0.0, 0.0, -0.25]);
    assert_eq!(upper.mass, 2.0);
}

fn joint_trajectory(opts: &ImportOptions) -> Vec<f64> {
    let (spec, _) = import(&arm_text(), "arm.urdf", opts).unwrap();
    spec.validate("arm.urdf").unwrap();
    let (def, _) = spec.lower().unwrap();
    let model = Model::new(&def, settings(1e-3, 4)).unwrap();
    let mut s = State::new(&model);
    for (k, x) in s.inputs_mut().iter_mut().enumerate() {
        *x = 0.5 - 0.3 * k as f64;
    }
    let names = ["shoulder", "elbow"];
    let mut out = Vec::new();
    for k in 0..1000 {
        step(&model, &mut s, 1e-3).unwrap();
        if k % 100 == 99 {
            let o = s.outputs();
            for n in names {
                let j = def.joints.iter().position(|j| j.name == n).unwrap();
                out.push(o.joints[j].q[0]);
                out.push(o.joints[j].qd[0]);
            }
            // the tool frame: a site when merged, a body when kept
            let tool = match def.sites.iter().position(|s| s.name == "tool0") {
                Some(i) => &o.sites[i],
                None => &o.bodies[def.bodies.iter().position(|b| b.name == "tool0").unwrap()],
            };
            out.extend(tool.r.iter().chain(tool.rot.iter()));
            out.extend(tool.v.iter().chain(tool.w.iter()));
        }
    }
    out
}

/// The merged tool (mass, centre of mass, rotated inertia and parallel-axis term) moves the
/// arm exactly as the tool kept as a body on a fixed joint, and its site (pose and twist)
/// follows the kept body.
#[test]
fn merged_fixed_links_move_like_kept_ones() {
    // without the joints' friction, whose stick–slip transitions would amplify the round-off
    // by which the two (equal) models differ
    let merged = joint_trajectory(&ImportOptions {
        no_friction: true,
        no_mimic: true,
        ..ImportOptions::default()
    });
    let kept = joint_trajectory(&ImportOptions {
        keep_fixed: true,
        no_friction: true,
        no_mimic: true,
        ..ImportOptions::default()
    });
    let d = merged
        .iter()
        .zip(&kept)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    eprintln!("merged vs kept: {d:.2e}");
    assert!(d <= 1e-11, "{d:e}");
}

#[test]
fn the_base_is_welded_or_freed_as_asked() {
    let (welded, _) = import(&arm_text(), "arm.urdf", &ImportOptions::default()).unwrap();
    assert!(welded.body.iter().all(|b| b.position.is_none()));
    assert_eq!(welded.joint[0].parent, "world");
    let opts = ImportOptions {
        base: Base::Floating,
        ..ImportOptions::default()
    };
    let (free, _) = import(&arm_text(), "arm.urdf", &opts).unwrap();
    free.validate("arm.urdf").unwrap();
    let base = free.body.iter().find(|b| b.name == "base_link").unwrap();
    assert_eq!(base.position, Some([0.0; 3]));
    assert_eq!(base.mass, 5.0);
    assert_eq!(free.joint[0].parent, "base_link");
    // a world link with a floating joint: free unless --fixed-base
    let text = arm_text().replace(
        "<link name=\"base_link\">",
        "<link name=\"world\"/>\n  <joint name=\"float\" type=\"floating\"><parent link=\"world\"/><child link=\"base_link\"/><origin xyz=\"0 0 1\"/></joint>\n  <link name=\"base_link\">",
    );
    let (spec, _) = import(&text, "arm.urdf", &ImportOptions::default()).unwrap();
    let base = spec.body.iter().find(|b| b.name == "base_link").unwrap();
    assert_eq!(base.position, Some([0.0, 0.0, 1.0]));
    let fixed = ImportOptions {
        base: Base::Fixed,
        ..ImportOptions::default()
    };
    let (spec, _) = import(&text, "arm.urdf", &fixed).unwrap();
    assert!(spec.body.iter().all(|b| b.name != "base_link"));
    assert_eq!(spec.joint[0].origin.xyz, [0.0, 0.0, 1.1]);
}

/// Malformed URDFs: each message names the file, the line and the element; exit non-zero; no
/// file written; no panic.
#[test]
fn malformed_urdfs_are_reported() {
    let link = |n: &str| {
        format!("<link name=\"{n}\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>")
    };
    let joint = |n: &str, t: &str, p: &str, c: &str| {
        format!("<joint name=\"{n}\" type=\"{t}\"><parent link=\"{p}\"/><child link=\"{c}\"/><axis xyz=\"0 1 0\"/></joint>")
    };
    let robot = |body: String| format!("<robot name=\"r\">\n{body}\n</robot>\n");
    let a = link("a");
    let b = link("b");
    let c = link("c");
    let cases: Vec<(String, String, &str)> = vec![
        ("unclosed".into(), "<robot name=\"r\">\n<link name=\"a\">\n</robot>".into(), "malformed XML"),
        ("not_a_robot".into(), "<model name=\"r\"/>".into(), "line 1: <model>: the root element of a URDF is <robot>"),
        ("no_links".into(), robot(String::new()), "the robot has no <link>"),
        ("missing_child".into(), robot(format!("{a}\n{}", joint("j", "revolute", "a", "forearm"))), "line 3: joint \"j\": child link \"forearm\" does not exist"),
        ("missing_parent".into(), robot(format!("{a}\n{}", joint("j", "revolute", "x", "a"))), "line 3: joint \"j\": parent link \"x\" does not exist"),
        ("two_parents".into(), robot(format!("{a}\n{b}\n{c}\n{}\n{}", joint("j1", "revolute", "a", "c"), joint("j2", "revolute", "b", "c"))), "line 6: joint \"j2\": link \"c\" already has a parent joint (\"j1\", line 5)"),
        ("two_roots".into(), robot(format!("{a}\n{b}")), "the robot has 2 root links (\"a\" (line 2), \"b\" (line 3))"),
        ("cycle".into(), robot(format!("{a}\n{b}\n{}\n{}", joint("j1", "revolute", "a", "b"), joint("j2", "revolute", "b", "a"))), "the joints form a cycle"),
        ("unknown_type".into(), robot(format!("{a}\n{b}\n{}", joint("j", "hinge", "a", "b"))), "line 4: joint \"j\": unknown joint type \"hinge\""),
        ("negative_mass".into(), robot("<link name=\"a\"><inertial><mass value=\"-1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>".into()), "line 2: link \"a\": mass -1 is negative"),
        ("nan_mass".into(), robot("<link name=\"a\"><inertial><mass value=\"nan\"/></inertial></link>".into()), "line 2: link \"a\": <mass> value=\"nan\": numbers must be finite"),
        ("short_xyz".into(), robot(format!("{a}\n{b}\n<joint name=\"j\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><origin xyz=\"0 1\"/></joint>")), "line 4: joint \"j\": <origin> xyz=\"0 1\": expected 3 numbers, found 2"),
        ("zero_axis".into(), robot(format!("{a}\n{b}\n<joint name=\"j\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><axis xyz=\"0 0 0\"/></joint>")), "line 4: joint \"j\": <axis> has zero length"),
        ("bad_number".into(), robot(format!("{a}\n{b}\n<joint name=\"j\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><axis xyz=\"0 one 0\"/></joint>")), "<axis> xyz=\"0 one 0\": not a list of numbers"),
        ("duplicate_link".into(), robot(format!("{a}\n{a}")), "line 3: link \"a\": duplicate link name (also line 2)"),
        ("no_parent_element".into(), robot(format!("{a}\n{b}\n<joint name=\"j\" type=\"fixed\"><child link=\"b\"/></joint>")), "line 4: joint \"j\": has no <parent>"),
        ("bad_inertia".into(), robot(format!("{a}\n<link name=\"b\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"3\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>\n{}", joint("j", "revolute", "a", "b"))), "violates the triangle inequality"),
        ("massless_leaf".into(), robot(format!("{a}\n<link name=\"tip\"/>\n{}", joint("j", "continuous", "a", "tip"))), "body \"tip\" has no mass and it is a leaf"),
        ("floating_inside".into(), robot(format!("{a}\n{b}\n{c}\n{}\n{}", joint("j1", "revolute", "a", "b"), joint("j2", "floating", "b", "c"))), "line 6: joint \"j2\": a floating joint is supported only between the world link and the base"),
    ];
    assert!(cases.len() >= 15);
    let tmp = tempfile::tempdir().unwrap();
    for (name, text, want) in &cases {
        let file = format!("{name}.urdf");
        std::fs::write(tmp.path().join(&file), text).unwrap();
        for cmd in ["import", "check", "build"] {
            let args: &[&str] = if cmd == "check" {
                &[cmd, &file]
            } else {
                &[cmd, &file, "-o", "out.file"]
            };
            let out = triad(args, tmp.path());
            let err = String::from_utf8_lossy(&out.stderr);
            assert!(!out.status.success(), "{name} {cmd}: accepted");
            assert!(
                err.contains(&format!("{file}: ")) && err.contains(want),
                "{name} {cmd}: expected {want:?} in\n{err}"
            );
            assert!(!err.contains("panicked"), "{name} {cmd}: {err}");
            assert!(
                !tmp.path().join("out.file").exists(),
                "{name} {cmd}: wrote a file"
            );
        }
    }
}

/// `<limit lower upper effort>` of revolute and prismatic joints become stops and an effort
/// clamp; continuous joints keep only the effort; placeholders (lower = upper, effort = 0) are
/// left out with a note; `no_limits` leaves everything out.
#[test]
fn limits_become_stops_unless_placeholders_or_turned_off() {
    let (spec, _) = import(&arm_text(), "arm.urdf", &ImportOptions::default()).unwrap();
    let shoulder = &spec.joint[spec.joint_index("shoulder").unwrap()];
    assert_eq!(
        (shoulder.lower, shoulder.upper, shoulder.effort),
        (Some(-2.0), Some(2.0), Some(50.0))
    );
    let off = ImportOptions {
        no_limits: true,
        ..ImportOptions::default()
    };
    let (spec, _) = import(&arm_text(), "arm.urdf", &off).unwrap();
    assert!(spec
        .joint
        .iter()
        .all(|j| j.lower.is_none() && j.effort.is_none()));
    let placeholder = arm_text()
        .replace(
            "<limit lower=\"-2\" upper=\"2\" effort=\"50\" velocity=\"3\"/>",
            "<limit lower=\"0\" upper=\"0\" effort=\"0\" velocity=\"0\"/>",
        )
        .replace(
            "<axis xyz=\"0 2 0\"/>",
            "<axis xyz=\"0 2 0\"/><limit lower=\"-1\" upper=\"1\" effort=\"7\"/>",
        );
    let (spec, outcome) = import(&placeholder, "arm.urdf", &ImportOptions::default()).unwrap();
    let shoulder = &spec.joint[spec.joint_index("shoulder").unwrap()];
    assert_eq!((shoulder.lower, shoulder.effort), (None, None));
    let elbow = &spec.joint[spec.joint_index("elbow").unwrap()];
    assert_eq!(
        (elbow.lower, elbow.upper, elbow.effort),
        (None, None, Some(7.0))
    );
    let notes = outcome.notes.join("\n");
    assert!(
        notes.contains("joint 'shoulder': <limit lower=\"0\" upper=\"0\"> is a placeholder"),
        "{notes}"
    );
    assert!(
        notes.contains("joint 'shoulder': <limit effort=\"0\"> is a placeholder"),
        "{notes}"
    );
}

/// `<visual>` shapes (a link without one: its `<collision>`) are kept for the viewer on their
/// host body, merged links' shapes moved into the host frame; a missing mesh file is not
/// looked for.
#[test]
fn shapes_are_kept_on_their_host_bodies() {
    let (spec, _) = import(&arm_text(), "arm.urdf", &ImportOptions::default()).unwrap();
    spec.validate("arm.urdf").unwrap();
    let on = |b: &str| spec.visual.iter().find(|v| v.body == b).unwrap();
    assert_eq!(on("upper_arm").cuboid, Some([0.05, 0.05, 0.5]));
    assert_eq!(on("upper_arm").rgba, Some([0.1, 0.2, 0.8, 1.0]));
    assert_eq!(on("forearm").cylinder, Some([0.03, 0.4]));
    // the tool's mesh sits on the forearm at the tool frame (the fixed joint's origin)
    let mesh = spec.visual.iter().find(|v| v.mesh.is_some()).unwrap();
    assert_eq!(mesh.body, "forearm");
    assert_eq!(mesh.scale, Some([0.001; 3]));
    assert!((Vec3::from(mesh.origin.xyz) - Vec3::new(0.0, 0.0, -0.4)).norm() < 1e-15);
    let r = rpy_to_matrix(&Vec3::from(mesh.origin.rpy));
    assert!((r - rpy_to_matrix(&Vec3::new(0.1, -0.2, 0.3))).amax() < 1e-15);
    assert_eq!(spec.visual.len(), 3);
}
