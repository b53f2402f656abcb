//! `triad animate` on bad input: a CSV without pose columns, a CSV of another model (other
//! bodies, or the same bodies in another geometry), an unreadable or malformed file each give one
//! clear message and a non-zero exit, write nothing, and never panic; a missing or unreadable
//! mesh is a warning, and the body is drawn with its default shape. The default output is
//! RESULT with `.html`; `simulate --animate` writes the page with or without `-o`.

mod common;
use common::triad;

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Runs triad; returns (success, stderr) after checking that nothing panicked.
fn run(args: &[&str], cwd: &Path) -> (bool, String) {
    let out = triad(args, cwd);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!err.contains("panicked"), "{err}");
    (out.status.success(), err)
}

/// A result CSV of the double pendulum (1 s at 0.05 s) in `dir`.
fn pendulum_csv(dir: &Path) -> PathBuf {
    let csv = dir.join("dp.csv");
    let (ok, err) = run(
        &[
            "simulate",
            "double_pendulum",
            "--stop",
            "1",
            "--step",
            "0.05",
            "-o",
            csv.to_str().unwrap(),
        ],
        dir,
    );
    assert!(ok, "{err}");
    csv
}

/// Asserts failure with `needle` in the message and no page written.
fn refused(args: &[&str], dir: &Path, needle: &str) {
    let (ok, err) = run(args, dir);
    assert!(!ok, "should fail: {args:?}");
    assert!(err.contains(needle), "{needle:?} not in: {err}");
    // one message (a model's problems add their count, as every command prints them)
    assert!(
        err.lines().count() == 1 || err.ends_with("1 problem\n"),
        "one message: {err}"
    );
    let pages: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(Result::ok)
        .filter(|e| e.path().extension().is_some_and(|x| x == "html"))
        .collect();
    assert!(pages.is_empty(), "nothing written: {pages:?}");
}

#[test]
fn csv_without_poses_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("q.csv");
    std::fs::write(
        &csv,
        "time,joint.shoulder.q,joint.elbow.q\n0,0.1,0.2\n0.1,0.2,0.3\n",
    )
    .unwrap();
    refused(
        &["animate", "double_pendulum", "q.csv", "-o", "out.html"],
        dir.path(),
        "q.csv: no pose columns (body.<B>.r[1..3] and body.<B>.R[1..3,1..3])",
    );
}

#[test]
fn csv_of_another_model_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let csv = pendulum_csv(dir.path());
    let csv = csv.to_str().unwrap();
    // other bodies
    refused(
        &["animate", "pendulum", csv],
        dir.path(),
        "not a result of model",
    );
    // the same bodies, another geometry: the elbow moved by 0.3 m
    let spec =
        std::fs::read_to_string(root().join("modelDescription/double_pendulum/spec.toml")).unwrap();
    let moved = spec.replacen("xyz = [0.0, 0.0, -1.0]", "xyz = [0.0, 0.0, -1.3]", 1);
    assert_ne!(moved, spec, "the test moves the elbow");
    std::fs::write(dir.path().join("moved.toml"), moved).unwrap();
    refused(
        &["animate", "moved.toml", csv],
        dir.path(),
        "at t = 0, joint elbow of the model joins link1 and link2 at points 3.000e-1 m apart",
    );
    // a rotation entry missing
    let mut reader = csv::Reader::from_path(csv).unwrap();
    let header = reader.headers().unwrap().clone();
    let drop = header
        .iter()
        .position(|h| h == "body.link2.R[3,3]")
        .unwrap();
    let mut writer = csv::Writer::from_path(dir.path().join("cut.csv")).unwrap();
    let keep = |r: &csv::StringRecord| -> Vec<String> {
        r.iter()
            .enumerate()
            .filter(|(k, _)| *k != drop)
            .map(|(_, c)| c.to_string())
            .collect()
    };
    writer.write_record(keep(&header)).unwrap();
    for r in reader.records() {
        writer.write_record(keep(&r.unwrap())).unwrap();
    }
    writer.flush().unwrap();
    refused(
        &["animate", "double_pendulum", "cut.csv"],
        dir.path(),
        "cut.csv: no column body.link2.R[3,3]",
    );
}

