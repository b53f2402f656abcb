//! `triad simulate` is `sim::Simulation` with a CSV writer: on the double pendulum its rows equal,
//! bit for bit, the outputs of a `Simulation` advanced over the same communication points; its
//! `system.energy` column is constant to 1e-10 (relative) at `--step 0.01`; with an input CSV
//! driving `joint.*.tau`, `system.energy - system.work` is constant to 1e-9 (the discrete
//! work–energy balance of the energy–momentum scheme). Errors write no file.

mod common;
use common::{read_csv, triad};

use triad::sim::Simulation;
use triad::spec::{bundled, Format, Spec};
use triad::variables::{read_state, Causality, VariableTable};

fn tol(x: f64) -> f64 {
    x * std::env::var("TRIAD_TOL_SCALE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1.0)
}

fn column(header: &[String], rows: &[Vec<f64>], name: &str) -> Vec<f64> {
    let k = header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name}"));
    rows.iter().map(|r| r[k]).collect()
}

fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

#[test]
fn simulate_equals_simulation_called_directly() {
    let tmp = tempfile::tempdir().unwrap();
    let out = triad(
        &[
            "simulate",
            "double_pendulum",
            "--stop",
            "1",
            "--step",
            "0.01",
            "-o",
            "dp.csv",
        ],
        tmp.path(),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (header, rows) = read_csv(&tmp.path().join("dp.csv"));

    let (_, text) = bundled()
        .iter()
        .find(|(n, _)| *n == "double_pendulum")
        .unwrap();
    let spec = Spec::from_str(text, Format::Toml, "dp").unwrap();
    let (def, settings) = spec.lower().unwrap();
    let table = VariableTable::new(&def, &settings);
    let outputs: Vec<_> = table.with_causality(Causality::Output).collect();
    let names: Vec<String> = std::iter::once("time".to_string())
        .chain(outputs.iter().map(|v| v.name.clone()))
        .collect();
    assert_eq!(header, names);
    assert_eq!(rows.len(), 101);

    let mut sim = Simulation::new(&def, settings, 0.0).unwrap();
    for (k, row) in rows.iter().enumerate() {
        if k > 0 {
            let target = if k == 100 { 1.0 } else { k as f64 * 0.01 };
            sim.advance(target - sim.time()).unwrap();
        }
        assert!(
            same(row[0], sim.time()),
            "row {k}: time {} vs {}",
            row[0],
            sim.time()
        );
        for (v, x) in outputs.iter().zip(&row[1..]) {
            let direct = match v.accessor {
                triad::variables::Accessor::JointQdd { joint, k } => {
                    sim.accelerations().unwrap().get(joint, k)
                }
                a => read_state(a, sim.state()),
            }
            .unwrap_or(f64::NAN);
            assert!(
                same(*x, direct),
                "row {k}, {}: csv {x} vs direct {direct}",
                v.name
            );
        }
    }
}

#[test]
fn energy_is_conserved_at_step_0_01() {
    let tmp = tempfile::tempdir().unwrap();
    let out = triad(
        &[
            "simulate",
            "double_pendulum",
            "--stop",
            "10",
            "--step",
            "0.01",
            "-o",
            "dp.csv",
        ],
        tmp.path(),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (header, rows) = read_csv(&tmp.path().join("dp.csv"));
    let energy = column(&header, &rows, "system.energy");
    let e0 = energy[0];
    assert!(
        e0.is_finite() && e0.abs() > 1.0,
        "initial energy {e0} (the pendulum starts raised, E0 = -m g (...) != 0)"
    );
    let drift = energy.iter().map(|e| (e - e0).abs()).fold(0.0, f64::max);
    assert!(
        drift <= tol(1e-10) * e0.abs(),
        "energy drift {drift:e} relative {:e}",
        drift / e0.abs()
    );
}

#[test]
fn energy_minus_work_is_constant_under_torque_inputs() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(
        tmp.path().join("tau.csv"),
        "time,joint.shoulder.tau,joint.elbow.tau\n0,1.5,-0.5\n0.5,-2.0,1.0\n1.25,0.0,0.75\n2,3.0,-1.0\n",
    )
    .unwrap();
    let out = triad(
        &[
            "simulate",
            "double_pendulum",
            "--stop",
            "3",
            "--step",
            "0.01",
            "--input",
            "tau.csv",
            "-o",
            "dp.csv",
        ],
        tmp.path(),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (header, rows) = read_csv(&tmp.path().join("dp.csv"));
    let energy = column(&header, &rows, "system.energy");
    let work = column(&header, &rows, "system.work");
    let scale = energy
        .iter()
        .chain(&work)
        .fold(1.0_f64, |a, x| a.max(x.abs()));
    let work_done = work.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
    assert!(
        work_done > 1e-2,
        "the torques did no work ({work_done}): inputs not applied?"
    );
    let balance: Vec<f64> = energy.iter().zip(&work).map(|(e, w)| e - w).collect();
    let drift = balance
        .iter()
        .map(|b| (b - balance[0]).abs())
        .fold(0.0, f64::max);
    assert!(
        drift <= tol(1e-9) * scale,
        "energy - work drifts by {drift:e} (scale {scale})"
    );
}

#[test]
fn input_errors_are_reported_and_write_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let cases = [
        (
            "time,joint.shoulder.torque\n0,1\n",
            "unknown column \"joint.shoulder.torque\"",
        ),
        (
            "time,system.energy\n0,1\n",
            "column \"system.energy\" is not an input variable",
        ),
        ("joint.shoulder.tau\n1\n", "no \"time\" column"),
        (
            "time,joint.shoulder.tau\n0,abc\n",
            "line 2, column \"joint.shoulder.tau\": \"abc\" is not a finite number",
        ),
        (
            "time,joint.shoulder.tau\n1,0\n0,1\n",
            "rows must be in time order",
        ),
    ];
    for (csv, want) in cases {
        std::fs::write(tmp.path().join("in.csv"), csv).unwrap();
        let out = triad(
            &[
                "simulate",
                "double_pendulum",
                "--stop",
                "0.1",
                "--input",
                "in.csv",
                "-o",
                "x.csv",
                "--plot",
                "x.png",
            ],
            tmp.path(),
        );
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{want}");
        assert!(stderr.contains(want), "expected {want:?} in {stderr}");
        assert!(!tmp.path().join("x.csv").exists() && !tmp.path().join("x.png").exists());
        assert_eq!(
            std::fs::read_dir(tmp.path()).unwrap().count(),
            1,
            "temporary files left behind"
        );
    }
}

#[test]
fn options_stdout_and_plot() {
    let tmp = tempfile::tempdir().unwrap();
    let out = triad(
        &[
            "simulate",
            "pendulum",
            "--stop",
            "0.05",
            "--step",
            "0.02",
            "--order",
            "4",
            "--max-step",
            "0.005",
        ],
        tmp.path(),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let times: Vec<&str> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap())
        .collect();
    assert_eq!(times, ["0", "0.02", "0.04", "0.05"]);
    let out = triad(&["simulate", "pendulum", "--order", "3"], tmp.path());
    assert_eq!(out.status.code(), Some(2));
    let out = triad(&["simulate", "pendulum", "--step=0"], tmp.path());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--step must be a positive number"));
    let out = triad(
        &[
            "simulate", "pendulum", "--stop", "0.2", "-o", "p.csv", "--plot", "p.png",
        ],
        tmp.path(),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let png = std::fs::read(tmp.path().join("p.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    assert_eq!(std::fs::read_dir(tmp.path()).unwrap().count(), 2);
}
