//! How MODEL is named on the command line: a spec file, a model folder (its `spec.toml`), or
//! the name of a shipped model; `check` prints `ok`, a summary and the model's notes, and
//! writes nothing.

mod common;
use common::triad;

use std::path::Path;

#[test]
fn file_folder_and_shipped_name_are_the_same_model() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let tmp = tempfile::tempdir().unwrap();
    let file = root.join("modelDescription/four_bar/spec.toml");
    let folder = root.join("modelDescription/four_bar");
    let outs: Vec<String> = [file.to_str().unwrap(), folder.to_str().unwrap(), "four_bar"]
        .iter()
        .map(|m| {
            let out = triad(&["check", m], tmp.path());
            assert!(
                out.status.success(),
                "{m}: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            String::from_utf8(out.stdout).unwrap()
        })
        .collect();
    for out in &outs {
        let mut lines = out.lines();
        assert!(lines.next().unwrap().ends_with(": ok"));
        assert_eq!(lines.next().unwrap(), "model FourBar: 3 bodies, 4 joints (1 loop-closing), 1 input, 74 outputs, 55 parameters");
        assert!(out.contains("note: joint 'coupler_rocker'"), "{out}");
    }
    assert_eq!(
        std::fs::read_dir(tmp.path()).unwrap().count(),
        0,
        "check wrote a file"
    );
}

#[test]
fn build_wants_a_spec_file_for_a_shipped_name() {
    let tmp = tempfile::tempdir().unwrap();
    let out = triad(&["build", "pendulum"], tmp.path());
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr)
        .contains("triad build modelDescription/pendulum/spec.toml"));
}

/// The example specs (`examples/specs/`) check and simulate: the massless wrist (a massless
/// yoke between two revolutes and a massless welded tool frame) keeps its energy.
#[test]
fn example_specs_check_and_simulate() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let tmp = tempfile::tempdir().unwrap();
    let spec = root.join("examples/specs/massless_wrist.toml");
    let spec = spec.to_str().unwrap();
    let out = triad(&["check", spec], tmp.path());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = triad(
        &["simulate", spec, "--stop", "2", "--step", "0.1"],
        tmp.path(),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut reader = csv::Reader::from_reader(out.stdout.as_slice());
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    let col = |name: &str| header.iter().position(|h| h == name).expect(name);
    let (e, w) = (col("system.energy"), col("system.work"));
    let rows: Vec<Vec<f64>> = reader
        .records()
        .map(|r| r.unwrap().iter().map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 21);
    let e0 = rows[0][e] - rows[0][w];
    for r in &rows {
        assert!(
            ((r[e] - r[w]) - e0).abs() <= 1e-9 * e0.abs().max(1.0),
            "{r:?}"
        );
    }
    assert!(
        header.iter().any(|h| h == "body.tool0.r[1]"),
        "the massless frame's pose is an output"
    );
}
