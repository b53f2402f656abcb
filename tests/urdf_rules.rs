//! URDF rules of issue 30, on synthetic robots of `tests/data/urdf/` written for these tests:
//!
//! - `<dynamics>` on a fixed joint is ignored with a note, merged or kept (`--keep-fixed`);
//! - a `<visual>` or `<collision>` that cannot be read is dropped with a warning naming its line,
//!   and every command accepts the robot;
//! - a link whose own inertia is impossible but which is welded by fixed joints into a possible
//!   rigid body is accepted with a note in both import modes, and the two modes move alike:
//!   `max |Δq|, |Δq̇| ≤ 1e-11` over 1 s; an impossible rigid body is refused, naming its
//!   impossible links at the line of their `<inertia>`;
//! - a joint cycle, an impossible inertia and a `<mimic>` of a missing joint are errors on
//!   their lines;
//! - every command that reads a URDF takes the import options: a single free box is checked,
//!   described, built, simulated and animated with `--floating-base`.

mod common;
use common::{read_csv, settings, triad};
use std::path::{Path, PathBuf};
use triad::mechanics::{step, Model, State};
use triad::urdf::{import, ImportOptions};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/urdf")
        .join(name)
}

fn text(name: &str) -> String {
    std::fs::read_to_string(data(name)).unwrap()
}

const KEEP: ImportOptions = ImportOptions {
    base: triad::urdf::Base::Auto,
    keep_fixed: true,
    no_limits: false,
    no_friction: false,
    no_mimic: false,
    contacts: false,
    on_ground: false,
};

/// Runs triad in `dir`: (success, stdout, stderr), after checking nothing panicked.
fn run(args: &[&str], dir: &Path) -> (bool, String, String) {
    let out = triad(args, dir);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        err,
    )
}

#[test]
fn dynamics_on_a_fixed_joint_is_ignored_with_a_note() {
    let urdf = data("fixed_dynamics.urdf");
    let urdf = urdf.to_str().unwrap();
    let tmp = tempfile::tempdir().unwrap();
    for keep in [false, true] {
        let mut args = vec!["check", urdf];
        if keep {
            args.push("--keep-fixed");
        }
        let (ok, out, err) = run(&args, tmp.path());
        assert!(ok, "{args:?}: {err}");
        for joint in ["tool_joint", "plate_joint"] {
            assert!(
                out.contains(&format!("note: joint '{joint}': <dynamics damping=")),
                "{args:?}: {out}"
            );
        }
        assert!(
            out.contains("friction=\"0.1\"> is ignored (the joint is fixed"),
            "{out}"
        );
        let opts = if keep { KEEP } else { ImportOptions::default() };
        let (spec, _) = import(&text("fixed_dynamics.urdf"), "fixed_dynamics.urdf", &opts).unwrap();
        spec.validate("fixed_dynamics.urdf").unwrap();
        let hinge = &spec.joint[spec.joint_index("hinge").unwrap()];
        assert_eq!(hinge.damping, 0.05);
        assert!(spec
            .joint
            .iter()
            .filter(|j| j.name != "hinge")
            .all(|j| j.damping == 0.0));
        assert_eq!(spec.joint.len(), if keep { 3 } else { 1 });
    }
    let (ok, _, err) = run(
        &["import", urdf, "--keep-fixed", "-o", "kept.toml"],
        tmp.path(),
    );
    assert!(ok, "{err}");
    let toml = std::fs::read_to_string(tmp.path().join("kept.toml")).unwrap();
    assert!(
        toml.contains("# note: joint 'tool_joint': <dynamics"),
        "{toml}"
    );
    let (ok, _, err) = run(&["build", "kept.toml", "-o", "kept.fmu"], tmp.path());
    assert!(ok, "{err}");
}

