//! `check` reports every problem of a file in one run (issue 35 item 6): when a stage finds
//! problems, the later stages still run on what can be salvaged (a link's missing `<inertia>`,
//! a body's unusable mass or inertia: a placeholder), leaving out what follows from the first
//! problem; a stage that cannot run is named in a note (`further checks skipped: …`). And the
//! message for a massless free root says how to fix a free body (weld it, or for an imported
//! robot drop `--floating-base`), not "make that joint fixed".

mod common;
use common::triad;
use std::path::{Path, PathBuf};

fn urdf(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/urdf")
        .join(name)
}

/// Runs triad in `dir`: (success, stdout, stderr), after checking nothing panicked.
fn run(args: &[&str], dir: &Path) -> (bool, String, String) {
    let out = triad(args, dir);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        err,
    )
}

const MOUNT: &str = "link \"finger_mount\" (body[1]): body \"finger_mount\" has no mass and it is a leaf whose joint lets it move in a way that moves no body with mass";

#[test]
fn a_urdf_with_problems_in_two_stages_gets_both_in_one_run() {
    let tmp = tempfile::tempdir().unwrap();
    let gripper = urdf("gripper.urdf");
    let (ok, _, err) = run(&["check", gripper.to_str().unwrap()], tmp.path());
    assert!(!ok);
    assert!(
        err.contains("line 21: link \"palm\": <inertial> has a mass but no <inertia>"),
        "{err}"
    );
    assert!(err.contains(&format!("line 33: {MOUNT}")), "{err}");
    assert!(err.contains("has 2 problems"), "{err}");
    // the palm's placeholder inertia adds nothing of its own
    assert!(!err.contains("body \"palm\""), "{err}");
    // with the inertia given, the second problem is still there, alone and the same
    let text = std::fs::read_to_string(&gripper).unwrap().replace(
        "      <mass value=\"0.5\"/>\n",
        "      <mass value=\"0.5\"/>\n      <inertia ixx=\"1e-3\" iyy=\"1e-3\" izz=\"1e-3\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/>\n",
    );
    std::fs::write(tmp.path().join("fixed.urdf"), text).unwrap();
    let (ok, _, err) = run(&["check", "fixed.urdf"], tmp.path());
    assert!(
        !ok && err.contains(MOUNT) && err.contains("has 1 problem"),
        "{err}"
    );
}

#[test]
fn a_spec_with_problems_in_two_stages_gets_both_in_one_run() {
    let tmp = tempfile::tempdir().unwrap();
    let spec = "name = \"Two\"\n\
        [[body]]\nname = \"palm\"\nmass = -0.5\ninertia = [0.001, 0.001, 0.5]\n\
        [[body]]\nname = \"mount\"\nmass = 0.0\ninertia = [0.0, 0.0, 0.0]\n\
        [[joint]]\nname = \"wrist\"\ntype = \"revolute\"\nparent = \"world\"\nchild = \"palm\"\naxis = [0.0, 0.0, 1.0]\n\
        [[joint]]\nname = \"slide\"\ntype = \"prismatic\"\nparent = \"palm\"\nchild = \"mount\"\naxis = [0.0, 1.0, 0.0]\n";
    std::fs::write(tmp.path().join("two.toml"), spec).unwrap();
    let (ok, _, err) = run(&["check", "two.toml"], tmp.path());
    assert!(!ok);
    for want in [
        "two.toml: body[0].mass: must be >= 0 (got -0.5)",
        "two.toml: body[0].inertia: violates the triangle inequality",
        "two.toml: body[1]: body \"mount\" has no mass and it is a leaf",
        "has 3 problems",
    ] {
        assert!(err.contains(want), "{want}\n{err}");
    }
    // a joint's zero axis: the later checks run with the axis z in its place
    let zero = spec
        .replace("axis = [0.0, 0.0, 1.0]", "axis = [0.0, 0.0, 0.0]")
        .replace("mass = -0.5", "mass = 0.5")
        .replace("[0.001, 0.001, 0.5]", "[0.001, 0.001, 0.001]");
    std::fs::write(tmp.path().join("zero.toml"), zero).unwrap();
    let (_, _, err) = run(&["check", "zero.toml"], tmp.path());
    assert!(
        err.contains("zero.toml: joint[0].axis: zero length"),
        "{err}"
    );
    assert!(
        err.contains("body \"mount\" has no mass") && err.contains("has 2 problems"),
        "{err}"
    );
}

