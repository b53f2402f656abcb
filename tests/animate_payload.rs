//! The replay's embedded payload gives back the recorded poses: for every body at every frame,
//! `|r_page − r_csv| ≤ 1e-6 m` and the angle of `R_csvᵀ R_page` ≤ 1e-6 rad (positions travel as
//! `f64`, orientations as `f32` unit quaternions: ≈ 1e-7 rad). Denser results are decimated to
//! `--fps` frames per second, each kept frame being a recorded row, the first and last included.
//! A 10 s run of the six-joint arm at 100 Hz makes a page well under 10 MB. Contact forces
//! (`contact.C.f[1..3]`) travel as `f32`: each component within 1.2e-7 of its own size, a zero
//! force exactly zero, decimated with the poses; the spec's `[ground]` and `[[collision]]`
//! shapes are in the payload.

mod common;
use common::{read_csv, triad};

use std::path::Path;

use triad::math::{Mat3, Vec3};

/// Angle of the rotation `a⁻¹ b`, rad (well conditioned near 0).
fn angle(a: &Mat3, b: &Mat3) -> f64 {
    let e = a.transpose() * b;
    let s = Vec3::new(
        e[(2, 1)] - e[(1, 2)],
        e[(0, 2)] - e[(2, 0)],
        e[(1, 0)] - e[(0, 1)],
    )
    .norm()
        / 2.0;
    let c = (e.trace() - 1.0) / 2.0;
    s.atan2(c)
}

/// Runs simulate then animate; returns (CSV path, page HTML).
fn replay(dir: &Path, model: &str, args: &[&str], fps: &str) -> (std::path::PathBuf, String) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let csv = dir.join("run.csv");
    let html = dir.join("run.html");
    let model = root.join(model);
    let model = model.to_str().unwrap();
    let mut sim = vec!["simulate", model, "-o", csv.to_str().unwrap()];
    sim.extend_from_slice(args);
    let out = triad(&sim, dir);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = triad(
        &[
            "animate",
            model,
            csv.to_str().unwrap(),
            "-o",
            html.to_str().unwrap(),
            "--fps",
            fps,
        ],
        dir,
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    (csv, std::fs::read_to_string(html).unwrap())
}

/// The largest position and angle errors of the page's poses against the CSV's rows.
fn errors(csv: &Path, html: &str) -> (f64, f64, usize, usize) {
    let (header, rows) = read_csv(csv);
    let poses = triad::viewer::decode(triad::viewer::payload_of(html).unwrap()).unwrap();
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let (mut dr, mut dtheta) = (0.0_f64, 0.0_f64);
    let mut row = 0;
    for (k, &t) in poses.time.iter().enumerate() {
        // every frame is a recorded row, in order
        while rows[row][0] != t {
            row += 1;
        }
        for (name, r, rot) in &poses.bodies {
            let r_csv = Vec3::from_fn(|i, _| rows[row][col(&format!("body.{name}.r[{}]", i + 1))]);
            let rot_csv = Mat3::from_fn(|i, j| {
                rows[row][col(&format!("body.{name}.R[{},{}]", i + 1, j + 1))]
            });
            dr = dr.max((r[k] - r_csv).norm());
            dtheta = dtheta.max(angle(&rot_csv, &rot[k]));
        }
    }
    assert_eq!(poses.time[0], rows[0][0], "the first row is kept");
    assert_eq!(
        *poses.time.last().unwrap(),
        rows.last().unwrap()[0],
        "the last row is kept"
    );
    (dr, dtheta, poses.time.len(), rows.len())
}