/// The warnings of `bad_visual.urdf`, each with its line.
const WARNINGS: [&str; 5] = [
    "warning: bad_visual.urdf: line 16: link \"arm\": <mesh> scale=\"1 1 1 1\": expected 3 numbers, found 4 (the <visual> of line 14 is dropped)",
    "warning: bad_visual.urdf: line 22: link \"arm\": <color> rgba=\"1 0 0\": expected 4 numbers, found 3 (the <visual> of line 19 is drawn in the default colour)",
    "warning: bad_visual.urdf: line 25: link \"arm\": <box> size=\"0.1 0.1\": expected 3 numbers, found 2 (the <collision> of line 24 is dropped)",
    "warning: bad_visual.urdf: line 28: link \"arm\": <cylinder> needs radius=\"…\" (the <collision> of line 27 is dropped)",
    "warning: bad_visual.urdf: line 33: link \"tip\": <sphere> radius=\"big\": not a list of numbers (the <visual> of line 33 is dropped)",
];

#[test]
fn unreadable_geometry_is_dropped_with_a_warning() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    std::fs::copy(data("bad_visual.urdf"), d.join("bad_visual.urdf")).unwrap();
    let u = "bad_visual.urdf";
    for args in [
        vec!["check", u],
        vec!["describe", u],
        vec!["import", u, "-o", "bad.toml"],
        vec!["import", u, "--keep-fixed", "-o", "kept.toml"],
        vec!["build", u, "-o", "bad.fmu"],
        vec!["simulate", u, "--stop", "0.2", "-o", "bad.csv"],
        vec!["animate", u, "bad.csv", "-o", "bad.html"],
    ] {
        let (ok, _, err) = run(&args, d);
        assert!(ok, "{args:?}: {err}");
        for w in WARNINGS {
            assert!(err.contains(w), "{args:?}: {w:?} not in\n{err}");
        }
    }
    for f in ["bad.toml", "kept.toml", "bad.fmu", "bad.csv", "bad.html"] {
        assert!(d.join(f).is_file(), "{f}");
    }
    let toml = std::fs::read_to_string(d.join("bad.toml")).unwrap();
    assert!(
        toml.contains("# warning: line 16: link \"arm\": <mesh> scale=\"1 1 1 1\""),
        "{toml}"
    );
    // what can be read is kept: the base's box and the arm's cylinder (in the default colour)
    let (spec, outcome) = import(&text(u), u, &ImportOptions::default()).unwrap();
    assert_eq!(outcome.warnings.len(), WARNINGS.len());
    assert_eq!(spec.visual.len(), 2, "{:?}", spec.visual);
    assert_eq!(spec.visual[0].cuboid, Some([0.1; 3]));
    assert_eq!(spec.visual[1].cylinder, Some([0.02, 0.5]));
    assert_eq!(spec.visual[1].rgba, None);
    // the dynamics is still checked: a bad inertial stays an error
    let broken = text(u).replace("<mass value=\"0.1\"/>", "<mass value=\"heavy\"/>");
    let e = import(&broken, u, &ImportOptions::default()).unwrap_err();
    assert!(
        e.to_string()
            .contains("line 32: link \"tip\": <mass> value=\"heavy\""),
        "{e}"
    );
}

/// Joint angles and rates of `shoulder` and `elbow` every 0.1 s over 1 s (order 2, h = 1e-3),
/// from a start off the rest pose, with torques on both joints.
fn welded_trajectory(opts: &ImportOptions) -> Vec<f64> {
    let (spec, _) = import(&text("welded_inertia.urdf"), "welded_inertia.urdf", opts).unwrap();
    spec.validate("welded_inertia.urdf").unwrap();
    let (mut def, _) = spec.lower().unwrap();
    for (j, q) in [("shoulder", 0.7), ("elbow", -0.4)] {
        let k = def.joints.iter().position(|d| d.name == j).unwrap();
        def.joints[k].initial = triad::mechanics::JointInitial::Coords {
            q: vec![q],
            qd: vec![1.5],
        };
    }
    let model = Model::new(&def, settings(1e-3, 2)).unwrap();
    let mut s = State::new(&model);
    for (k, x) in s.inputs_mut().iter_mut().enumerate() {
        *x = 0.8 - 1.1 * k as f64;
    }
    let mut out = Vec::new();
    for k in 0..1000 {
        step(&model, &mut s, 1e-3).unwrap();
        if k % 100 == 99 {
            let o = s.outputs();
            for n in ["shoulder", "elbow"] {
                let j = def.joints.iter().position(|j| j.name == n).unwrap();
                out.push(o.joints[j].q[0]);
                out.push(o.joints[j].qd[0]);
            }
        }
    }
    out
}

