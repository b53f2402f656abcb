//! The integrator's results are pinned bit for bit: `triad simulate` on three shipped models —
//! a tree (`robot_arm`, with a torque input file), a closed loop (`four_bar`) and a free body
//! (`free_body`) — at orders 2 and 4 must print exactly the CSV committed in
//! `tests/data/golden/`. Every number is written in shortest round-trip form, so equal text
//! means equal `f64` bits. A refactoring that changes a single rounding fails here;
//! `UPDATE_GOLDEN=1` rewrites the files instead (only when a change of results is intended,
//! and said so in the commit).

use std::path::{Path, PathBuf};
use std::process::Command;

/// (golden file stem, model, order, extra arguments)
const RUNS: &[(&str, &str, &str, &[&str])] = &[
    (
        "robot_arm_o2",
        "robot_arm",
        "2",
        &["--input", "tests/data/golden/robot_arm_tau.csv"],
    ),
    (
        "robot_arm_o4",
        "robot_arm",
        "4",
        &["--input", "tests/data/golden/robot_arm_tau.csv"],
    ),
    ("four_bar_o2", "four_bar", "2", &[]),
    ("four_bar_o4", "four_bar", "4", &[]),
    ("free_body_o2", "free_body", "2", &[]),
    ("free_body_o4", "free_body", "4", &[]),
];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn simulate(model: &str, order: &str, extra: &[&str], out: &Path) {
    let spec = format!("modelDescription/{model}/spec.toml");
    let status = Command::new(env!("CARGO_BIN_EXE_triad"))
        .current_dir(root())
        .args([
            "simulate", &spec, "--stop", "1", "--step", "0.05", "--order", order,
        ])
        .args(extra)
        .arg("-o")
        .arg(out)
        .status()
        .unwrap();
    assert!(status.success(), "triad simulate {spec} failed");
}

#[test]
fn simulate_output_is_unchanged_bit_for_bit() {
    let tmp = tempfile::tempdir().unwrap();
    let update = std::env::var_os("UPDATE_GOLDEN").is_some();
    let mut differ = Vec::new();
    for (stem, model, order, extra) in RUNS {
        let out = tmp.path().join(format!("{stem}.csv"));
        simulate(model, order, extra, &out);
        let got = std::fs::read_to_string(&out).unwrap();
        let golden = root().join(format!("tests/data/golden/{stem}.csv"));
        if update {
            std::fs::write(&golden, &got).unwrap();
            continue;
        }
        let want = std::fs::read_to_string(&golden)
            .unwrap_or_else(|e| panic!("{}: {e}", golden.display()));
        if got != want {
            let line = got
                .lines()
                .zip(want.lines())
                .position(|(a, b)| a != b)
                .map_or(0, |k| k + 1);
            differ.push(format!("{stem} (first differing line {line})"));
        }
    }
    assert!(differ.is_empty(), "results changed: {differ:?}");
}
