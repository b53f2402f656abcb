//! `triad describe` lists exactly the variables of interface.md §3 for every shipped model, in
//! the order inputs, outputs, parameters, with value references 0, 1, 2, ... (unique). The
//! expected names are derived here from the spec with the rules of §3, independently of the
//! variable table's code.

use std::process::Command;

use triad::spec::{bundled, Format, JointKind, Spec};

fn idx(base: &str, n: usize) -> Vec<String> {
    (1..=n).map(|k| format!("{base}[{k}]")).collect()
}

fn coords(kind: JointKind) -> usize {
    match kind {
        JointKind::Revolute | JointKind::Prismatic => 1,
        JointKind::Cylindrical | JointKind::Universal => 2,
        JointKind::Planar => 3,
        JointKind::Spherical | JointKind::Fixed => 0,
    }
}

/// (name, causality) in the order of interface.md §3.
fn expected(spec: &Spec) -> Vec<(String, &'static str)> {
    let mut joints: Vec<_> = spec.joint.iter().filter(|j| !j.is_loop_closing()).collect();
    joints.extend(spec.joint.iter().filter(|j| j.is_loop_closing()));
    let mut out = Vec::new();
    let mut add =
        |names: Vec<String>, c: &'static str| out.extend(names.into_iter().map(|n| (n, c)));
    for j in joints.iter().filter(|j| j.actuated) {
        let p = format!("joint.{}", j.name);
        match j.kind {
            JointKind::Revolute => add(vec![format!("{p}.tau")], "input"),
            JointKind::Prismatic => add(vec![format!("{p}.f")], "input"),
            JointKind::Cylindrical => add(vec![format!("{p}.f"), format!("{p}.tau")], "input"),
            JointKind::Universal => add(idx(&format!("{p}.tau"), 2), "input"),
            JointKind::Spherical => add(idx(&format!("{p}.tau"), 3), "input"),
            _ => {}
        }
    }
    for l in &spec.load {
        if l.torque {
            add(idx(&format!("body.{}.torque", l.body), 3), "input");
        }
        if l.force {
            add(idx(&format!("body.{}.force", l.body), 3), "input");
        }
    }
    for b in &spec.body {
        let p = format!("body.{}", b.name);
        add(idx(&format!("{p}.r"), 3), "output");
        add(
            (1..=3)
                .flat_map(|i| (1..=3).map(move |j| format!("body.{}.R[{i},{j}]", b.name)))
                .collect(),
            "output",
        );
        add(idx(&format!("{p}.v"), 3), "output");
        add(idx(&format!("{p}.w"), 3), "output");
    }
    for j in &joints {
        let p = format!("joint.{}", j.name);
        let n = coords(j.kind);
        if j.kind == JointKind::Spherical {
            add(idx(&format!("{p}.quat"), 4), "output");
            add(idx(&format!("{p}.w"), 3), "output");
        } else if n == 1 {
            add(vec![format!("{p}.q"), format!("{p}.qd")], "output");
        } else {
            add(idx(&format!("{p}.q"), n), "output");
            add(idx(&format!("{p}.qd"), n), "output");
        }
    }
    add(vec!["system.energy".into(), "system.work".into()], "output");
    add(idx("system.p", 3), "output");
    add(idx("system.L", 3), "output");
    add(vec!["system.constraint_residual".into()], "output");
    add(idx("gravity", 3), "parameter");
    for b in &spec.body {
        add(vec![format!("body.{}.mass", b.name)], "parameter");
        add(
            (1..=3)
                .flat_map(|i| (1..=3).map(move |j| format!("body.{}.inertia[{i},{j}]", b.name)))
                .collect(),
            "parameter",
        );
    }
    for j in &joints {
        let p = format!("joint.{}", j.name);
        if j.kind == JointKind::Fixed {
            continue;
        }
        if !j.is_loop_closing() {
            if j.kind == JointKind::Spherical {
                add(idx(&format!("{p}.q0"), 4), "parameter");
                add(idx(&format!("{p}.qd0"), 3), "parameter");
            } else if coords(j.kind) == 1 {
                add(vec![format!("{p}.q0"), format!("{p}.qd0")], "parameter");
            } else {
                add(idx(&format!("{p}.q0"), coords(j.kind)), "parameter");
                add(idx(&format!("{p}.qd0"), coords(j.kind)), "parameter");
            }
        }
        add(vec![format!("{p}.damping")], "parameter");
        if j.kind != JointKind::Spherical {
            add(vec![format!("{p}.stiffness")], "parameter");
        }
    }
    add(
        vec![
            "solver.max_step".into(),
            "solver.tolerance".into(),
            "solver.order".into(),
            "solver.max_substeps".into(),
            "solver.stages".into(),
            "solver.rtol".into(),
            "solver.atol".into(),
            "solver.min_step".into(),
        ],
        "parameter",
    );
    // the accelerations of a model without contact (none of the shipped has joint friction),
    // last: every tree joint's (closed loops: not the loop-closing joint's)
    if spec.collision.is_empty() {
        for j in joints.iter().filter(|j| !j.is_loop_closing()) {
            let p = format!("joint.{}", j.name);
            match (j.kind, coords(j.kind)) {
                (JointKind::Spherical | JointKind::Fixed, _) => {}
                (_, 1) => add(vec![format!("{p}.qdd")], "output"),
                (_, n) => add(idx(&format!("{p}.qdd"), n), "output"),
            }
        }
    }
    out
}