#[test]
fn a_stage_that_cannot_run_is_named_in_a_note() {
    let tmp = tempfile::tempdir().unwrap();
    // a joint that cannot be read: the tree is not known
    let text = std::fs::read_to_string(urdf("gripper.urdf"))
        .unwrap()
        .replace("type=\"prismatic\"", "type=\"slider\"");
    std::fs::write(tmp.path().join("g.urdf"), text).unwrap();
    let (ok, _, err) = run(&["check", "g.urdf"], tmp.path());
    assert!(!ok);
    assert!(
        err.contains("<inertial> has a mass but no <inertia>"),
        "{err}"
    );
    assert!(err.contains("unknown joint type \"slider\""), "{err}");
    assert!(
        err.contains(
            "note: further checks skipped: an element could not be read (line 26: <joint>)"
        ),
        "{err}"
    );
    // a spec that cannot be read whole
    let spec = "name = \"M\"\n[[body]]\nname = \"a\"\nmass = 1.0\ninertia = [1.0, 1.0, 1.0]\n\
        [[joint]]\nname = \"j\"\ntype = \"hinge\"\nparent = \"world\"\nchild = \"a\"\n";
    std::fs::write(tmp.path().join("m.toml"), spec).unwrap();
    let (_, _, err) = run(&["check", "m.toml"], tmp.path());
    assert!(err.contains("unknown joint type \"hinge\""), "{err}");
    assert!(err.contains("note: further checks skipped:"), "{err}");
}

#[test]
fn a_massless_free_root_is_told_how_to_fix_a_free_body() {
    let tmp = tempfile::tempdir().unwrap();
    let root = urdf("free_root.urdf");
    let root = root.to_str().unwrap();
    let (ok, _, err) = run(&["check", root], tmp.path());
    assert!(ok, "welded, the massless root is fine: {err}");
    let (ok, _, err) = run(&["check", root, "--floating-base"], tmp.path());
    assert!(!ok);
    assert!(
        err.contains("body \"base\" has no mass and it is a free body (the root of its tree)"),
        "{err}"
    );
    assert!(
        err.contains("give it mass and inertia, or weld it to the world (drop --floating-base)"),
        "{err}"
    );
    assert!(!err.contains("make that joint fixed"), "{err}");
    // in a spec: weld it with a fixed joint; a lone free body names no joints
    let spec = "name = \"F\"\n\
        [[body]]\nname = \"base\"\nmass = 0.0\ninertia = [0.0, 0.0, 0.0]\nposition = [0.0, 0.0, 1.0]\n\
        [[body]]\nname = \"arm\"\nmass = 1.0\ncom = [0.2, 0.0, 0.0]\ninertia = [0.01, 0.01, 0.01]\n\
        [[body]]\nname = \"loose\"\nmass = 0.0\ninertia = [0.0, 0.0, 0.0]\nposition = [1.0, 0.0, 1.0]\n\
        [[joint]]\nname = \"hinge\"\ntype = \"revolute\"\nparent = \"base\"\nchild = \"arm\"\naxis = [0.0, 0.0, 1.0]\n";
    std::fs::write(tmp.path().join("f.toml"), spec).unwrap();
    let (ok, _, err) = run(&["check", "f.toml"], tmp.path());
    assert!(!ok);
    assert!(
        err.contains("or weld it to the world (a fixed joint)")
            || err.contains("weld it to the world or to a body with mass (a fixed joint)"),
        "{err}"
    );
    assert!(
        !err.contains("make that joint fixed") && !err.contains("on joints )"),
        "{err}"
    );
}