#[test]
fn poses_round_trip_through_the_page() {
    let dir = tempfile::tempdir().unwrap();
    let arm = "modelDescription/robot_arm/robot_arm.urdf";
    let (csv, html) = replay(dir.path(), arm, &["--stop", "10", "--step", "0.01"], "100");
    let (dr, dtheta, frames, rows) = errors(&csv, &html);
    eprintln!(
        "robot_arm, 10 s at 100 Hz: {frames} frames, page {:.2} MB, |Δr| ≤ {dr:.1e} m, |Δθ| ≤ {dtheta:.1e} rad",
        html.len() as f64 / 1e6
    );
    assert_eq!(frames, rows);
    assert!(dr <= 1e-6, "position error {dr:e} m");
    assert!(dtheta <= 1e-6, "angle error {dtheta:e} rad");
    assert!(html.len() < 10_000_000, "page of {} bytes", html.len());

    // a chain in a wide motion (loop-closing joints, sites)
    for model in [
        "modelDescription/double_pendulum/spec.toml",
        "modelDescription/four_bar/spec.toml",
        "modelDescription/free_body/spec.toml",
    ] {
        let (csv, html) = replay(dir.path(), model, &["--stop", "2", "--step", "0.01"], "100");
        let (dr, dtheta, _, _) = errors(&csv, &html);
        assert!(
            dr <= 1e-6 && dtheta <= 1e-6,
            "{model}: {dr:e} m, {dtheta:e} rad"
        );
    }
}

#[test]
fn dense_results_are_decimated_to_recorded_rows() {
    let dir = tempfile::tempdir().unwrap();
    let (csv, html) = replay(
        dir.path(),
        "modelDescription/double_pendulum/spec.toml",
        &["--stop", "1", "--step", "0.001"],
        "50",
    );
    let (dr, dtheta, frames, rows) = errors(&csv, &html);
    assert_eq!(rows, 1001);
    assert_eq!(frames, 51, "one frame per 20 ms, first and last included");
    assert!(dr <= 1e-6 && dtheta <= 1e-6);
}

#[test]
fn contact_forces_round_trip_through_the_page() {
    let dir = tempfile::tempdir().unwrap();
    let ball = "examples/specs/bouncing_ball.toml";
    for fps in ["100", "30"] {
        let (csv, html) = replay(dir.path(), ball, &["--stop", "3", "--step", "0.01"], fps);
        let (dr, dtheta, frames, rows) = errors(&csv, &html);
        assert!(dr <= 1e-6 && dtheta <= 1e-6, "{dr:e} m, {dtheta:e} rad");
        let (header, data) = read_csv(&csv);
        let col = |name: &str| header.iter().position(|h| h == name).unwrap();
        let payload = triad::viewer::payload_of(&html).unwrap();
        let page = triad::viewer::decode(payload).unwrap();
        assert_eq!(page.forces.len(), 1, "one collision shape");
        let (name, forces) = &page.forces[0];
        assert_eq!(name, "shell");
        assert_eq!(forces.len(), frames);
        let (mut row, mut touching, mut worst) = (0, 0, 0.0_f64);
        for (k, &t) in page.time.iter().enumerate() {
            while data[row][0] != t {
                row += 1;
            }
            for i in 0..3 {
                let want = data[row][col(&format!("contact.shell.f[{}]", i + 1))];
                let got = forces[k][i];
                if want == 0.0 {
                    assert_eq!(got, 0.0, "a zero force stays zero (t = {t})");
                } else {
                    worst = worst.max((got - want).abs() / want.abs());
                }
            }
            if forces[k].norm() > 0.0 {
                touching += 1;
            }
        }
        eprintln!(
            "bouncing_ball at {fps} fps: {frames} of {rows} rows, {touching} with a contact force, \
             force error ≤ {worst:.1e} relative"
        );
        assert!(worst <= 1.2e-7, "force error {worst:e}");
        // it bounces lower and lower, and touches the ground in many rows after 1.5 s
        assert!(
            touching >= frames / 10,
            "{touching} frames with a contact force"
        );
        let v: serde_json::Value = serde_json::from_str(payload).unwrap();
        assert_eq!(v["ground"]["normal"], serde_json::json!([0.0, 0.0, 1.0]));
        assert_eq!(v["ground"]["height"], 0.0);
        assert_eq!(v["contacts"][0]["shape"]["kind"], "sphere");
        assert_eq!(v["contacts"][0]["body"], 0);
        // the weight (1 kg × 9.81 m/s²) about half the model's size long, rounded to 1-2-5
        assert_eq!(v["forces"]["basis"], "weight");
        assert!((v["forces"]["reference"].as_f64().unwrap() - 9.81).abs() < 1e-12);
        let scale = v["forces"]["scale"].as_f64().unwrap();
        let length = v["length"].as_f64().unwrap();
        let arrow = 9.81 / scale / length;
        assert!(
            (0.2..1.3).contains(&arrow),
            "the weight is {arrow} of the model's size"
        );
    }
}
