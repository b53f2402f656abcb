//! Collision shapes that start below the ground (issue 35 item 4).
//!
//! - `check`, `build` (standard output) and `simulate` (standard error) warn of every shape whose
//!   gap `contact.C.gap = n·x − height − r` (lowest point) is below `−1e-9` m at the initial
//!   state, naming the shape, its body and the depth, and saying what moves it out; the exit
//!   status stays 0 (a start in contact is legal). A shape on the ground (gap within ±1e-9 m)
//!   gets no warning.
//! - `--on-ground` moves the floating base by `−min gap` along the ground normal, so the lowest
//!   shape's gap is 0 to 1e-12 m (every shape hangs from the base: a translation `δ n` adds `δ`
//!   to every gap); without a floating base or without `--contacts` it is refused, and a spec
//!   MODEL refuses it like every import option.

mod common;
use common::triad;
use std::path::{Path, PathBuf};
use triad::sim::Simulation;
use triad::urdf::{import, to_toml, Base, ImportOptions};

fn urdf(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/urdf")
        .join(name)
}

/// A ball (radius 0.1 m) and a box on a free body whose origin is at height `z`: the ball's
/// gap is `z − 0.1`, the box's (half height 0.05, 0.5 m above) `z + 0.45`.
fn ball(z: f64) -> String {
    format!(
        "name = \"Ball\"\n[[body]]\nname = \"ball\"\nmass = 1.0\ninertia = [0.004, 0.004, 0.004]\n\
         position = [0.0, 0.0, {z:?}]\n[ground]\n[solver]\nmax_step = 1e-4\n\
         [[collision]]\nname = \"foot\"\nbody = \"ball\"\nsphere = {{ radius = 0.1 }}\n\
         [[collision]]\nname = \"lid\"\nbody = \"ball\"\nbox = {{ size = [0.1, 0.1, 0.1] }}\n\
         origin = {{ xyz = [0.0, 0.0, 0.5] }}\n"
    )
}

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

/// The depth `check` reports for shape `name` ("'foot' on body 'ball': 0.1 m below").
fn reported_depth(text: &str, name: &str) -> Option<f64> {
    let line = text
        .lines()
        .find(|l| l.contains(&format!("'{name}' on body")))?;
    let at = line.find(": ")? + 2;
    line[at..].split(" m below").next()?.trim().parse().ok()
}

#[test]
fn check_build_and_simulate_warn_of_a_shape_below_the_ground() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("deep.toml"), ball(0.0)).unwrap();
    let (ok, out, _) = run(&["check", "deep.toml"], tmp.path());
    assert!(
        ok,
        "a start below the ground is a warning, not a problem: {out}"
    );
    assert!(
        out.contains("warning: 1 collision shape starts below the ground"),
        "{out}"
    );
    let depth = reported_depth(&out, "foot").expect("the shape, its body and depth");
    assert!((depth - 0.1).abs() < 1e-9, "{out}");
    assert!(
        reported_depth(&out, "lid").is_none(),
        "the lid is above: {out}"
    );
    for fix in [
        "lower [ground] height by at least 0.1 m (to -0.1 m or below)",
        "raise the initial `position` of free body 'ball' by 0.1 m",
    ] {
        assert!(out.contains(fix), "{fix}: {out}");
    }
    let (ok, out, err) = run(&["build", "deep.toml", "-o", "deep.fmu"], tmp.path());
    assert!(ok, "{err}");
    assert!(reported_depth(&out, "foot").is_some(), "build: {out}");
    let (ok, _, err) = run(
        &["simulate", "deep.toml", "--stop", "1e-3", "--step", "1e-3"],
        tmp.path(),
    );
    assert!(ok, "{err}");
    assert!(reported_depth(&err, "foot").is_some(), "simulate: {err}");
    // --set moves the ground: the warning follows the parameters of the run
    let (ok, _, err) = run(
        &[
            "simulate",
            "deep.toml",
            "--stop",
            "1e-3",
            "--step",
            "1e-3",
            "--set",
            "ground.height=-0.1",
        ],
        tmp.path(),
    );
    assert!(ok && !err.contains("below the ground"), "{err}");
}