#[test]
fn unreadable_and_malformed_files_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    refused(
        &["animate", "double_pendulum", "missing.csv"],
        d,
        "missing.csv: cannot read the file",
    );
    std::fs::create_dir(d.join("folder.csv")).unwrap();
    refused(
        &["animate", "double_pendulum", "folder.csv", "-o", "x.html"],
        d,
        "folder.csv",
    );
    std::fs::write(d.join("bin.csv"), [0xffu8, 0xfe, 0x00, 0x01, 0x9c]).unwrap();
    refused(&["animate", "double_pendulum", "bin.csv"], d, "bin.csv:");
    std::fs::write(d.join("empty.csv"), "").unwrap();
    refused(
        &["animate", "double_pendulum", "empty.csv"],
        d,
        "no `time` column",
    );
    let csv = pendulum_csv(d);
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let mut cells: Vec<&str> = lines[3].split(',').collect();
    cells[2] = "oops";
    lines[3] = cells.join(",");
    std::fs::write(d.join("bad.csv"), lines.join("\n")).unwrap();
    std::fs::remove_file(&csv).unwrap();
    refused(
        &["animate", "double_pendulum", "bad.csv"],
        d,
        "bad.csv: line 4, column",
    );
    refused(
        &["animate", "nothing_here.toml", "bad.csv"],
        d,
        "nothing_here.toml",
    );
    refused(
        &["animate", "double_pendulum", "bad.csv", "--fps", "0"],
        d,
        "--fps must be a positive number",
    );
}

/// Copies the mesh arm without `missing` (a mesh file), or with it replaced by garbage.
fn mesh_arm_copy(dir: &Path, missing: &str, garbage: bool) -> PathBuf {
    let src = root().join("tests/data/urdf/mesh_arm");
    let dst = dir.join("mesh_arm");
    std::fs::create_dir_all(dst.join("meshes")).unwrap();
    std::fs::copy(src.join("mesh_arm.urdf"), dst.join("mesh_arm.urdf")).unwrap();
    for e in std::fs::read_dir(src.join("meshes")).unwrap() {
        let e = e.unwrap();
        let name = e.file_name();
        if name == missing {
            if garbage {
                std::fs::write(
                    dst.join("meshes").join(&name),
                    "solid broken\n  facet oops\n",
                )
                .unwrap();
            }
            continue;
        }
        std::fs::copy(e.path(), dst.join("meshes").join(name)).unwrap();
    }
    dst.join("mesh_arm.urdf")
}

/// The shapes of body `name` in a page: (kind, default) pairs.
fn shapes(html: &str, name: &str) -> Vec<(String, bool)> {
    let v: serde_json::Value =
        serde_json::from_str(triad::viewer::payload_of(html).unwrap()).unwrap();
    let body = v["bodies"]
        .as_array()
        .unwrap()
        .iter()
        .find(|b| b["name"] == name)
        .unwrap();
    body["shapes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            (
                s["kind"].as_str().unwrap().to_string(),
                s["default"].as_bool().unwrap(),
            )
        })
        .collect()
}

#[test]
fn a_missing_or_unreadable_mesh_falls_back_to_the_default_shape() {
    for garbage in [false, true] {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        let urdf = mesh_arm_copy(d, "upper.obj", garbage);
        let urdf = urdf.to_str().unwrap();
        let (ok, err) = run(&["simulate", urdf, "--stop", "0.5", "-o", "arm.csv"], d);
        assert!(ok, "{err}");
        let (ok, err) = run(&["animate", urdf, "arm.csv"], d);
        assert!(ok, "{err}");
        let warning = err
            .lines()
            .find(|l| l.starts_with("warning:"))
            .unwrap_or_else(|| panic!("{err}"));
        assert!(
            warning.contains("visual[1] of body upper: mesh package://mesh_arm/meshes/upper.obj")
                && warning.contains("its default shape is drawn instead"),
            "{warning}"
        );
        if !garbage {
            assert!(warning.contains("not found (tried"), "{warning}");
        }
        // the default output name, and the body drawn by its defaults beside its other shapes
        let html = std::fs::read_to_string(d.join("arm.html")).unwrap();
        let upper = shapes(&html, "upper");
        assert!(upper.contains(&("cylinder".into(), false)), "{upper:?}");
        assert!(upper.contains(&("box".into(), true)), "{upper:?}");
        assert!(upper.contains(&("capsule".into(), true)), "{upper:?}");
        let fore = shapes(&html, "fore");
        assert_eq!(
            fore,
            [("mesh".to_string(), false), ("mesh".to_string(), false)]
        );
    }
}

