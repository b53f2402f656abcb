//! Actuator gears and gains as FMU parameters: `actuator.A.gear` (fixed before initialisation),
//! `actuator.A.kp` (position servos) and `actuator.A.kv` (position and velocity servos), tunable
//! between steps as `joint.J.damping` is.
//!
//! The servo's force acts through the coordinate's exact discrete gradient and its work over a
//! step is `τ Δq` whatever the gains are, so `energy − work` stays at round-off when kp and kv
//! change between steps: that is the decisive check (a gain held in the model instead of the
//! state, or read at another point than the work, would show as a jump of `E − W` at the
//! change). A gain set through `fmi2SetReal` between steps gives the same run as the same gain
//! set on the state; bad values are refused by name with nothing changed; a restored FMU state
//! brings its gains back.

mod common;
mod fmu_support;

use common::spec_model;
use fmu_support::*;
use triad::ffi::common::*;
use triad::ffi::state::*;
use triad::ffi::types::*;
use triad::mechanics::{step, State};
use triad::variables::{Causality, Variability};

/// A cart on a rail carrying a rod on a hinge, a position servo on each and a velocity servo
/// on the hinge too, released off rest under gravity.
const SERVOS: &str = r#"
name = "Servos"
gravity = [0.0, 0.0, -9.81]
[solver]
max_step = 0.02
order = 4
[[body]]
name = "cart"
mass = 2.0
inertia = [0.02, 0.03, 0.04]
[[body]]
name = "rod"
mass = 1.0
com = [0.0, 0.0, -0.5]
inertia = [0.083, 0.083, 1e-4]
[[joint]]
name = "rail"
type = "prismatic"
parent = "world"
child = "cart"
axis = [1.0, 0.0, 0.0]
initial = { q = 0.1, qd = -0.3 }
[[joint]]
name = "hinge"
type = "revolute"
parent = "cart"
child = "rod"
axis = [0.0, 1.0, 0.0]
initial = { q = 0.8, qd = 1.5 }
[[actuator]]
name = "p_rail"
joint = "rail"
kind = "position"
gear = 0.5
kp = 40.0
kv = 3.0
[[actuator]]
name = "p_hinge"
joint = "hinge"
kind = "position"
gear = -2.0
kp = 10.0
kv = 0.5
forcerange = [-3.0, 3.0]
[[actuator]]
name = "v_hinge"
joint = "hinge"
kind = "velocity"
kv = 0.8
"#;

/// The gains the runs switch to, step by step: `(actuator, k, value)`, k = 0 for kp, 1 for kv
/// (once: switching stiffness periodically would pump energy in, parametrically, as a swing).
fn schedule(i: usize) -> &'static [(usize, usize, f64)] {
    match i {
        10 => &[(0, 0, 400.0), (1, 1, 0.0)],
        20 => &[(0, 1, 0.0), (2, 1, 5.0)],
        30 => &[(1, 0, 60.0), (0, 0, 5.0)],
        40 => &[(0, 1, 8.0), (1, 1, 2.0), (2, 1, 0.0)],
        _ => &[],
    }
}

fn controls(s: &mut State) {
    s.inputs_mut().copy_from_slice(&[0.4, -0.6, 1.0]);
}

/// Gains changed at steps 10, 20, 30 and 40 of 500 at a step of 0.02 s (order 4):
/// `energy − work` moves by at most 1e-14 of the largest energy or work met, while the servos
/// do work of the order of the energy, and the changes do change the motion.
#[test]
fn energy_minus_work_at_round_off_when_gains_change_between_steps() {
    let (m, mut s) = spec_model(SERVOS);
    controls(&mut s);
    let (m_fixed, mut fixed) = spec_model(SERVOS);
    controls(&mut fixed);
    let e0 = s.outputs().energy - s.outputs().work;
    let (mut worst, mut scale) = (0.0_f64, s.outputs().energy.abs());
    for i in 0..500 {
        for &(a, k, v) in schedule(i) {
            s.set_gain(a, k, v);
        }
        step(&m, &mut s, 0.02).unwrap_or_else(|e| panic!("step {i}: {e}"));
        step(&m_fixed, &mut fixed, 0.02).unwrap();
        worst = worst.max((s.outputs().energy - s.outputs().work - e0).abs());
        scale = scale
            .max(s.outputs().energy.abs())
            .max(s.outputs().work.abs());
    }
    let (q, q_fixed) = (s.outputs().joints[0].q[0], fixed.outputs().joints[0].q[0]);
    eprintln!(
        "|Δ(E − W)| ≤ {:.1e} of the scale {scale:.2} J; work {:.3} J; rail {q} (fixed gains {q_fixed})",
        worst / scale,
        s.outputs().work
    );
    assert!(worst / scale < 1e-14, "{:e}", worst / scale);
    assert!(s.outputs().work.abs() > 0.1, "the servos did no work");
    assert!((q - q_fixed).abs() > 1e-3, "the gains changed nothing");
    assert_eq!(s.gains(0), [5.0, 8.0]);
    assert_eq!(s.gains(2), [0.0, 0.0]);
}

