//! `triad simulate`'s everyday options: input rows take effect at their own times (a pulse
//! between communication points moves the model exactly as a run whose communication points
//! include it), `--set NAME=VALUE` (checked like `fmi2SetReal`), `--outputs PATTERN` (globs
//! choosing the columns). Bad values: a clear message, non-zero exit, no file written.

mod common;
use common::{read_csv, triad};

use std::path::Path;

fn run_ok(args: &[&str], dir: &Path) {
    let out = triad(args, dir);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn run_err(args: &[&str], dir: &Path) -> String {
    let out = triad(args, dir);
    assert!(!out.status.success(), "{args:?} succeeded");
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// The rows of `fine` at the times of `coarse`'s rows.
fn at_times(coarse: &[Vec<f64>], fine: &[Vec<f64>]) -> Vec<Vec<f64>> {
    coarse
        .iter()
        .map(|r| {
            fine.iter()
                .find(|f| (f[0] - r[0]).abs() < 1e-12)
                .unwrap_or_else(|| panic!("no fine row at t = {}", r[0]))
                .clone()
        })
        .collect()
}

#[test]
fn a_pulse_between_communication_points_is_applied_at_its_own_time() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    std::fs::write(
        d.join("pulse.csv"),
        "time,joint.shoulder.tau\n0,0\n0.005,100\n0.006,0\n",
    )
    .unwrap();
    let common = [
        "simulate",
        "double_pendulum",
        "--stop",
        "0.05",
        "--max-step",
        "0.001",
    ];
    let with = |step: &str, input: bool, out: &str| {
        let mut a: Vec<&str> = common.to_vec();
        a.extend(["--step", step, "-o", out]);
        if input {
            a.extend(["--input", "pulse.csv"]);
        }
        run_ok(&a, d);
        read_csv(&d.join(out))
    };
    let (h, coarse) = with("0.01", true, "coarse.csv");
    let (_, fine) = with("0.001", true, "fine.csv");
    let (_, none) = with("0.01", false, "none.csv");
    let q = h.iter().position(|c| c == "joint.shoulder.q").unwrap();
    let fine = at_times(&coarse, &fine);
    for (c, f) in coarse.iter().zip(&fine) {
        for (k, (a, b)) in c.iter().zip(f).enumerate() {
            assert!(
                (a - b).abs() <= 1e-12 * a.abs().max(1.0),
                "t = {}: column {} {a} vs {b}",
                c[0],
                h[k]
            );
        }
    }
    // and the pulse did something: 0.1 N·m·s on the shoulder
    let moved = (coarse.last().unwrap()[q] - none.last().unwrap()[q]).abs();
    assert!(
        moved > 1e-3,
        "the pulse moved the shoulder by {moved} rad only"
    );
}

#[test]
fn set_changes_parameters_as_fmi2_set_real_would() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    run_ok(
        &[
            "simulate",
            "double_pendulum",
            "--stop",
            "0.01",
            "--set",
            "joint.elbow.q0=0.3",
            "--set",
            "joint.elbow.damping = 0.5",
            "-o",
            "set.csv",
        ],
        d,
    );
    let (h, rows) = read_csv(&d.join("set.csv"));
    let q = h.iter().position(|c| c == "joint.elbow.q").unwrap();
    assert!((rows[0][q] - 0.3).abs() < 1e-12, "{}", rows[0][q]);
    let work = h.iter().position(|c| c == "system.work").unwrap();
    assert!(rows.last().unwrap()[work] < 0.0, "damping dissipates");

    for (set, want) in [
        ("solver.max_step=1e-300", "solver.max_step must be in"),
        ("joint.elbow.damping=-1", "damping must be >= 0"),
        ("joint.elbo.q0=1", "did you mean \"joint.elbow.q0\""),
        ("system.energy=1", "is not a parameter"),
        ("joint.elbow.q0=abc", "is not a number"),
        ("joint.elbow.q0", "expected NAME=VALUE"),
        ("body.link1.inertia[1,1]=100", "triangle inequality"),
    ] {
        let err = run_err(
            &["simulate", "double_pendulum", "--set", set, "-o", "bad.csv"],
            d,
        );
        assert!(err.contains(want), "--set {set}: {err}");
        assert!(!d.join("bad.csv").exists());
    }
}

#[test]
fn outputs_chooses_the_columns() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    run_ok(
        &[
            "simulate",
            "double_pendulum",
            "--stop",
            "0.01",
            "--outputs",
            "joint.*.q,system.energy",
            "--outputs",
            "body.link2.R[1,2]",
            "-o",
            "few.csv",
        ],
        d,
    );
    let (h, rows) = read_csv(&d.join("few.csv"));
    assert_eq!(
        h,
        [
            "time",
            "body.link2.R[1,2]",
            "joint.shoulder.q",
            "joint.elbow.q",
            "system.energy"
        ]
    );
    assert!(rows.iter().all(|r| r.len() == 5));
    let err = run_err(
        &[
            "simulate",
            "double_pendulum",
            "--outputs",
            "joint.*.torque",
            "-o",
            "bad.csv",
        ],
        d,
    );
    assert!(
        err.contains("\"joint.*.torque\" matches no output"),
        "{err}"
    );
    assert!(!d.join("bad.csv").exists());
}
