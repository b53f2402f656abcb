//! `triad linearize`: an analytic reference (the pendulum), the operating point from a result,
//! the file formats and the errors.

mod common;

use common::triad;

fn json(args: &[&str]) -> serde_json::Value {
    let dir = tempfile::tempdir().unwrap();
    let out = triad(args, dir.path());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

fn at(v: &serde_json::Value, key: &str, r: usize, c: usize) -> f64 {
    v[key][r][c].as_f64().unwrap()
}

/// The rod of `pendulum` (m = 1 kg, COM 0.5 m below the hinge, I_c = 0.0833583 kg·m²):
/// `q̈ = (τ − m g l sin q)/I`, so `A = [0 1; −m g l cos q / I 0]`, `B = [0; 1/I]`.
#[test]
fn the_pendulum_matches_its_analytic_linear_model() {
    let (m, g, l) = (1.0, 9.81, 0.5);
    let i = 0.083_358_333_333_333_33 + m * l * l;
    for q in [1.0_f64, 0.0, -2.5] {
        let set = format!("joint.hinge.q0={q}");
        let v = json(&["linearize", "pendulum", "--set", &set, "-o", "-"]);
        let want = -m * g * l * q.cos() / i;
        assert!((at(&v, "A", 1, 0) - want).abs() <= 1e-13, "{v}");
        assert_eq!(at(&v, "A", 0, 1), 1.0);
        assert!((at(&v, "B", 1, 0) - 1.0 / i).abs() <= 1e-13);
        let xdot = v["xdot0"][1].as_f64().unwrap();
        assert!((xdot + m * g * l * q.sin() / i).abs() <= 1e-13);
        assert_eq!(v["x_names"][0], "joint.hinge.q");
        assert_eq!(v["u_names"][0], "joint.hinge.tau");
    }
}

/// The operating point read from a result's row is the state of that row.
#[test]
fn a_result_row_is_the_operating_point() {
    let dir = tempfile::tempdir().unwrap();
    let out = triad(
        &["simulate", "heavy_top", "--stop", "0.5", "-o", "r.csv"],
        dir.path(),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = dir.path().join("r.csv").display().to_string();
    let v = json(&[
        "linearize",
        "heavy_top",
        "--at",
        &csv,
        "--time",
        "0.5",
        "-o",
        "-",
    ]);
    assert_eq!(v["t0"].as_f64(), Some(0.5));
    // the rates of the row, and quat outputs y0 equal to the row's quaternion
    let (header, rows) = common::read_csv(&dir.path().join("r.csv"));
    let row = rows.iter().find(|r| (r[0] - 0.5).abs() < 1e-12).unwrap();
    let col = |n: &str| row[header.iter().position(|h| h == n).unwrap()];
    for k in 1..=3 {
        let x = v["x0"][2 + k].as_f64().unwrap();
        assert_eq!(x, col(&format!("joint.tip.w[{k}]")));
    }
    let names: Vec<&str> = v["y_names"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s.as_str().unwrap())
        .collect();
    let k = names
        .iter()
        .position(|n| *n == "joint.tip.quat[2]")
        .unwrap();
    let y = v["y0"][k].as_f64().unwrap();
    assert!((y - col("joint.tip.quat[2]")).abs() < 1e-12, "{y}");
    let bad = triad(
        &["linearize", "heavy_top", "--at", &csv, "--time", "0.123"],
        dir.path(),
    );
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("no row at time 0.123"));
}

#[test]
fn the_three_formats_are_written() {
    let dir = tempfile::tempdir().unwrap();
    for ext in ["json", "npz", "mat"] {
        let name = format!("ra.{ext}");
        let out = triad(&["linearize", "robot_arm", "-o", &name], dir.path());
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let bytes = std::fs::read(dir.path().join(&name)).unwrap();
        match ext {
            "npz" => assert_eq!(&bytes[..2], b"PK"),
            "mat" => assert_eq!(&bytes[126..128], b"IM"),
            _ => assert_eq!(bytes[0], b'{'),
        }
    }
}

#[test]
fn bad_requests_are_refused_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&[&str], &str); 10] = [
        (
            &[
                "linearize",
                "four_bar",
                "--coordinates",
                "nosuch",
                "-o",
                "x.json",
            ],
            "no joint 'nosuch'",
        ),
        (
            &[
                "linearize",
                "four_bar",
                "--coordinates",
                "coupler_rocker",
                "-o",
                "x.json",
            ],
            "closes a loop",
        ),
        (
            &[
                "linearize",
                "four_bar",
                "--coordinates",
                "crank_pivot,rocker_pivot",
                "-o",
                "x.json",
            ],
            "leave 1 independent coordinate",
        ),
        (
            &[
                "linearize",
                "four_bar",
                "--coordinates",
                "crank_pivot,crank_pivot",
                "-o",
                "x.json",
            ],
            "named twice",
        ),
        // the slider at its dead centre cannot drive the crank
        (
            &[
                "linearize",
                "slider_crank",
                "--set",
                "joint.crank_pivot.q0=0",
                "--set",
                "joint.crank_rod.q0=0",
                "--set",
                "joint.guide.q0=0.8",
                "--set",
                "joint.crank_pivot.qd0=0",
                "--set",
                "joint.crank_rod.qd0=0",
                "--set",
                "joint.guide.qd0=0",
                "--coordinates",
                "guide",
                "-o",
                "x.json",
            ],
            "not independent here",
        ),
        (
            &[
                "linearize",
                "pendulum",
                "--coordinates",
                "hinge",
                "-o",
                "x.json",
            ],
            "no closed loops",
        ),
        (
            &["linearize", "pendulum", "--step", "-0.01", "-o", "x.json"],
            "must be a positive number",
        ),
        (
            &["linearize", "pendulum", "-o", "x.txt"],
            ".json, .npz or .mat",
        ),
        (
            &["linearize", "pendulum", "--u", "nosuch=1", "-o", "x.json"],
            "no such input",
        ),
        (
            &[
                "linearize",
                "pendulum",
                "--u",
                "joint.hinge.tau=nan",
                "-o",
                "x.json",
            ],
            "not a finite number",
        ),
    ];
    for (args, msg) in cases {
        let out = triad(args, dir.path());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            !out.status.success() && err.contains(msg),
            "{args:?}: {err}"
        );
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