/// The parameters are in the table with their units, variability and start values; a motor
/// has only its gear.
#[test]
fn the_parameters_and_their_attributes() {
    let motor = SERVOS.replace(
        "name = \"v_hinge\"\njoint = \"hinge\"\nkind = \"velocity\"\nkv = 0.8",
        "name = \"m_hinge\"\njoint = \"hinge\"\nkind = \"motor\"\ngear = 3.0",
    );
    let m = TestModel::new(&motor);
    let find = |name: &str| m.table.vars.iter().find(|v| v.name == name);
    for (name, unit, variability, start) in [
        ("actuator.p_rail.gear", "1", Variability::Fixed, 0.5),
        ("actuator.p_rail.kp", "N/m", Variability::Tunable, 40.0),
        ("actuator.p_rail.kv", "N.s/m", Variability::Tunable, 3.0),
        ("actuator.p_hinge.gear", "1", Variability::Fixed, -2.0),
        ("actuator.p_hinge.kp", "N.m/rad", Variability::Tunable, 10.0),
        (
            "actuator.p_hinge.kv",
            "N.m.s/rad",
            Variability::Tunable,
            0.5,
        ),
        ("actuator.m_hinge.gear", "1", Variability::Fixed, 3.0),
    ] {
        let v = find(name).unwrap_or_else(|| panic!("no {name}"));
        assert_eq!(v.causality, Causality::Parameter, "{name}");
        assert_eq!(v.variability, variability, "{name}");
        assert_eq!(v.unit, Some(unit), "{name}");
        assert_eq!(v.start, Some(start), "{name}");
        assert!(!v.description.is_empty(), "{name}");
    }
    assert!(find("actuator.m_hinge.kp").is_none() && find("actuator.m_hinge.kv").is_none());
    let velocity = TestModel::new(SERVOS);
    let has = |name: &str| velocity.table.vars.iter().any(|v| v.name == name);
    assert!(has("actuator.v_hinge.kv") && !has("actuator.v_hinge.kp"));
}

