//! The contact part of the spec (`[ground]`, `[[collision]]`, `[[contact_pair]]`,
//! `self_collision`): every mistake is reported with its path and nothing is built; a contact
//! that fixed steps do not resolve gets a warning from `check`; the FMU's contact variables
//! and ground parameters.

mod common;
use common::triad;
use triad::spec::{Format, Spec};

const BASE: &str = "name = \"M\"\n[[body]]\nname = \"a\"\nmass = 1.0\ninertia = [0.01, 0.01, 0.01]\nposition = [0.0, 0.0, 1.0]\n\
    [[body]]\nname = \"b\"\nmass = 1.0\ninertia = [0.01, 0.01, 0.01]\nposition = [1.0, 0.0, 1.0]\n";

fn problems(extra: &str) -> String {
    match Spec::from_str(&format!("{BASE}{extra}"), Format::Toml, "m.toml") {
        Ok(_) => String::new(),
        Err(e) => e.to_string(),
    }
}

#[test]
fn every_contact_mistake_is_named_with_its_path() {
    for (extra, want) in [
        ("[ground]\nstiffness = 0.0\n", "ground.stiffness: must be > 0"),
        ("[ground]\nfriction = -0.1\n", "ground.friction: must be >= 0"),
        ("[ground]\ndamping = nan\n", "ground.damping: must be finite"),
        ("[ground]\nheight = inf\n", "ground.height: must be finite"),
        ("[[collision]]\nbody = \"a\"\n", "collision[0]: give exactly one of sphere, capsule, box, cylinder"),
        ("[[collision]]\nbody = \"a\"\nsphere = { radius = 0.1 }\nbox = { size = [1.0, 1.0, 1.0] }\n", "collision[0]: give exactly one"),
        ("[[collision]]\nbody = \"c\"\nsphere = { radius = 0.1 }\n", "collision[0].body: no body named \"c\""),
        ("[[collision]]\nbody = \"world\"\nsphere = { radius = 0.1 }\n", "collision[0].body: a collision shape must be fixed on a body"),
        ("[[collision]]\nbody = \"a\"\nsphere = { radius = -0.1 }\n", "collision[0].sphere: sizes must be finite and > 0"),
        ("[[collision]]\nbody = \"a\"\ncapsule = { radius = 0.1, length = -1.0 }\n", "collision[0].capsule: radius must be > 0 and length >= 0"),
        ("[[collision]]\nbody = \"a\"\nbox = { size = [0.1, 0.0, 0.1] }\n", "collision[0].box: sizes must be finite and > 0"),
        ("[[collision]]\nbody = \"a\"\nsphere = { radius = 0.1 }\nstiffness = -5.0\n", "collision[0].stiffness: must be > 0"),
        ("[[collision]]\nname = \"x\"\nbody = \"a\"\nsphere = { radius = 0.1 }\n[[collision]]\nname = \"x\"\nbody = \"b\"\nsphere = { radius = 0.1 }\n", "collision[1].name: duplicate collision name \"x\""),
        ("[[collision]]\nname = \"1x\"\nbody = \"a\"\nsphere = { radius = 0.1 }\n", "collision[0].name: \"1x\" is not an identifier"),
        ("[[collision]]\nbody = \"a\"\nsphere = { radius = 0.1 }\n[[contact_pair]]\na = \"a_1\"\nb = \"b_7\"\n", "contact_pair[0].b: no collision shape named \"b_7\""),
        ("[[collision]]\nbody = \"a\"\nsphere = { radius = 0.1 }\n[[collision]]\nbody = \"a\"\nsphere = { radius = 0.2 }\n[[contact_pair]]\na = \"a_1\"\nb = \"a_2\"\n", "are on the same body \"a\""),
        ("[[collision]]\nbody = \"a\"\ncylinder = { radius = 0.1, length = 0.2 }\n[[collision]]\nbody = \"b\"\nsphere = { radius = 0.2 }\n[[contact_pair]]\na = \"a_1\"\nb = \"b_1\"\n", "a cylinder touches the ground only"),
        ("[[collision]]\nbody = \"a\"\nsphere = { radius = 0.1 }\n[[collision]]\nbody = \"b\"\nsphere = { radius = 0.2 }\n[[contact_pair]]\na = \"a_1\"\nb = \"b_1\"\n[[contact_pair]]\na = \"b_1\"\nb = \"a_1\"\n", "contact_pair[1]: the pair \"b_1\", \"a_1\" is listed twice"),
        ("[[collision]]\nbody = \"a\"\ncone = { radius = 0.1 }\n", "collision[0].cone: unknown field"),
    ] {
        let got = problems(extra);
        assert!(got.contains(want), "{extra}\nwanted: {want}\ngot: {got}");
    }
    // and a correct one
    assert_eq!(
        problems("[ground]\n[[collision]]\nbody = \"a\"\nsphere = { radius = 0.1 }\n"),
        ""
    );
}