#[test]
fn impossible_inertias_welded_into_a_possible_body_are_accepted() {
    let u = "welded_inertia.urdf";
    let (merged, m_out) = import(&text(u), u, &ImportOptions::default()).unwrap();
    let (kept, k_out) = import(&text(u), u, &KEEP).unwrap();
    merged.validate(u).unwrap();
    kept.validate(u).unwrap();
    for (notes, keep) in [(&m_out.notes, false), (&k_out.notes, true)] {
        let notes = notes.join("\n");
        for (link, welded) in [
            ("weight", "'upper', 'sensor'"),
            ("sensor", "'upper', 'weight'"),
            ("fore", "'hand'"),
        ] {
            assert!(
                notes.contains(&format!(
                    "link '{link}': its own inertia violates the triangle inequality"
                )) && notes.contains(&format!(
                    "accepted: it is welded by fixed joints to {welded}, and the rigid body they form is possible"
                )),
                "{link} (keep {keep}): {notes}"
            );
        }
        assert!(notes.contains("read as zero"), "{notes}");
        if keep {
            assert!(notes.contains("link 'weight': its own inertia violates the triangle inequality: principal moments 0.0001 + 0.0001 < 0.001, which no mass distribution has; accepted: it is welded by fixed joints to 'upper', 'sensor', and the rigid body they form is possible (kept as a massless body on its fixed joint; 'upper' carries its inertial)"), "{notes}");
            assert!(
                notes.contains("'fore' carries the inertials of the whole cluster"),
                "{notes}"
            );
        }
    }
    let body = |spec: &triad::spec::Spec, n: &str| {
        spec.body[spec.body.iter().position(|b| b.name == n).unwrap()].clone()
    };
    // kept: the impossible links are massless bodies, their hosts carry them
    assert_eq!(body(&kept, "weight").mass, 0.0);
    assert_eq!(body(&kept, "upper").mass, 2.5);
    assert_eq!(body(&kept, "sensor").mass, 0.001);
    assert_eq!(body(&kept, "hand").mass, 0.0);
    assert!((body(&kept, "fore").mass - 1.2).abs() < 1e-15);
    // the same rigid bodies: merged ones and the kept clusters have the same mass
    assert!((body(&merged, "upper").mass - 2.501).abs() < 1e-15);
    let a = welded_trajectory(&ImportOptions::default());
    let b = welded_trajectory(&KEEP);
    let d = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    eprintln!("merged vs kept over 1 s: {d:.2e}");
    assert!(d <= common::tol(1e-11), "{d:e}");
    // the command line says so too
    let tmp = tempfile::tempdir().unwrap();
    let path = data(u);
    for extra in [None, Some("--keep-fixed")] {
        let mut args = vec!["check", path.to_str().unwrap()];
        args.extend(extra);
        let (ok, out, err) = run(&args, tmp.path());
        assert!(ok, "{args:?}: {err}");
        assert!(
            out.contains("note: link 'weight': its own inertia"),
            "{out}"
        );
    }
}

