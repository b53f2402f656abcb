//! Every shipped model runs under `triad simulate` and behaves as its physics says. With no
//! inputs they are all conservative: `system.energy` stays at its initial value (relative 1e-8
//! over 2 s at the default steps) and the constraints hold (`system.constraint_residual`
//! < 1e-8). Model-specific invariants: the heavy top keeps its vertical angular momentum
//! `L[3]` (gravity has no moment about the vertical through the fixed tip), the free body keeps
//! all of `L` and flips its spin about the intermediate axis (Dzhanibekov) within 10 s, and the
//! slider of the slider-crank stays on its line (z = 0) while the crank turns.

use std::path::Path;
use std::process::Command;

fn tol(x: f64) -> f64 {
    x * std::env::var("TRIAD_TOL_SCALE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1.0)
}

struct Run {
    header: Vec<String>,
    rows: Vec<Vec<f64>>,
}

impl Run {
    fn col(&self, name: &str) -> Vec<f64> {
        let k = self
            .header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("no column {name}"));
        self.rows.iter().map(|r| r[k]).collect()
    }
}

fn simulate(model: &str, stop: &str, dir: &Path) -> Run {
    let out_name = format!("{model}.csv");
    let out = Command::new(env!("CARGO_BIN_EXE_triad"))
        .args(["simulate", model, "--stop", stop, "-o", &out_name])
        .current_dir(dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{model}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut reader = csv::Reader::from_path(dir.join(out_name)).unwrap();
    let header = reader.headers().unwrap().iter().map(String::from).collect();
    let rows = reader
        .records()
        .map(|r| {
            r.unwrap()
                .iter()
                .map(|x| x.parse::<f64>().unwrap())
                .collect()
        })
        .collect();
    Run { header, rows }
}

fn max_dev(v: &[f64]) -> f64 {
    v.iter().map(|x| (x - v[0]).abs()).fold(0.0, f64::max)
}

#[test]
fn every_shipped_model_is_conservative_without_inputs() {
    let tmp = tempfile::tempdir().unwrap();
    for (name, _) in triad::spec::bundled() {
        let run = simulate(name, "2", tmp.path());
        let e = run.col("system.energy");
        assert!(e.iter().all(|x| x.is_finite()), "{name}: non-finite energy");
        let scale = e.iter().fold(1e-3_f64, |a, x| a.max(x.abs()));
        assert!(
            max_dev(&e) <= tol(1e-8) * scale,
            "{name}: energy drifts by {:e} (scale {scale})",
            max_dev(&e)
        );
        let w = run.col("system.work");
        assert!(
            w.iter().all(|x| x.abs() <= tol(1e-12) * scale),
            "{name}: work without inputs"
        );
        let res = run.col("system.constraint_residual");
        assert!(
            res.iter().all(|r| *r < tol(1e-8)),
            "{name}: constraint residual up to {:e}",
            res.iter().fold(0.0_f64, |a, x| a.max(*x))
        );
        // something moves (every model starts off equilibrium or spinning)
        let moving = run
            .header
            .iter()
            .enumerate()
            .filter(|(_, h)| h.ends_with(".w[1]") || h.ends_with(".w[2]") || h.ends_with(".w[3]"))
            .any(|(k, _)| run.rows.iter().any(|r| r[k].abs() > 1e-3));
        assert!(moving, "{name}: nothing moves");
    }
}

#[test]
fn heavy_top_keeps_vertical_angular_momentum() {
    let tmp = tempfile::tempdir().unwrap();
    let run = simulate("heavy_top", "5", tmp.path());
    let l3 = run.col("system.L[3]");
    assert!(l3[0].abs() > 1.0, "the top spins: L3(0) = {}", l3[0]);
    assert!(
        max_dev(&l3) <= tol(1e-8) * l3[0].abs(),
        "L3 drifts by {:e}",
        max_dev(&l3)
    );
}

#[test]
fn free_body_flips_and_keeps_its_momentum() {
    let tmp = tempfile::tempdir().unwrap();
    let run = simulate("free_body", "10", tmp.path());
    for i in 1..=3 {
        let l = run.col(&format!("system.L[{i}]"));
        assert!(
            max_dev(&l) <= tol(1e-9) * 4.0,
            "L[{i}] drifts by {:e}",
            max_dev(&l)
        );
    }
    // body y axis in world coordinates: column 2 of R; it turns over (Dzhanibekov flip)
    let r22 = run.col("body.body.R[2,2]");
    assert!((r22[0] - 1.0).abs() < 1e-12);
    assert!(
        r22.iter().any(|x| *x < -0.9),
        "the spin never flipped: min R[2,2] = {}",
        r22.iter().fold(1.0_f64, |a, x| a.min(*x))
    );
}

#[test]
fn slider_stays_on_its_guide() {
    let tmp = tempfile::tempdir().unwrap();
    let run = simulate("slider_crank", "2", tmp.path());
    let z = run.col("body.slider.r[3]");
    let y = run.col("body.slider.r[2]");
    assert!(
        z.iter().chain(&y).all(|v| v.abs() < 1e-9),
        "the slider left its guide"
    );
    let x = run.col("body.slider.r[1]");
    let (lo, hi) = x
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(*v), b.max(*v)));
    // stroke of a crank of 0.2 m: 0.4 m between the dead centres, if the crank turns over
    assert!(
        hi <= 0.8 + 1e-9 && lo >= 0.4 - 1e-9,
        "slider outside [l - r, l + r]: [{lo}, {hi}]"
    );
}