#[test]
fn every_mesh_of_the_test_arm_is_read() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let urdf = root().join("tests/data/urdf/mesh_arm/mesh_arm.urdf");
    let urdf = urdf.to_str().unwrap();
    let (ok, err) = run(
        &[
            "simulate",
            urdf,
            "--stop",
            "0.2",
            "-o",
            "arm.csv",
            "--animate",
            "arm.html",
        ],
        d,
    );
    assert!(ok, "{err}");
    assert!(!err.contains("warning"), "{err}");
    let html = std::fs::read_to_string(d.join("arm.html")).unwrap();
    let v: serde_json::Value =
        serde_json::from_str(triad::viewer::payload_of(&html).unwrap()).unwrap();
    assert_eq!(
        v["meshes"].as_array().unwrap().len(),
        4,
        "base.stl, upper.obj, fore.stl, tool.dae"
    );
    assert_eq!(v["world"][0]["kind"], "mesh");
    assert_eq!(v["sites"][0]["name"], "tool");
    // the meshes as read: the OBJ's MTL colour, the DAE's unit and colour, the STL's extent
    let upper = triad::viewer::load_mesh(&root().join("tests/data/urdf/mesh_arm/meshes/upper.obj"))
        .unwrap();
    assert_eq!(upper.parts[0].rgba, Some([0.2, 0.4, 0.9, 1.0]));
    assert_eq!(upper.triangles(), 12);
    let tool =
        triad::viewer::load_mesh(&root().join("tests/data/urdf/mesh_arm/meshes/tool.dae")).unwrap();
    assert_eq!(tool.triangles(), 12);
    assert!(tool.parts[0]
        .positions
        .iter()
        .all(|p| p[0].abs() <= 0.05 + 1e-6));
    assert_eq!(tool.parts[0].rgba, Some([0.2, 0.7, 0.3, 1.0]));
    let fore =
        triad::viewer::load_mesh(&root().join("tests/data/urdf/mesh_arm/meshes/fore.stl")).unwrap();
    assert_eq!(
        (fore.parts[0].positions.len(), fore.triangles()),
        (8, 12),
        "repeated vertices merged"
    );
}

#[test]
fn simulate_animate_writes_the_page_with_or_without_a_csv_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (ok, err) = run(
        &[
            "simulate",
            "double_pendulum",
            "--stop",
            "0.3",
            "--animate",
            "dp.html",
        ],
        d,
    );
    assert!(ok, "{err}");
    let poses = triad::viewer::decode(
        triad::viewer::payload_of(&std::fs::read_to_string(d.join("dp.html")).unwrap()).unwrap(),
    )
    .unwrap();
    assert_eq!(poses.time.len(), 31);
    assert_eq!(poses.bodies.len(), 2);
}

/// `--outputs` chooses the CSV's columns only: the replay still has every pose.
#[test]
fn simulate_animate_replays_every_body_whatever_outputs_writes() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let (ok, err) = run(
        &[
            "simulate",
            "double_pendulum",
            "--stop",
            "0.2",
            "--outputs",
            "joint.*.q",
            "-o",
            "q.csv",
            "--animate",
            "dp.html",
        ],
        d,
    );
    assert!(ok, "{err}");
    let csv = std::fs::read_to_string(d.join("q.csv")).unwrap();
    assert_eq!(
        csv.lines().next().unwrap(),
        "time,joint.shoulder.q,joint.elbow.q"
    );
    let html = std::fs::read_to_string(d.join("dp.html")).unwrap();
    assert!(html.contains("link2"), "the page names the bodies");
}

#[test]
fn the_ground_is_drawn_where_the_run_had_it() {
    // ground.height is a parameter: a run that sets it puts the ground where its gaps say
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let ball = root().join("examples/specs/bouncing_ball.toml");
    let ball = ball.to_str().unwrap();
    let ground_of = |page: &str| -> serde_json::Value {
        let html = std::fs::read_to_string(d.join(page)).unwrap();
        let v: serde_json::Value =
            serde_json::from_str(triad::viewer::payload_of(&html).unwrap()).unwrap();
        v["ground"].clone()
    };
    let (ok, err) = run(&["simulate", ball, "--stop", "0.5", "-o", "a.csv"], d);
    assert!(ok, "{err}");
    let (ok, err) = run(&["animate", ball, "a.csv", "-o", "a.html"], d);
    assert!(ok && !err.contains("warning"), "{err}");
    assert_eq!(ground_of("a.html")["height"], 0.0);
    let (ok, err) = run(
        &[
            "simulate",
            ball,
            "--stop",
            "0.5",
            "--set",
            "ground.height=0.25",
            "-o",
            "b.csv",
            "--animate",
            "b.html",
        ],
        d,
    );
    assert!(ok, "{err}");
    assert!(
        err.contains("warning: the ground is drawn at height 0.25 m, where the result's contact gaps put it (the spec says 0 m"),
        "{err}"
    );
    let h = ground_of("b.html")["height"].as_f64().unwrap();
    assert!((h - 0.25).abs() < 1e-12, "{h}");
    assert_eq!(
        ground_of("b.html")["normal"],
        serde_json::json!([0.0, 0.0, 1.0])
    );
}