/// Through the FMI 2 interface: gains set between steps give the run of the same gains set on
/// the state, bit for bit; bad values are refused by name and change nothing; the gear is
/// fixed after initialisation; a restored FMU state brings its gains back.
#[test]
fn tunable_through_the_fmu_refused_out_of_range_and_restored() {
    let m = TestModel::new(SERVOS);
    let f = Fmu::new(&m);
    let gear = m.vr("actuator.p_rail.gear");
    assert_eq!(f.set_real(&[gear], &[0.0]), fmi2Error);
    assert!(
        f.last_message().contains("actuator.p_rail.gear"),
        "{}",
        f.last_message()
    );
    assert_eq!(f.set_real(&[gear], &[0.25]), fmi2OK);
    assert_eq!(f.setup(0.0), fmi2OK);
    assert_eq!(unsafe { fmi2EnterInitializationMode(f.c) }, fmi2OK);
    assert_eq!(unsafe { fmi2ExitInitializationMode(f.c) }, fmi2OK);
    let ctrl = [
        "actuator.p_rail.ctrl",
        "actuator.p_hinge.ctrl",
        "actuator.v_hinge.ctrl",
    ]
    .map(|n| m.vr(n));
    assert_eq!(f.set_real(&ctrl, &[0.4, -0.6, 1.0]), fmi2OK);
    // the same run on the state directly, gear 0.25
    let (mm, mut s) = spec_model(&SERVOS.replace("gear = 0.5", "gear = 0.25"));
    controls(&mut s);
    let names = ["p_rail", "p_hinge", "v_hinge"];
    let q = m.vr("joint.rail.q");
    let mut t = 0.0;
    let mut saved: fmi2FMUstate = std::ptr::null_mut();
    let mut at_save = (0.0, Vec::new());
    for i in 0..100 {
        for &(a, k, v) in schedule(i) {
            let name = format!("actuator.{}.{}", names[a], ["kp", "kv"][k]);
            assert_eq!(f.set_real(&[m.vr(&name)], &[v]), fmi2OK, "{name}");
            assert_eq!(f.get_real(&[m.vr(&name)]).1, vec![v], "{name}");
            s.set_gain(a, k, v);
        }
        if i == 15 {
            assert_eq!(unsafe { fmi2GetFMUstate(f.c, &mut saved) }, fmi2OK);
            at_save = (t, f.get_real(&[m.vr("actuator.p_rail.kp")]).1);
        }
        assert_eq!(f.step(t, 0.02), fmi2OK, "{:?}", f.messages());
        step(&mm, &mut s, 0.02).unwrap();
        t += 0.02;
        assert_eq!(
            f.get_real(&[q]).1[0],
            s.outputs().joints[0].q[0],
            "step {i}"
        );
    }
    // out of range: refused by name, nothing changed (not even the good value set with it)
    let (kp, kv) = (m.vr("actuator.p_hinge.kp"), m.vr("actuator.p_hinge.kv"));
    let before = f.get_real(&[kp, kv]).1;
    for (vrs, values, name) in [
        (vec![kp], vec![-1.0], "actuator.p_hinge.kp"),
        (vec![kv, kp], vec![7.0, f64::NAN], "actuator.p_hinge.kp"),
        (vec![kp, kv], vec![7.0, -0.1], "actuator.p_hinge.kv"),
    ] {
        assert_eq!(f.set_real(&vrs, &values), fmi2Error, "{name}");
        assert!(f.last_message().contains(name), "{}", f.last_message());
        assert_eq!(f.get_real(&[kp, kv]).1, before);
    }
    assert_eq!(f.set_real(&[gear], &[1.0]), fmi2Error, "gear is fixed");
    assert!(
        f.last_message().contains("fixed parameter"),
        "{}",
        f.last_message()
    );
    // restoring the saved state brings back its gains, and the run from there is the same
    assert_eq!(unsafe { fmi2SetFMUstate(f.c, saved) }, fmi2OK);
    assert_eq!(f.get_real(&[m.vr("actuator.p_rail.kp")]).1, at_save.1);
    assert_eq!(unsafe { fmi2FreeFMUstate(f.c, &mut saved) }, fmi2OK);
}

/// The linear models read the state's gains: a position servo on a free rotor, kp and kv set
/// on the state, gives `A = [[0, 1], [−g² kp / I, −g² kv / I]]`, `B = [0, g kp / I]` with the
/// new gains, to round-off.
#[test]
fn the_linear_model_uses_the_tuned_gains() {
    let text = "name = \"Servo\"\ngravity = [0.0, 0.0, 0.0]\n[[body]]\nname = \"r\"\nmass = 1.0\n\
                inertia = [0.5, 0.5, 0.5]\n[[joint]]\nname = \"spin\"\ntype = \"revolute\"\nparent = \"world\"\n\
                child = \"r\"\naxis = [0.0, 0.0, 1.0]\n[[actuator]]\nname = \"a\"\njoint = \"spin\"\n\
                kind = \"position\"\ngear = 2.0\nkp = 30.0\nkv = 4.0\n";
    let (m, mut s) = spec_model(text);
    let (g, kp, kv, i) = (2.0, 55.0, 1.5, 0.5);
    s.set_gain(0, 0, kp);
    s.set_gain(0, 1, kv);
    let lin = triad::mechanics::Operating::of(&m, &s)
        .unwrap()
        .linearize(&[])
        .unwrap();
    let want_a = [[0.0, 1.0], [-g * g * kp / i, -g * g * kv / i]];
    for (r, row) in want_a.iter().enumerate() {
        for (c, want) in row.iter().enumerate() {
            assert!((lin.a[(r, c)] - want).abs() < 1e-12, "A {r} {c}: {}", lin.a);
        }
    }
    assert!((lin.b[(1, 0)] - g * kp / i).abs() < 1e-12, "B {}", lin.b);
}

