//! Whether a model with massless or inertia-less bodies is determined, decided with a tolerance
//! (`model/determinacy.rs`): the smallest singular value σ of the singular bodies' joint rows
//! on their null directions measures how far their softest motion is from moving no mass; its
//! kinetic energy is ≈ σ² of the model's scale. σ below 1e-6 (an energy below 1e-12, singular to
//! round-off) is refused by `check`, naming the bodies and joints; a model above it takes its
//! steps; a run that fails where the motion is nearly undetermined says so, with the bodies,
//! the estimate and a hint.
//!
//! The robot is `tests/data/urdf/neck.urdf`: a point-mass head on two massless neck links whose
//! centre of mass lies on the last axis only as far as `rpy="0 0 1.5708"` puts it (3.7e-7 m off).

mod common;
use common::triad;
use std::path::{Path, PathBuf};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/urdf")
        .join(name)
}

fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn a_neck_singular_to_round_off_is_refused_with_its_names() {
    let tmp = tempfile::tempdir().unwrap();
    let neck = data("neck.urdf");
    let out = triad(&["check", neck.to_str().unwrap()], tmp.path());
    assert!(!out.status.success());
    let msg = stderr(&out);
    for want in ["link \"head\"", "'neck_yaw'", "round-off", "1.5708"] {
        assert!(msg.contains(want), "missing {want:?} in: {msg}");
    }
    // the same neck with the exact angle: its motion is not determined at all
    let exact = tmp.path().join("exact.urdf");
    let text = std::fs::read_to_string(&neck).unwrap();
    std::fs::write(&exact, text.replace("1.5708\"", "1.5707963267948966\"")).unwrap();
    let out = triad(&["check", exact.to_str().unwrap()], tmp.path());
    assert!(!out.status.success());
    assert!(stderr(&out).contains("not determined"), "{}", stderr(&out));
    // refused by every command that builds the model, nothing written
    let out = triad(
        &["simulate", neck.to_str().unwrap(), "-o", "x.csv"],
        tmp.path(),
    );
    assert!(!out.status.success());
    assert!(!tmp.path().join("x.csv").exists());
}

#[test]
fn the_determined_neck_runs_at_both_orders() {
    let tmp = tempfile::tempdir().unwrap();
    let neck = data("neck_determined.urdf");
    let neck = neck.to_str().unwrap();
    assert!(triad(&["check", neck], tmp.path()).status.success());
    for order in ["2", "4"] {
        let out = triad(
            &[
                "simulate",
                neck,
                "--order",
                order,
                "--stop",
                "1",
                "--set",
                "joint.neck_pitch.q0=0.3",
                "--set",
                "joint.neck_roll.qd0=0.5",
                "--set",
                "joint.neck_yaw.qd0=1",
                "-o",
                "d.csv",
            ],
            tmp.path(),
        );
        assert!(out.status.success(), "order {order}: {}", stderr(&out));
    }
}

#[test]
fn a_step_that_fails_near_a_singular_configuration_says_what_is_known() {
    // the centre of mass 1 mm off the last axis: determined at the start (σ ≈ 1e-3), but the
    // massless links carry the point mass through configurations where it is not
    let tmp = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(data("neck.urdf"))
        .unwrap()
        .replace("1.5708\"", "1.5707963267948966\"")
        .replace("xyz=\"0 -0.1 0\"", "xyz=\"1e-3 -0.1 0\"");
    let path = tmp.path().join("mm.urdf");
    std::fs::write(&path, text).unwrap();
    let path = path.to_str().unwrap();
    assert!(triad(&["check", path], tmp.path()).status.success());
    let out = triad(
        &[
            "simulate",
            path,
            "--stop",
            "0.5",
            "--set",
            "joint.neck_pitch.q0=0.3",
            "--set",
            "joint.neck_roll.qd0=0.5",
            "-o",
            "mm.csv",
        ],
        tmp.path(),
    );
    assert!(
        !out.status.success(),
        "the run was expected to meet the singular set"
    );
    let msg = stderr(&out);
    for want in [
        "nearly undetermined",
        "'head'",
        "'neck_yaw'",
        "of the model's scale",
        "give 'head' mass and inertia",
    ] {
        assert!(msg.contains(want), "missing {want:?} in: {msg}");
    }
}