#[test]
fn describe_lists_exactly_the_interface_variables() {
    for (name, text) in bundled() {
        let spec = Spec::from_str(text, Format::Toml, name).unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_triad"))
            .args(["describe", name])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let stdout = String::from_utf8(out.stdout).unwrap();
        let mut lines = stdout.lines();
        let header: Vec<&str> = lines.next().unwrap().split_whitespace().collect();
        assert_eq!(
            header[..6],
            ["name", "vr", "causality", "variability", "type", "unit"]
        );
        let rows: Vec<Vec<&str>> = lines.map(|l| l.split_whitespace().collect()).collect();
        let got: Vec<(String, &str)> = rows.iter().map(|r| (r[0].to_string(), r[2])).collect();
        let want = expected(&spec);
        let got_c: Vec<(String, &str)> = got.iter().map(|(n, c)| (n.clone(), *c)).collect();
        assert_eq!(got_c, want, "{name}");
        for (k, r) in rows.iter().enumerate() {
            assert_eq!(
                r[1],
                k.to_string(),
                "{name}: value references must be 0, 1, 2, ..."
            );
        }
    }
}

#[test]
fn describe_columns_are_aligned() {
    let out = Command::new(env!("CARGO_BIN_EXE_triad"))
        .args(["describe", "double_pendulum"])
        .output()
        .unwrap();
    let stdout = String::from_utf8(out.stdout).unwrap();
    // start of the third column (causality)
    let col = |l: &str| {
        let tok = l.split_whitespace().nth(2)?;
        let after_vr = l.find(l.split_whitespace().nth(1)?)?;
        l[after_vr..].find(tok).map(|p| p + after_vr)
    };
    let cols: std::collections::BTreeSet<_> = stdout.lines().filter_map(col).collect();
    assert_eq!(cols.len(), 1, "{stdout}");
}

/// One body per joint type, every actuator kind, and a body load.
const ZOO: &str = r#"
name = "Zoo"
[[body]]
name = "a"
mass = 1.0
inertia = [1.0, 1.0, 1.0]
[[body]]
name = "b"
mass = 1.0
inertia = [1.0, 1.0, 1.0]
[[body]]
name = "c"
mass = 1.0
inertia = [1.0, 1.0, 1.0]
[[body]]
name = "d"
mass = 1.0
inertia = [1.0, 1.0, 1.0]
[[body]]
name = "e"
mass = 1.0
inertia = [1.0, 1.0, 1.0]
[[body]]
name = "f"
mass = 1.0
inertia = [1.0, 1.0, 1.0]
[[body]]
name = "g"
mass = 1.0
inertia = [1.0, 1.0, 1.0]
[[joint]]
name = "rev"
type = "revolute"
parent = "world"
child = "a"
axis = [0.0, 0.0, 2.0]
actuated = true
[[joint]]
name = "pri"
type = "prismatic"
parent = "world"
child = "b"
axis = [1.0, 0.0, 0.0]
actuated = true
initial = { q = 0.5, qd = -1.0 }
[[joint]]
name = "cyl"
type = "cylindrical"
parent = "world"
child = "c"
axis = [0.0, 1.0, 0.0]
actuated = true
initial = { q = [0.1, 0.2], qd = [0.0, 1.0] }
[[joint]]
name = "uni"
type = "universal"
parent = "world"
child = "d"
axis = [1.0, 0.0, 0.0]
axis2 = [0.0, 1.0, 0.0]
actuated = true
[[joint]]
name = "sph"
type = "spherical"
parent = "world"
child = "e"
actuated = true
damping = 0.1
initial = { rpy = [0.1, 0.2, 0.3], w = [1.0, 0.0, 0.0] }
[[joint]]
name = "pla"
type = "planar"
parent = "world"
child = "f"
axis = [0.0, 0.0, 1.0]
initial = { q = [1.0, 2.0, 0.5] }
[[joint]]
name = "fix"
type = "fixed"
parent = "world"
child = "g"
origin = { xyz = [0.0, 0.0, 1.0], rpy = [0.0, 0.5, 0.0] }
[[load]]
body = "g"
torque = true
force = true
"#;

#[test]
fn describe_covers_every_joint_type() {
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("zoo.toml");
    std::fs::write(&path, ZOO).unwrap();
    let spec = Spec::from_str(ZOO, Format::Toml, "zoo.toml").unwrap_or_else(|e| panic!("{e}"));
    let out = Command::new(env!("CARGO_BIN_EXE_triad"))
        .args(["describe", path.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    let got: Vec<(String, String)> = stdout
        .lines()
        .skip(1)
        .map(|l| {
            let cols: Vec<&str> = l.split_whitespace().collect();
            (cols[0].to_string(), cols[2].to_string())
        })
        .collect();
    let want: Vec<(String, String)> = expected(&spec)
        .into_iter()
        .map(|(n, c)| (n, c.to_string()))
        .collect();
    assert_eq!(got, want);
    let units: std::collections::HashMap<&str, &str> = stdout
        .lines()
        .skip(1)
        .map(|l| {
            let cols: Vec<&str> = l.split_whitespace().collect();
            (cols[0], cols[5])
        })
        .collect();
    assert_eq!(units["joint.cyl.q[1]"], "m");
    assert_eq!(units["joint.cyl.q[2]"], "rad");
    assert_eq!(units["joint.pla.qd[3]"], "rad/s");
    assert_eq!(units["joint.pla.qd[1]"], "m/s");
    assert_eq!(units["joint.sph.quat[1]"], "1");
    assert_eq!(units["body.g.force[3]"], "N");
}