/// A joint's `actuatorfrcrange` is a pair of fixed parameters, `joint.J.actuatorfrcrange[1]`
/// and `[2]`: set before initialisation they give the run of the spec with that range, bit for
/// bit; either end may be set first (lo < hi is checked when the model is built, at
/// `fmi2EnterInitializationMode`, and an inverted range is refused there); a NaN is refused
/// at once, by name.
#[test]
fn the_actuator_force_range_is_a_fixed_parameter() {
    let rotor = |range: &str| {
        format!(
            "name = \"Rotor\"\ngravity = [0.0, 0.0, 0.0]\n[solver]\nmax_step = 0.05\n\
             [[body]]\nname = \"r\"\nmass = 1.0\n\
             inertia = [0.5, 0.5, 0.5]\n[[joint]]\nname = \"spin\"\ntype = \"revolute\"\n\
             parent = \"world\"\nchild = \"r\"\naxis = [0.0, 0.0, 1.0]\n\
             actuatorfrcrange = {range}\n[[actuator]]\nname = \"a\"\njoint = \"spin\"\n\
             kind = \"motor\"\ngear = 2.0\n"
        )
    };
    let m = TestModel::new(&rotor("[-0.3, 0.8]"));
    let (lo, hi) = (
        m.vr("joint.spin.actuatorfrcrange[1]"),
        m.vr("joint.spin.actuatorfrcrange[2]"),
    );
    for (name, start) in [
        ("joint.spin.actuatorfrcrange[1]", -0.3),
        ("joint.spin.actuatorfrcrange[2]", 0.8),
    ] {
        let v = m.table.vars.iter().find(|v| v.name == name).unwrap();
        assert_eq!(v.causality, Causality::Parameter, "{name}");
        assert_eq!(v.variability, Variability::Fixed, "{name}");
        assert_eq!((v.unit, v.start), (Some("N.m"), Some(start)), "{name}");
    }
    let ctrl = m.vr("actuator.a.ctrl");
    let q = m.vr("joint.spin.q");
    // the new range [0.9, 1.2] set upper end first, then lower: legal in either order
    for order in [[hi, lo], [lo, hi]] {
        let f = Fmu::new(&m);
        for vr in order {
            let v = if vr == lo { 0.9 } else { 1.2 };
            assert_eq!(f.set_real(&[vr], &[v]), fmi2OK, "{:?}", f.messages());
        }
        assert_eq!(f.setup(0.0), fmi2OK);
        assert_eq!(unsafe { fmi2EnterInitializationMode(f.c) }, fmi2OK);
        assert_eq!(unsafe { fmi2ExitInitializationMode(f.c) }, fmi2OK);
        assert_eq!(f.get_real(&[lo, hi]).1, vec![0.9, 1.2]);
        let (mm, mut s) = spec_model(&rotor("[0.9, 1.2]"));
        assert_eq!(f.set_real(&[ctrl], &[0.2]), fmi2OK);
        s.inputs_mut().copy_from_slice(&[0.2]);
        for i in 0..20 {
            assert_eq!(f.step(0.05 * f64::from(i), 0.05), fmi2OK);
            step(&mm, &mut s, 0.05).unwrap();
        }
        // 2·0.2 = 0.4 N·m is below the range: 0.9 N·m acts
        let got = f.get_real(&[q]).1[0];
        assert_eq!(got, s.outputs().joints[0].q[0]);
        // q ≈ ½ (τ / I) t² = 0.9 rad at t = 1 s (the step's error is O((hω)²): 4e-4 here),
        // against 0.4 rad for the unclamped 0.4 N·m
        assert!((got - 0.5 * 0.9 / 0.5).abs() < 1e-3, "{got}");
    }
    // a NaN is refused by name, an inverted range when the model is built
    let f = Fmu::new(&m);
    assert_eq!(f.set_real(&[lo], &[f64::NAN]), fmi2Error);
    assert!(
        f.last_message().contains("joint.spin.actuatorfrcrange[1]"),
        "{}",
        f.last_message()
    );
    assert_eq!(f.set_real(&[lo], &[1.0]), fmi2OK);
    assert_eq!(f.setup(0.0), fmi2OK);
    // the model is built when initialisation starts
    assert_eq!(unsafe { fmi2EnterInitializationMode(f.c) }, fmi2Error);
    assert!(
        f.last_message().contains("actuator force range"),
        "{}",
        f.last_message()
    );
}