#[test]
fn an_impossible_rigid_body_is_refused_naming_its_impossible_links() {
    let u = "welded_inertia.urdf";
    let bad = text(u).replace(
        "izz=\"0.001\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/>",
        "izz=\"10\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/>",
    );
    assert_ne!(bad, text(u));
    let want = "line 22: link \"weight\": <inertia> violates the triangle inequality: principal moments 0.0001 + 0.0001 < 10, which no mass distribution has; welded by fixed joints to \"upper\", \"sensor\", the rigid body they form is impossible too";
    for opts in [ImportOptions::default(), KEEP] {
        let e = import(&bad, u, &opts).unwrap_err().to_string();
        assert!(e.contains(want), "{e}");
        // the valid host is not blamed
        assert!(!e.contains("link \"upper\": <inertia>"), "{e}");
        assert!(!e.contains("link \"upper\" (body"), "{e}");
    }
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join(u), &bad).unwrap();
    for args in [
        vec!["import", u, "-o", "out.toml"],
        vec!["import", u, "--keep-fixed", "-o", "out.toml"],
        vec!["check", u],
        vec!["check", u, "--keep-fixed"],
        vec!["build", u, "--keep-fixed", "-o", "out.fmu"],
    ] {
        let (ok, _, err) = run(&args, tmp.path());
        assert!(!ok, "{args:?} accepted");
        assert!(err.contains(&format!("{u}: {want}")), "{args:?}: {err}");
        assert!(!tmp.path().join("out.toml").exists());
        assert!(!tmp.path().join("out.fmu").exists());
    }
    // a single link (welded to nothing) with an impossible inertia: refused on its <inertia> line
    let alone = text(u).replace(
        "<inertia ixx=\"0.05\" iyy=\"0.05\" izz=\"0.004\"",
        "<inertia ixx=\"0.05\" iyy=\"0.05\" izz=\"0.4\"",
    );
    let e = import(&alone, u, &ImportOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("line 14: link \"upper\": <inertia> violates the triangle inequality"),
        "{e}"
    );
}

/// Boundaries of the rule: a massless link without inertial, a link with zero inertia and an
/// impossible link welded to the world are all accepted, in both modes.
#[test]
fn legal_inputs_near_the_rule_are_accepted() {
    let u = "welded_inertia.urdf";
    // the sensor massless with a zero inertia, or without <inertial> (kept: a massless body)
    let zero = text(u).replace(
        "<mass value=\"0.001\"/>\n      <inertia ixx=\"1e-9\" iyy=\"1e-9\" izz=\"2.0000001e-9\"",
        "<mass value=\"0\"/>\n      <inertia ixx=\"0\" iyy=\"0\" izz=\"0\"",
    );
    let bare = text(u).replace(
        "<inertial>\n      <mass value=\"0.001\"/>\n      <inertia ixx=\"1e-9\" iyy=\"1e-9\" izz=\"2.0000001e-9\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/>\n    </inertial>",
        "",
    );
    assert!(zero != text(u) && bare != text(u));
    // the base (welded to the world) with an impossible inertia: it does not move
    let world = text(u).replace(
        "<inertial><mass value=\"1\"/><inertia ixx=\"0.01\" iyy=\"0.01\" izz=\"0.01\"",
        "<inertial><mass value=\"1\"/><inertia ixx=\"0.01\" iyy=\"0.01\" izz=\"0.05\"",
    );
    let world_kept = world.replace(
        "<joint name=\"shoulder\" type=\"revolute\">\n    <parent link=\"base_link\"/>",
        "<link name=\"post\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"3\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>\n  <joint name=\"post_joint\" type=\"fixed\"><parent link=\"base_link\"/><child link=\"post\"/></joint>\n  <joint name=\"shoulder\" type=\"revolute\">\n    <parent link=\"base_link\"/>",
    );
    assert_ne!(world_kept, world);
    for t in [&zero, &bare, &world, &world_kept] {
        for opts in [ImportOptions::default(), KEEP] {
            let (spec, out) = import(t, u, &opts).unwrap_or_else(|e| panic!("{e}"));
            spec.validate(u).unwrap_or_else(|e| panic!("{e}"));
            if t == &zero || t == &bare {
                assert!(!out.notes.join("\n").contains("link 'sensor'"));
            }
            // kept, the post is a body on a fixed joint to the world, massless
            if t == &world_kept && opts.keep_fixed {
                let notes = out.notes.join("\n");
                assert!(
                    notes.contains("link 'post': its inertia violates the triangle inequality"),
                    "{notes}"
                );
            }
        }
    }
}

