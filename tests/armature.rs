//! Rotor inertia in joint space (`armature`): exact energy account, the integrator against the
//! minimal-coordinate dynamics, the closed form of a driven rotor, momenta of a floating base,
//! and bad values refused.

mod common;

use common::trees::{with_armature, ALL_KINDS, FLOATING, ROTOR};
use common::{spec_error, spec_model};
use triad::mechanics::{step, Model, Operating, State};

fn set_inputs(s: &mut State, u: &[f64]) {
    let n = s.inputs().len();
    s.inputs_mut().copy_from_slice(&u[..n]);
}

const U: [f64; 15] = [
    0.7, -1.2, 0.4, 0.9, -0.5, 0.3, 0.2, -0.1, 0.6, 0.25, -0.35, 0.15, 0.5, -0.2, 0.1,
];

/// `energy − work` is constant to round-off with rotors on every coordinate of every joint
/// kind, springs, dampers, stops, actuators and body loads, at both orders.
#[test]
fn energy_minus_work_is_exact_with_rotors() {
    for (name, text) in [("all kinds", ALL_KINDS), ("floating", FLOATING)] {
        for order in ["", "\norder = 4"] {
            let text =
                with_armature(text).replace("max_step = 1e-3", &format!("max_step = 1e-3{order}"));
            let (m, mut s) = spec_model(&text);
            set_inputs(&mut s, &U);
            let e0 = s.outputs().energy - s.outputs().work;
            let scale = s.outputs().energy.abs().max(1.0);
            let mut worst = 0.0_f64;
            for _ in 0..2000 {
                step(&m, &mut s, 2e-3).unwrap();
                let d = (s.outputs().energy - s.outputs().work - e0).abs();
                worst = worst.max(d);
            }
            eprintln!("{name}{order}: |Δ(E − W)| ≤ {worst:.2e} of {scale:.2e}");
            assert!(worst < 1e-11 * scale, "{name}{order}: {worst:e}");
        }
    }
}

/// The step's rotors are the continuous model's `a q̈`: the integrator's accelerations
/// (Richardson slope of one step) equal `tree_dynamics`' with the armature on its diagonal.
#[test]
fn rotors_accelerate_as_the_minimal_dynamics_says() {
    for (name, text) in [("all kinds", ALL_KINDS), ("floating", FLOATING)] {
        let text = with_armature(text);
        let (m, mut s) = spec_model(&text);
        set_inputs(&mut s, &U);
        let op = Operating::of(&m, &s).unwrap();
        let (acc, _) = op.dynamics.accelerations(&op.q, &op.nu, &op.u).unwrap();
        let slope = |h: f64| {
            let (m, mut s) = spec_model(&text);
            set_inputs(&mut s, &U);
            let v0 = Operating::of(&m, &s).unwrap().nu;
            step(&m, &mut s, h).unwrap();
            let v1 = Operating::of(&m, &s).unwrap().nu;
            v0.iter()
                .zip(&v1)
                .map(|(a, b)| (b - a) / h)
                .collect::<Vec<_>>()
        };
        let h = 4e-6;
        let (s1, s2) = (slope(h), slope(h / 2.0));
        let want: Vec<f64> = s1.iter().zip(&s2).map(|(a, b)| 2.0 * b - a).collect();
        let err = acc
            .iter()
            .zip(&want)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        let scale = want.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        eprintln!("{name}: |q̈ − integrator| = {err:.2e} of {scale:.2e}");
        assert!(err <= 1e-6 * scale, "{name}: {err:e} of {scale:e}");
        // and the rotors change the motion: without them the accelerations differ
        let (m0, mut s0) = spec_model(text.replace("armature = 0.35\n", "").as_str());
        set_inputs(&mut s0, &U);
        let op0 = Operating::of(&m0, &s0).unwrap();
        let (acc0, _) = op0.dynamics.accelerations(&op0.q, &op0.nu, &op0.u).unwrap();
        let moved = acc
            .iter()
            .zip(&acc0)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(
            moved > 1e-2 * scale,
            "{name}: the armature changed nothing ({moved:e})"
        );
    }
}

/// A rotor on a vertical axis without gravity, driven by a constant torque τ: the angle is
/// `τ t²/(2 (I + a))` (the body's inertia about the axis plus the armature) to the midpoint
/// rule's phase error on the body's turn (O(h²): 2e-7 here; the rotor's own coordinate is
/// integrated exactly), and `energy = work` exactly, the rotor's `½ a ω²` included.
#[test]
fn a_driven_rotor_turns_as_its_total_inertia_says() {
    let text = format!("{ROTOR}armature = 0.06\n");
    let (m, mut s): (Model, State) = spec_model(&text);
    s.inputs_mut()[0] = 0.5;
    for _ in 0..1000 {
        step(&m, &mut s, 1e-3).unwrap();
    }
    let q = s.outputs().joints[0].q[0];
    let qd = s.outputs().joints[0].qd[0];
    let want = 0.5 * 1.0 / (2.0 * (0.04 + 0.06));
    eprintln!("q = {q}, want {want}, qd = {qd}");
    assert!((q - want).abs() < 1e-6 * want, "{q} vs {want}");
    assert!((qd - 0.5 / 0.1).abs() < 1e-5, "{qd}");
    // without the rotor the same torque turns it 2.5 times as far
    assert!((q - 0.5 / (2.0 * 0.04)).abs() > 1.0);
    // energy ≈ ½ (I + a) q̇², and = the work τ Δq exactly
    let e = s.outputs().energy;
    assert!((e - 0.5 * 0.1 * qd * qd).abs() < 1e-5 * e, "{e}");
    assert!(
        (e - s.outputs().work).abs() < 1e-13 * e,
        "{e} {}",
        s.outputs().work
    );
}

/// On a floating base the rotors are internal: without gravity the linear and angular momenta
/// of the bodies stay what they were, to round-off.
#[test]
fn rotors_keep_the_momenta_of_a_floating_base() {
    let text =
        with_armature(FLOATING).replace("gravity = [0.0, 0.0, -9.81]", "gravity = [0.0, 0.0, 0.0]");
    let (m, mut s) = spec_model(&text);
    // joint torques only (internal); the body loads stay 0
    s.inputs_mut()[0] = 0.8;
    s.inputs_mut()[1] = -0.6;
    let (p0, l0) = (s.outputs().p, s.outputs().l);
    for _ in 0..2000 {
        step(&m, &mut s, 2e-3).unwrap();
    }
    let (dp, dl) = ((s.outputs().p - p0).norm(), (s.outputs().l - l0).norm());
    eprintln!("|Δp| = {dp:.2e}, |ΔL| = {dl:.2e}");
    assert!(dp < 1e-12 && dl < 1e-12, "{dp:e} {dl:e}");
}

/// Negative, non-finite or misplaced armatures are refused with the joint named.
#[test]
fn bad_armatures_are_refused() {
    for (bad, words) in [
        (
            ALL_KINDS.replace("name = \"j1\"", "name = \"j1\"\narmature = -1.0"),
            "armature",
        ),
        (
            ALL_KINDS.replace(
                "type = \"spherical\"",
                "type = \"spherical\"\narmature = 0.1",
            ),
            "spherical joints take no armature",
        ),
    ] {
        let err = spec_error(&bad);
        assert!(err.contains(words), "{words:?} not in {err:?}");
    }
}