#[test]
fn check_warns_when_fixed_steps_do_not_resolve_a_contact() {
    let tmp = tempfile::tempdir().unwrap();
    let stiff = format!("{BASE}[solver]\nmax_step = 1e-2\n[ground]\nstiffness = 1e6\n[[collision]]\nbody = \"a\"\nsphere = {{ radius = 0.1 }}\n");
    std::fs::write(tmp.path().join("stiff.toml"), &stiff).unwrap();
    let out = triad(&["check", "stiff.toml"], tmp.path());
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("does not resolve the contact of collision shape 'a_1'"),
        "{text}"
    );
    // error control, or a small enough step: no warning
    for fix in ["rtol = 1e-6", "max_step = 1e-4"] {
        let text2 = stiff.replace("max_step = 1e-2", fix);
        std::fs::write(tmp.path().join("ok.toml"), text2).unwrap();
        let out = triad(&["check", "ok.toml"], tmp.path());
        assert!(
            !String::from_utf8_lossy(&out.stdout).contains("does not resolve"),
            "{fix}"
        );
    }
}

#[test]
fn the_fmu_reads_contact_outputs_and_takes_ground_parameters() {
    let tmp = tempfile::tempdir().unwrap();
    let spec =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/specs/bouncing_ball.toml");
    let out = triad(&["describe", spec.to_str().unwrap()], tmp.path());
    let text = String::from_utf8_lossy(&out.stdout);
    for name in [
        "contact.shell.f[3]",
        "contact.shell.gap",
        "ground.height",
        "ground.friction",
        "ground.stiffness",
        "ground.damping",
    ] {
        assert!(
            text.lines().any(|l| l.starts_with(name)),
            "{name} missing:\n{text}"
        );
    }
    // a ground parameter set like any other: ice (no friction) lets the ball slide on
    let run = |set: &str| {
        let out = triad(
            &[
                "simulate",
                spec.to_str().unwrap(),
                "--stop",
                "2",
                "--set",
                set,
                "--outputs",
                "body.ball.w[2]",
            ],
            tmp.path(),
        );
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let csv = String::from_utf8(out.stdout).unwrap();
        csv.lines()
            .last()
            .unwrap()
            .split(',')
            .nth(1)
            .unwrap()
            .parse::<f64>()
            .unwrap()
    };
    let spin_ice = run("ground.friction=0");
    let spin_rubber = run("ground.friction=1");
    assert!(
        (spin_ice + 5.0).abs() < 1e-9,
        "without friction the spin stays: {spin_ice}"
    );
    assert!((spin_rubber - 5.714).abs() < 0.01, "rolling: {spin_rubber}");
    // out of range: refused like fmi2SetReal
    let out = triad(
        &[
            "simulate",
            spec.to_str().unwrap(),
            "--set",
            "ground.stiffness=-1",
            "-o",
            "x.csv",
        ],
        tmp.path(),
    );
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("ground.stiffness"));
}