#[test]
fn urdf_errors_carry_their_line() {
    let link = |n: &str| {
        format!("  <link name=\"{n}\">\n    <inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial>\n  </link>\n")
    };
    let joint = |n: &str, p: &str, c: &str| {
        format!("  <joint name=\"{n}\" type=\"revolute\">\n    <parent link=\"{p}\"/><child link=\"{c}\"/>\n    <axis xyz=\"0 1 0\"/>\n  </joint>\n")
    };
    let robot = |body: String| format!("<robot name=\"r\">\n{body}</robot>\n");
    // links on lines 2-4, 5-7, 8-10 (and 11-13); joints from line 11 (14) on, 4 lines each
    let ring = robot(format!(
        "{}{}{}{}{}{}",
        link("a"),
        link("b"),
        link("c"),
        joint("j1", "a", "b"),
        joint("j2", "b", "c"),
        joint("j3", "c", "a")
    ));
    let detached = robot(format!(
        "{}{}{}{}{}{}{}{}",
        link("a"),
        link("b"),
        link("c"),
        link("root"),
        joint("j0", "root", "a"),
        joint("j1", "b", "c"),
        joint("j2", "c", "b"),
        String::new()
    ));
    let triangle = robot(format!(
        "{}  <link name=\"b\">\n    <inertial>\n      <mass value=\"1\"/>\n      <inertia ixx=\"1\" iyy=\"1\" izz=\"3\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/>\n    </inertial>\n  </link>\n{}",
        link("a"),
        joint("j", "a", "b")
    ));
    let mimic = robot(format!(
        "{}{}  <joint name=\"j\" type=\"revolute\">\n    <parent link=\"a\"/><child link=\"b\"/>\n    <axis xyz=\"0 1 0\"/>\n    <mimic joint=\"nope\" multiplier=\"2\"/>\n  </joint>\n",
        link("a"),
        link("b")
    ));
    let cases = [
        ("ring", ring, "line 11: joint \"j1\": the joints form a cycle: joints \"j1\" (line 11), \"j2\" (line 15), \"j3\" (line 19) join links"),
        ("detached", detached, "line 18: joint \"j1\": the joints form a cycle: joints \"j1\" (line 18), \"j2\" (line 22) join links"),
        ("triangle", triangle, "line 8: link \"b\": <inertia> violates the triangle inequality"),
        ("mimic", mimic, "line 11: joint \"j\": <mimic joint=\"nope\">: there is no joint \"nope\""),
    ];
    let tmp = tempfile::tempdir().unwrap();
    for (name, text, want) in &cases {
        let file = format!("{name}.urdf");
        std::fs::write(tmp.path().join(&file), text).unwrap();
        for args in [
            vec!["import", &file, "-o", "out.toml"],
            vec!["import", &file, "--keep-fixed", "-o", "out.toml"],
            vec!["check", &file],
            vec!["simulate", &file, "--stop", "0.01", "-o", "out.csv"],
        ] {
            let (ok, _, err) = run(&args, tmp.path());
            assert!(!ok, "{name} {args:?}: accepted");
            assert!(
                err.contains(&format!("{file}: {want}")),
                "{name} {args:?}: expected {want:?} in\n{err}"
            );
            assert!(!tmp.path().join("out.toml").exists(), "{name}: wrote");
            assert!(!tmp.path().join("out.csv").exists(), "{name}: wrote");
        }
    }
}