/// Closed loops: x holds the independent coordinates triad picks (the actuated crank), or those
/// `--coordinates` names; y holds the dependent joints too, not the loop-closing joint's.
#[test]
fn closed_loops_are_linearised_in_independent_coordinates() {
    let dir = tempfile::tempdir().unwrap();
    for (args, x_names) in [
        (
            &["linearize", "four_bar", "-o", "a.json"][..],
            vec!["joint.crank_pivot.q", "joint.crank_pivot.qd"],
        ),
        (
            &[
                "linearize",
                "four_bar",
                "--coordinates",
                "rocker_pivot",
                "-o",
                "a.json",
            ][..],
            vec!["joint.rocker_pivot.q", "joint.rocker_pivot.qd"],
        ),
        (
            &[
                "linearize",
                "slider_crank",
                "--coordinates",
                "guide",
                "-o",
                "a.json",
            ][..],
            vec!["joint.guide.q", "joint.guide.qd"],
        ),
    ] {
        let out = triad(args, dir.path());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{args:?}: {err}");
        assert!(err.contains("independent coordinate"), "{err}");
        let text = std::fs::read_to_string(dir.path().join("a.json")).unwrap();
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        let names: Vec<&str> = v["x_names"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| s.as_str().unwrap())
            .collect();
        assert_eq!(names, x_names, "{args:?}");
        let ys: Vec<&str> = v["y_names"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| s.as_str().unwrap())
            .collect();
        assert!(
            ys.len() == 6
                && !ys
                    .iter()
                    .any(|y| y.contains("rod_slider") || y.contains("coupler_rocker")),
            "{ys:?}"
        );
        assert_eq!(v["A"].as_array().unwrap().len(), 2);
        assert_eq!(v["Ad"].as_array().unwrap().len(), 2);
    }
}