#[test]
fn a_shape_on_the_ground_or_above_gets_no_warning() {
    let tmp = tempfile::tempdir().unwrap();
    // exactly on it, within 1e-9 m of it, above it
    for z in [0.1, 0.1 - 5e-10, 0.1 + 5e-10, 0.5] {
        std::fs::write(tmp.path().join("on.toml"), ball(z)).unwrap();
        let (ok, out, err) = run(&["check", "on.toml"], tmp.path());
        assert!(ok, "{err}");
        assert!(!out.contains("below the ground"), "z = {z}: {out}");
    }
    // 1e-8 m below is below
    std::fs::write(tmp.path().join("in.toml"), ball(0.1 - 1e-8)).unwrap();
    let (_, out, _) = run(&["check", "in.toml"], tmp.path());
    assert!(
        out.contains("'foot' on body 'ball': 1.00e-8 m below"),
        "{out}"
    );
}

/// The smallest initial gap of an imported robot, read from the mechanics.
fn lowest_gap(text: &str, opts: &ImportOptions) -> f64 {
    let (spec, _) = import(text, "robot.urdf", opts).unwrap();
    spec.validate("robot.urdf").unwrap();
    let (def, settings) = spec.lower().unwrap();
    let sim = Simulation::new(&def, settings, 0.0).unwrap();
    sim.state()
        .outputs()
        .contacts
        .iter()
        .map(|c| c.gap)
        .fold(f64::INFINITY, f64::min)
}

const ON_GROUND: ImportOptions = ImportOptions {
    base: Base::Auto,
    keep_fixed: false,
    no_limits: false,
    no_friction: false,
    no_mimic: false,
    contacts: true,
    on_ground: true,
};

#[test]
fn on_ground_rests_the_lowest_shape_on_the_ground() {
    // contacts.urdf: a floating joint puts the base 0.5 m up, the foot then 0.2 m above
    let text = std::fs::read_to_string(urdf("contacts.urdf")).unwrap();
    let plain = ImportOptions {
        on_ground: false,
        ..ON_GROUND
    };
    assert!(lowest_gap(&text, &plain) > 0.1);
    assert!(lowest_gap(&text, &ON_GROUND).abs() <= 1e-12);
    // the floating joint lower, the foot in the ground: raised
    let low = text.replace("<origin xyz=\"0 0 0.5\"/>", "<origin xyz=\"0 0 0.1\"/>");
    assert!(lowest_gap(&low, &plain) < -0.1);
    assert!(lowest_gap(&low, &ON_GROUND).abs() <= 1e-12);
    // the written spec carries the position and says why
    let (spec, outcome) = import(&low, "robot.urdf", &ON_GROUND).unwrap();
    let toml = to_toml(&spec, &outcome).unwrap();
    assert!(
        toml.contains("# position: raised by") && toml.contains("rests on the ground (gap 0)"),
        "{toml}"
    );
    let base = spec.body.iter().find(|b| b.name == "body").unwrap();
    assert!(base.position.unwrap()[2] > 0.1);
}

#[test]
fn on_ground_through_the_command_line() {
    let tmp = tempfile::tempdir().unwrap();
    let model = urdf("contacts.urdf");
    let model = model.to_str().unwrap();
    let (ok, csv, err) = run(
        &[
            "simulate",
            model,
            "--contacts",
            "--on-ground",
            "--stop",
            "1e-3",
            "--step",
            "1e-3",
            "--outputs",
            "contact.*.gap",
        ],
        tmp.path(),
    );
    assert!(ok, "{err}");
    assert!(!err.contains("below the ground"), "{err}");
    let first: Vec<f64> = csv
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .skip(1)
        .map(|x| x.parse().unwrap())
        .collect();
    let lowest = first.iter().copied().fold(f64::INFINITY, f64::min);
    assert!(lowest.abs() <= 1e-12, "{csv}");
    let (ok, toml, err) = run(&["import", model, "--contacts", "--on-ground"], tmp.path());
    assert!(ok, "{err}");
    assert!(
        toml.contains("# note: --on-ground: the floating base 'body' starts at position"),
        "{toml}"
    );
}