#[test]
fn every_command_takes_the_import_options() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    std::fs::copy(data("free_box.urdf"), d.join("free_box.urdf")).unwrap();
    let u = "free_box.urdf";
    // without the option nothing moves, and the message names the option of this command
    let (ok, _, err) = run(&["check", u], d);
    assert!(!ok);
    // kept links welded to the world move no more than merged ones
    let welded = data("fixed_dynamics.urdf");
    let welded = std::fs::read_to_string(welded)
        .unwrap()
        .replace("type=\"revolute\"", "type=\"fixed\"");
    std::fs::write(d.join("welded.urdf"), welded).unwrap();
    for keep in [&[][..], &["--keep-fixed"][..]] {
        let mut args = vec!["check", "welded.urdf"];
        args.extend(keep);
        let (ok, _, e) = run(&args, d);
        assert!(!ok && e.contains("nothing moves"), "{args:?}: {e}");
    }
    assert!(
        err.contains("nothing moves: every link is welded to the world through root link 'box'; run the command again with --floating-base to free it"),
        "{err}"
    );
    let (ok, out, err) = run(&["check", u, "--floating-base"], d);
    assert!(ok, "{err}");
    assert!(out.contains("model free_box: 1 body, 0 joints"), "{out}");
    let (ok, out, err) = run(&["describe", "--floating-base", u], d);
    assert!(ok, "{err}");
    assert!(out.contains("body.box.r[3]"), "{out}");
    let (ok, _, err) = run(&["build", u, "--floating-base", "-o", "box.fmu"], d);
    assert!(ok, "{err}");
    assert!(d.join("box.fmu").is_file());
    let (ok, _, err) = run(
        &[
            "simulate",
            u,
            "--floating-base",
            "--stop",
            "0.5",
            "--step",
            "0.05",
            "-o",
            "box.csv",
        ],
        d,
    );
    assert!(ok, "{err}");
    // free fall: z = -g t^2 / 2
    let (header, rows) = read_csv(&d.join("box.csv"));
    let z = header.iter().position(|h| h == "body.box.r[3]").unwrap();
    let last = rows.last().unwrap();
    assert!((last[0] - 0.5).abs() < 1e-12);
    assert!((last[z] + 0.5 * 9.81 * 0.25).abs() < 1e-9, "{}", last[z]);
    // the replay: of another model without the option, accepted with it
    let (ok, _, err) = run(&["animate", u, "box.csv", "-o", "box.html"], d);
    assert!(!ok && err.contains("nothing moves"), "{err}");
    assert!(!d.join("box.html").exists());
    let (ok, _, err) = run(
        &["animate", u, "box.csv", "--floating-base", "-o", "box.html"],
        d,
    );
    assert!(ok, "{err}");
    assert!(d.join("box.html").is_file());
    // --keep-fixed and --no-limits as well, on each command; --fixed-base conflicts with
    // --floating-base
    let arm = data("arm.urdf");
    let arm = arm.to_str().unwrap();
    for cmd in ["check", "describe"] {
        let (ok, _, err) = run(
            &[cmd, arm, "--keep-fixed", "--no-limits", "--fixed-base"],
            d,
        );
        assert!(ok, "{cmd}: {err}");
    }
    let (ok, _, _) = run(&["check", arm, "--fixed-base", "--floating-base"], d);
    assert!(!ok);
    let (ok, out, _) = run(&["describe", arm, "--keep-fixed"], d);
    assert!(ok && out.contains("body.tool0.r[1]"), "{out}");
    let (ok, _, err) = run(
        &[
            "simulate",
            arm,
            "--keep-fixed",
            "--no-limits",
            "--stop",
            "0.05",
            "-o",
            "arm.csv",
        ],
        d,
    );
    assert!(ok, "{err}");
    let (ok, _, err) = run(
        &["animate", arm, "arm.csv", "--keep-fixed", "-o", "arm.html"],
        d,
    );
    assert!(ok, "{err}");
    // without the run's options: another model, and the message says what to give
    let (ok, _, err) = run(&["animate", arm, "arm.csv", "-o", "other.html"], d);
    assert!(
        !ok && err.contains("a .urdf is replayed as imported with the options of the run"),
        "{err}"
    );
    assert!(!d.join("other.html").exists());
    // not for a spec: refused, nothing written
    let (ok, _, err) = run(&["check", "double_pendulum", "--floating-base"], d);
    assert!(
        !ok && err.contains("--floating-base is for a .urdf MODEL only"),
        "{err}"
    );
    let spec = Path::new(env!("CARGO_MANIFEST_DIR")).join("modelDescription/pendulum/spec.toml");
    let (ok, _, err) = run(
        &[
            "build",
            spec.to_str().unwrap(),
            "--keep-fixed",
            "-o",
            "p.fmu",
        ],
        d,
    );
    assert!(
        !ok && err.contains("--keep-fixed is for a .urdf MODEL only"),
        "{err}"
    );
    assert!(!d.join("p.fmu").exists());
    // and --help says so
    for cmd in [
        "check", "describe", "simulate", "build", "animate", "import",
    ] {
        let (ok, out, _) = run(&[cmd, "--help"], d);
        assert!(ok);
        for opt in [
            "--floating-base",
            "--fixed-base",
            "--keep-fixed",
            "--no-limits",
        ] {
            assert!(out.contains(opt), "{cmd} --help lacks {opt}:\n{out}");
        }
    }
}
