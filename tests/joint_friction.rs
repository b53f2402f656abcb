//! Coulomb joint friction (`friction`): a joint holds below its breakaway torque within the
//! bristle's creep bound and slides above it at the Coulomb force, `energy − work` stays exact
//! (the bristle's energy in the energy, its loss in the work), and what friction excludes is
//! refused by name.

mod common;

use common::trees::{ALL_KINDS, ROTOR};
use common::{spec_error, spec_model};
use triad::mechanics::{step, Model, State};

fn rotor(friction: f64) -> String {
    format!("{ROTOR}friction = {friction}\n")
}

fn run(m: &Model, s: &mut State, steps: usize) -> Vec<f64> {
    (0..steps)
        .map(|_| {
            step(m, s, 1e-3).unwrap();
            s.outputs().joints[0].q[0]
        })
        .collect()
}

/// Below breakaway (torque 0.3 against a limit of 0.5 N·m, applied at once) the joint holds:
/// the bristle deflects by τ/k = τ δ/C = 6e-5 rad (δ = 1e-4 rad); the first swing overshoots
/// towards the limit and slips by a fraction of δ (measured 3.7e-6 rad), then nothing moves:
/// |q| stays below δ, and the last second moves it by less than 1e-9 rad.
#[test]
fn a_joint_holds_below_breakaway() {
    let (m, mut s) = spec_model(&rotor(0.5));
    s.inputs_mut()[0] = 0.3;
    let q = run(&m, &mut s, 2000);
    let worst = q.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
    let drift = (q[1999] - q[999]).abs();
    eprintln!(
        "held: |q| ≤ {worst:.3e} rad, drift over the last second {drift:.2e} rad, end {:.4e}",
        q[1999]
    );
    assert!(worst <= 1e-4, "{worst:e}");
    assert!(drift < 1e-9, "{drift:e}");
    assert!((q[1999] - 0.3 * 1e-4 / 0.5).abs() < 1e-5, "{}", q[1999]);
}

/// Above it (torque 0.8) the joint slides at the Coulomb force: the angle after 1 s is that of
/// `(τ − C)/I` to 1 %, and friction's loss, counted in the work, keeps `energy − work` at
/// round-off while the friction took `C·q` of the input's work.
#[test]
fn a_joint_slides_above_breakaway_with_exact_energy() {
    let (m, mut s) = spec_model(&rotor(0.5));
    s.inputs_mut()[0] = 0.8;
    let e0 = s.outputs().energy - s.outputs().work;
    let mut worst = 0.0_f64;
    for _ in 0..1000 {
        step(&m, &mut s, 1e-3).unwrap();
        worst = worst.max((s.outputs().energy - s.outputs().work - e0).abs());
    }
    let q = s.outputs().joints[0].q[0];
    let want = 0.5 * (0.8 - 0.5) / 0.04;
    eprintln!(
        "slid: q = {q:.5} (Coulomb {want:.5}), |Δ(E − W)| ≤ {worst:.2e} of {:.3}",
        s.outputs().energy
    );
    assert!((q - want).abs() < 1e-2 * want, "{q} vs {want}");
    assert!(
        worst < 1e-13 * s.outputs().energy.max(1.0) * 10.0,
        "{worst:e}"
    );
    // the friction's loss is what the input did beyond the kinetic energy
    let lost = 0.8 * q - s.outputs().energy;
    assert!(
        (lost - 0.5 * q).abs() < 1e-2 * lost,
        "{lost} vs {}",
        0.5 * q
    );
}

/// Friction on every coordinate of every joint kind that takes it (the spherical joint's cone
/// included), with springs, dampers, rotors and inputs: `energy − work` constant to round-off at both orders while joints stick
/// and slip.
#[test]
fn energy_minus_work_is_exact_with_friction() {
    let mut text = String::new();
    for line in ALL_KINDS.lines() {
        text.push_str(line);
        text.push('\n');
        if line.starts_with("type = \"") && !line.contains("spherical") {
            text.push_str("friction = 0.4\narmature = 0.05\n");
        } else if line.contains("spherical") {
            // a spherical joint's friction is a cone on its relative rotation (no armature)
            text.push_str("friction = 0.4\n");
        }
    }
    for order in ["", "\norder = 4"] {
        let text = text.replace("max_step = 1e-3", &format!("max_step = 1e-3{order}"));
        let (m, mut s) = spec_model(&text);
        let n = s.inputs().len();
        let u = [
            0.7, -1.2, 0.4, 0.9, -0.5, 0.3, 0.2, -0.1, 0.6, 0.25, -0.35, 0.15, 0.5, -0.2, 0.1,
        ];
        s.inputs_mut().copy_from_slice(&u[..n]);
        let e0 = s.outputs().energy - s.outputs().work;
        let scale = s.outputs().energy.abs().max(1.0);
        let mut worst = 0.0_f64;
        for _ in 0..2000 {
            step(&m, &mut s, 2e-3).unwrap();
            worst = worst.max((s.outputs().energy - s.outputs().work - e0).abs());
        }
        eprintln!(
            "all kinds{order}: |Δ(E − W)| ≤ {worst:.2e} of {scale:.2e}, work {:.3}",
            s.outputs().work
        );
        assert!(worst < 1e-11 * scale, "{order}: {worst:e}");
    }
}

/// What friction rules out is refused by name: a negative value, a fixed joint's, and the
/// FMU's directional derivatives (its bristle is no FMU state; `triad linearize` has it).
#[test]
fn friction_refusals_are_named() {
    let bad = ALL_KINDS.replace("name = \"j1\"", "name = \"j1\"\nfriction = -1.0");
    let err = spec_error(&bad);
    assert!(err.contains("friction"), "{err}");
    let bad = rotor(0.1).replace("type = \"revolute\"", "type = \"fixed\"");
    let err = spec_error(&bad);
    assert!(err.contains("fixed joints take no friction"), "{err}");
    let (m, _) = spec_model(&rotor(0.5));
    let e = triad::mechanics::supported(m.def())
        .unwrap_err()
        .to_string();
    assert!(e.contains("Coulomb friction"), "{e}");
}
