//! `--contacts` (issue 31 item 5), on `tests/data/urdf/contacts.urdf`, a robot written to hold
//! every kind of `<collision>`:
//!
//! - spheres, boxes and cylinders become `[[collision]]` shapes of the same size on the body
//!   that carries their link, placed in its frame (a foot merged into its leg by a rotated fixed
//!   joint: `T_leg←shape = T_leg←foot ∘ origin`), named after their links (`tail.tip` →
//!   `tail_tip`, `tail_tip_2`); meshes, zero sizes and links welded to the world are left out,
//!   each kind with a note; a `[ground]` with the defaults is added;
//! - the written TOML says where each shape came from, and builds the same FMU as the URDF;
//! - every command that reads a URDF takes `--contacts`; a spec refuses it;
//! - dropped, the robot comes to rest on the ground: the vertical contact forces sum to its
//!   weight within 1 %, and `energy − work` stays constant to 1e-12 of the energy scale.

mod common;
use common::{read_csv, triad};
use std::path::{Path, PathBuf};
use triad::math::{rpy_to_matrix, Vec3};
use triad::urdf::{import, to_toml, ImportOptions};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/urdf/contacts.urdf")
}

const CONTACTS: ImportOptions = ImportOptions {
    base: triad::urdf::Base::Auto,
    keep_fixed: false,
    no_limits: false,
    no_friction: false,
    no_mimic: false,
    contacts: true,
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
fn collisions_become_shapes_on_their_host_bodies() {
    let text = std::fs::read_to_string(data()).unwrap();
    let (plain, _) = import(&text, "contacts.urdf", &ImportOptions::default()).unwrap();
    assert!(plain.collision.is_empty() && plain.ground.is_none());
    let (spec, out) = import(&text, "contacts.urdf", &CONTACTS).unwrap();
    spec.validate("contacts.urdf").unwrap();
    let names: Vec<_> = spec.collision_names();
    assert_eq!(names, ["body", "leg", "foot", "tail_tip", "tail_tip_2"]);
    let by = |n: &str| &spec.collision[names.iter().position(|m| m == n).unwrap()];
    assert_eq!(by("body").cuboid.unwrap().size, [0.3, 0.2, 0.1]);
    let leg = by("leg").cylinder.unwrap();
    assert_eq!((leg.radius, leg.length), (0.02, 0.2));
    assert_eq!(by("leg").origin.xyz, [0.0, 0.0, -0.1]);
    // the foot's sphere, merged into the leg: T_leg←foot ∘ origin
    let foot = by("foot");
    assert_eq!(
        (foot.body.as_str(), foot.sphere.unwrap().radius),
        ("leg", 0.03)
    );
    let r = rpy_to_matrix(&Vec3::new(0.0, 0.3, 0.0));
    let want = Vec3::new(0.0, 0.0, -0.2) + r * Vec3::new(0.01, 0.0, -0.01);
    assert!((Vec3::from(foot.origin.xyz) - want).norm() < 1e-15);
    assert!((rpy_to_matrix(&Vec3::from(foot.origin.rpy)) - r).amax() < 1e-15);
    assert_eq!(by("tail_tip_2").body, "tail_tip");
    // the ground: the defaults at height 0
    let g = spec.ground.unwrap();
    let law = triad::mechanics::ContactLaw::default();
    assert_eq!(
        (g.height, g.friction, g.stiffness, g.damping),
        (0.0, law.friction, law.stiffness, law.damping)
    );
    // what was left out, each kind once, with its lines
    let notes = out.notes.join("\n");
    for want in [
        "1 <collision> cylinder ('leg' (line 36)): cylinder shapes touch the ground",
        "1 <collision> mesh left out ('leg' (line 40))",
        "1 <collision> element of links welded to the world left out ('stand' (line 86))",
        "1 <collision> element of zero size left out ('leg' (line 41))",
    ] {
        assert!(notes.contains(want), "{want}\n{notes}");
    }
    assert_eq!(out.collisions.len(), 5);
    assert!(
        out.collisions[2].contains("link \"foot\" (line 53, merged into body leg)"),
        "{:?}",
        out.collisions
    );
    // the TOML says where every shape came from and reads back as the same spec
    let toml = to_toml(&spec, &out).unwrap();
    assert!(toml.contains("# The ground (--contacts)"), "{toml}");
    assert!(
        toml.contains("# URDF <collision> of link \"tail.tip\" (line 75)\n[[collision]]\nname = \"tail_tip_2\""),
        "{toml}"
    );
    let back = triad::spec::Spec::from_str(&toml, triad::spec::Format::Toml, "c.toml").unwrap();
    assert_eq!(back, spec);
}

#[test]
fn every_command_takes_contacts_and_the_spec_builds_the_same_fmu() {
    let tmp = tempfile::tempdir().unwrap();
    let urdf = data();
    let urdf = urdf.to_str().unwrap();
    for args in [
        vec!["import", urdf, "--contacts", "-o", "bot.toml"],
        vec!["build", urdf, "--contacts", "-o", "from_urdf.fmu"],
        vec!["build", "bot.toml", "-o", "from_toml.fmu"],
        vec![
            "simulate",
            urdf,
            "--contacts",
            "--stop",
            "0.1",
            "-o",
            "out.csv",
        ],
        vec!["animate", urdf, "out.csv", "--contacts", "-o", "out.html"],
    ] {
        let (ok, _, err) = run(&args, tmp.path());
        assert!(ok, "{args:?}: {err}");
    }
    let a = std::fs::read(tmp.path().join("from_urdf.fmu")).unwrap();
    let b = std::fs::read(tmp.path().join("from_toml.fmu")).unwrap();
    assert!(a == b, "the FMUs differ");
    let (ok, out, err) = run(&["check", urdf, "--contacts"], tmp.path());
    assert!(ok, "{err}");
    assert!(out.contains("note: 1 <collision> mesh left out"), "{out}");
    let (ok, table, _) = run(&["describe", urdf, "--contacts"], tmp.path());
    assert!(ok && table.contains("contact.foot.f[3]") && table.contains("ground.stiffness"));
    let (_, table, _) = run(&["describe", urdf], tmp.path());
    assert!(
        !table.contains("contact.") && !table.contains("ground."),
        "{table}"
    );
    // a spec takes no import options
    let (ok, _, err) = run(&["check", "bot.toml", "--contacts"], tmp.path());
    assert!(!ok && err.contains("--contacts"), "{err}");
}

#[test]
fn the_dropped_robot_rests_on_its_weight() {
    let tmp = tempfile::tempdir().unwrap();
    let urdf = data();
    let args = [
        "simulate",
        urdf.to_str().unwrap(),
        "--contacts",
        "--stop",
        "3",
        "--step",
        "0.01",
        "--max-step",
        "5e-4",
        "-o",
        "drop.csv",
    ];
    let (ok, _, err) = run(&args, tmp.path());
    assert!(ok, "{err}");
    let (head, rows) = read_csv(&tmp.path().join("drop.csv"));
    let col = |n: &str| head.iter().position(|h| h == n).unwrap();
    let (e, w) = (col("system.energy"), col("system.work"));
    let scale = rows.iter().map(|r| r[e].abs()).fold(0.0, f64::max);
    let drift = rows
        .iter()
        .map(|r| (r[e] - r[w] - (rows[0][e] - rows[0][w])).abs())
        .fold(0.0, f64::max);
    eprintln!("energy - work: {:.2e} of {scale:.3} J", drift);
    assert!(drift <= 1e-12 * scale, "{drift:e}");
    let weight = 2.6 * 9.81;
    let last = rows.last().unwrap();
    let fz: f64 = head
        .iter()
        .enumerate()
        .filter(|(_, h)| h.starts_with("contact.") && h.ends_with(".f[3]"))
        .map(|(i, _)| last[i])
        .sum();
    eprintln!("vertical contact forces {fz:.4} N, weight {weight:.4} N");
    assert!((fz - weight).abs() <= 0.01 * weight, "{fz} vs {weight}");
}
