//! Every malformed spec in `tests/data/bad_specs/` is rejected by the built `triad` binary with
//! the expected `file: path: reason` line, a non-zero exit and no panic; `triad simulate -o`
//! on it writes no file. A new bad spec must be added to the table below.

mod common;
use common::triad;

use std::path::{Path, PathBuf};

/// (file, expected message lines after "file: ").
const CASES: &[(&str, &[&str])] = &[
    ("syntax_error.toml", &["line 5, column 8: TOML syntax error"]),
    ("syntax_error.json", &["line 5, column 3: JSON syntax error: trailing comma"]),
    ("unknown_field.toml", &["body[0].mas: unknown field \"mas\"; did you mean \"mass\"?", "body[0]: missing field \"mass\""]),
    ("missing_body.toml", &["joint[0].child: no body named \"rdo\"; did you mean \"rod\"?"]),
    ("two_tree_parents.toml", &["joint[1].child: body \"rod\" already has a tree parent (joint[0] \"hinge\"); if this joint closes a loop, give it child_origin"]),
    ("zero_axis.toml", &["joint[1].axis: zero length"]),
    ("negative_mass.toml", &["body[0].mass: must be >= 0 (got -1)"]),
    ("not_positive_definite.toml", &["body[0].inertia: has a negative principal moment"]),
    ("triangle_inequality.toml", &["body[0].inertia: violates the triangle inequality: principal moments 1 + 1 < 3"]),
    ("bad_name.toml", &["body[0].name: \"rod-1\" is not an identifier"]),
    ("duplicate_name.toml", &["body[1].name: duplicate body name \"rod\" (also body[0])"]),
    ("wrong_vector_length.toml", &["body[0].com: expected 3 numbers, found 2"]),
    ("nan.toml", &["gravity: must be finite (nan and inf are not allowed)", "body[0].mass: must be finite (got NaN)"]),
    ("loop_not_closed.toml", &["joint[3]: loop-closing joint \"coupler_rocker\" is violated by the initial pose"]),
    ("unknown_joint_type.toml", &["joint[0].type: unknown joint type \"hinge\"; valid types are revolute, prismatic, cylindrical, universal, spherical, planar, fixed"]),
    ("bad_solver_order.toml", &["solver.order: must be 2 or 4 (got 3)"]),
    ("actuated_planar.toml", &["joint[0].actuated: planar joints cannot be actuated"]),
    ("spherical_stiffness.toml", &["joint[0].stiffness: spherical joints take no stiffness"]),
    ("no_pose.toml", &["body[1]: body \"floating\" has no pose"]),
    ("parent_without_pose.toml", &["body[0]: body \"base\" has no tree joint to the world (it is only a parent or a loop-closing child): attach it with a joint without child_origin, or make it a floating base by giving position"]),
    ("massless_leaf.toml", &["body[1]: body \"tool\" has no mass and it is a leaf whose joint lets it move in a way that moves no body with mass"]),
    ("universal_not_perpendicular.toml", &["joint[0].axis2: must be perpendicular to axis"]),
    ("tree_cycle.toml", &["joint[0]: tree joints ba, ab form a cycle that never reaches the world"]),
    ("bad_initial_length.toml", &["joint[0].initial.q: a revolute joint has 1 coordinate: expected 1 number, found 2"]),
    (
        "many_problems.toml",
        &[
            "name: \"1bad\" is not an identifier",
            "experiment.stop: must be greater than experiment.start",
            "solver.max_step: must be in [1e-9, 1e3] s (got 0)",
            "solver.tolerance: must be in [1e-14, 1e-3) (got 0.1)",
            "body[0].mass: must be >= 0 (got -0.5)",
            "joint[0]: a revolute joint needs axis = [x, y, z]",
            "joint[0].parent: no body named \"wrld\" (use a [[body]] name or \"world\"); did you mean \"world\"?",
        ],
    ),
];

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/bad_specs")
}

#[test]
fn every_bad_spec_is_listed() {
    let mut files: Vec<String> = std::fs::read_dir(dir())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    let mut listed: Vec<String> = CASES.iter().map(|(f, _)| (*f).to_string()).collect();
    listed.sort();
    assert_eq!(files, listed);
    assert!(files.len() >= 15);
}

#[test]
fn check_reports_the_expected_problems() {
    let mut failures = Vec::new();
    for (file, expected) in CASES {
        let out = triad(&["check", file], &dir());
        let stderr = String::from_utf8_lossy(&out.stderr);
        if out.status.success() || out.status.code() != Some(1) {
            failures.push(format!("{file}: exit status {:?}", out.status));
        }
        if stderr.contains("panicked") {
            failures.push(format!("{file}: panicked\n{stderr}"));
        }
        for want in *expected {
            let line = format!("{file}: {want}");
            if !stderr.lines().any(|l| l.starts_with(&line)) {
                failures.push(format!(
                    "{file}: expected a line starting {line:?}, got\n{stderr}"
                ));
            }
        }
        assert!(
            out.stdout.is_empty(),
            "{file}: check printed to stdout on error"
        );
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn many_problems_are_reported_at_once() {
    let out = triad(&["check", "many_problems.toml"], &dir());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("error: many_problems.toml has 7 problems"),
        "{stderr}"
    );
}

#[test]
fn simulate_writes_nothing_on_error() {
    let tmp = tempfile::tempdir().unwrap();
    for (file, _) in CASES {
        let spec = dir().join(file);
        let out = triad(
            &[
                "simulate",
                spec.to_str().unwrap(),
                "-o",
                "x.csv",
                "--plot",
                "x.png",
            ],
            tmp.path(),
        );
        assert!(!out.status.success(), "{file}");
        assert!(
            !String::from_utf8_lossy(&out.stderr).contains("panicked"),
            "{file}"
        );
        let left: Vec<_> = std::fs::read_dir(tmp.path()).unwrap().collect();
        assert!(
            left.is_empty(),
            "{file}: simulate left files behind: {left:?}"
        );
    }
}

#[test]
fn describe_and_build_refuse_bad_specs() {
    let tmp = tempfile::tempdir().unwrap();
    for cmd in ["describe", "build"] {
        let spec = dir().join("zero_axis.toml");
        let out = triad(&[cmd, spec.to_str().unwrap()], tmp.path());
        assert_eq!(out.status.code(), Some(1), "{cmd}");
        assert!(
            String::from_utf8_lossy(&out.stderr)
                .contains("zero_axis.toml: joint[1].axis: zero length"),
            "{cmd}"
        );
        assert!(out.stdout.is_empty(), "{cmd}");
        assert_eq!(std::fs::read_dir(tmp.path()).unwrap().count(), 0, "{cmd}");
    }
}

#[test]
fn missing_file_and_unknown_extension() {
    let tmp = tempfile::tempdir().unwrap();
    let out = triad(&["check", "nowhere.toml"], tmp.path());
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("nowhere.toml: cannot read the file"));
    std::fs::write(tmp.path().join("m.yaml"), "name: x").unwrap();
    let out = triad(&["check", "m.yaml"], tmp.path());
    assert!(String::from_utf8_lossy(&out.stderr)
        .contains("m.yaml: unknown file type: a model spec ends in .toml or .json"));
    let out = triad(&["check", "no_such_model"], tmp.path());
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("no shipped model of that name (shipped: ")
    );
}