#[test]
fn on_ground_needs_a_floating_base_and_contacts() {
    let tmp = tempfile::tempdir().unwrap();
    let arm = urdf("arm.urdf");
    let arm = arm.to_str().unwrap();
    let (ok, _, err) = run(&["check", arm, "--contacts", "--on-ground"], tmp.path());
    assert!(!ok);
    assert!(
        err.contains("--on-ground: places a floating base, and this robot's base is welded to the world: add --floating-base"),
        "{err}"
    );
    let (ok, _, err) = run(
        &["check", arm, "--contacts", "--on-ground", "--fixed-base"],
        tmp.path(),
    );
    assert!(!ok && err.contains("drop --fixed-base"), "{err}");
    let bot = urdf("contacts.urdf");
    let (ok, _, err) = run(
        &["import", bot.to_str().unwrap(), "--on-ground"],
        tmp.path(),
    );
    assert!(!ok);
    assert!(
        err.contains(
            "--on-ground: rests the robot's collision shapes on the ground: it needs --contacts"
        ),
        "{err}"
    );
    // a spec takes no import option
    std::fs::write(tmp.path().join("ball.toml"), ball(0.5)).unwrap();
    let (ok, _, err) = run(&["check", "ball.toml", "--on-ground"], tmp.path());
    assert!(
        !ok && err.contains("--on-ground is for a .urdf MODEL only"),
        "{err}"
    );
    // every command that takes the import options lists it
    for command in [
        "check", "describe", "simulate", "build", "import", "animate",
    ] {
        let (_, help, _) = run(&[command, "--help"], tmp.path());
        assert!(help.contains("--on-ground"), "{command} --help");
    }
}

/// ANYmal C from example-robot-data (`$TRIAD_ANYMAL_URDF`, else in the project's `.venv`), the
/// robot of the issue: the base at the origin puts 43 of 45 shapes below the ground.
fn anymal() -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("TRIAD_ANYMAL_URDF") {
        return Some(PathBuf::from(p));
    }
    let lib = Path::new(env!("CARGO_MANIFEST_DIR")).join(".venv/lib");
    std::fs::read_dir(lib).ok()?.flatten().find_map(|py| {
        let p = py.path().join(
            "site-packages/cmeel.prefix/share/example-robot-data/robots/anymal_c_simple_description/urdf/anymal.urdf",
        );
        p.is_file().then_some(p)
    })
}

#[test]
fn anymal_is_warned_of_and_placed_on_the_ground() {
    let Some(path) = anymal() else {
        eprintln!("skipped: example-robot-data's anymal.urdf not found");
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let model = path.to_str().unwrap();
    let (ok, out, err) = run(
        &["check", model, "--floating-base", "--contacts"],
        tmp.path(),
    );
    assert!(ok, "{err}");
    assert!(
        out.contains("collision shapes start below the ground"),
        "{out}"
    );
    assert!(out.contains("import with --on-ground"), "{out}");
    let text = std::fs::read_to_string(&path).unwrap();
    let opts = ImportOptions {
        base: Base::Floating,
        ..ON_GROUND
    };
    assert!(lowest_gap(&text, &opts).abs() <= 1e-12);
    let (ok, out, err) = run(
        &[
            "check",
            model,
            "--floating-base",
            "--contacts",
            "--on-ground",
        ],
        tmp.path(),
    );
    assert!(ok && !out.contains("below the ground"), "{out}{err}");
}
