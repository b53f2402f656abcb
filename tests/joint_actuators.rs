//! Joint actuators (`[[actuator]]`, the input `actuator.A.ctrl`): MuJoCo's motor, position and
//! velocity laws through a gear, with their control and force clamps. Their work over a step is
//! exactly `τ Δq`, so `energy − work` stays at round-off at large steps; a position servo
//! settles to `ctrl / gear`; a clamped force is the force; the continuous model (linear models,
//! `joint.J.qdd`) has the same law; the spec refuses what they cannot drive, by path.

mod common;

use common::spec_model;
use triad::mechanics::{step, Model, Operating, State};
use triad::spec::{Format, Spec};

/// A cart on a prismatic joint along x carrying a rod on a revolute joint about y, released off
/// rest; `actuators` is appended as written.
fn cart_rod(gravity: f64, max_step: f64, actuators: &str) -> String {
    format!(
        r#"
name = "CartRod"
gravity = [0.0, 0.0, {gravity}]
[solver]
max_step = {max_step}
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
actuated = true
initial = {{ q = 0.1, qd = -0.3 }}
[[joint]]
name = "hinge"
type = "revolute"
parent = "cart"
child = "rod"
axis = [0.0, 1.0, 0.0]
actuated = true
initial = {{ q = 0.8, qd = 1.5 }}
{actuators}"#
    )
}

/// One actuator of `kind` on each joint, with gears and, when `clamps`, ranges that are hit.
fn on_both(kind: &str, clamps: bool) -> String {
    let gains = match kind {
        "motor" => "",
        "position" => "kp = 40.0\nkv = 3.0\n",
        _ => "kv = 6.0\n",
    };
    let ranges = if clamps {
        "ctrlrange = [-0.5, 0.8]\nforcerange = [-2.0, 1.5]\n"
    } else {
        ""
    };
    format!(
        "[[actuator]]\nname = \"a_rail\"\njoint = \"rail\"\nkind = \"{kind}\"\ngear = 0.5\n{gains}{ranges}\
         [[actuator]]\nname = \"a_hinge\"\njoint = \"hinge\"\nkind = \"{kind}\"\ngear = -2.0\n{gains}{ranges}"
    )
}

/// The inputs: `joint.rail.f`, `joint.hinge.tau`, then the two controls.
fn controls(s: &mut State, u: [f64; 4]) {
    s.inputs_mut().copy_from_slice(&u);
}

/// Largest `|Δ(energy − work)|` over `n` steps of `h`, the controls changed halfway, relative to
/// the largest energy or work met.
fn drift(m: &Model, s: &mut State, h: f64, n: usize) -> f64 {
    let e0 = s.outputs().energy - s.outputs().work;
    let (mut worst, mut scale) = (0.0_f64, s.outputs().energy.abs());
    for i in 0..n {
        if i == n / 2 {
            controls(s, [0.2, -0.1, -1.3, 2.1]);
        }
        step(m, s, h).unwrap();
        worst = worst.max((s.outputs().energy - s.outputs().work - e0).abs());
        scale = scale
            .max(s.outputs().energy.abs())
            .max(s.outputs().work.abs());
    }
    worst / scale
}

/// Each law, with and without clamps, both orders, at a step of 0.05 s (the servos' period
/// is ≈ 0.25 s): `energy − work` moves by at most 1e-14 of the largest energy or work over
/// 10 s, while the actuators' work is of the order of the energy or more.
#[test]
fn energy_minus_work_at_round_off_for_every_law_at_a_large_step() {
    for kind in ["motor", "position", "velocity"] {
        for clamps in [false, true] {
            for order in [2, 4] {
                let text = cart_rod(-9.81, 0.05, &on_both(kind, clamps)).replace(
                    "max_step = 0.05",
                    &format!("max_step = 0.05\norder = {order}"),
                );
                let (m, mut s) = spec_model(&text);
                controls(&mut s, [0.3, 0.2, 0.7, -0.4]);
                let worst = drift(&m, &mut s, 0.05, 200);
                let work = s.outputs().work;
                eprintln!(
                    "{kind} clamps {clamps} order {order}: |Δ(E − W)| ≤ {worst:.1e} of the scale, work {work:.3} J"
                );
                assert!(worst < 1e-14, "{kind} {clamps} {order}: {worst:e}");
                assert!(
                    work.abs() > 0.1,
                    "{kind}: the actuators did no work ({work})"
                );
            }
        }
    }
}

/// Without gravity a position servo holds its joint at `L = ctrl`, `q = ctrl / gear`: after
/// 40 s at a step of 0.05 s both joints sit there to 1e-9.
#[test]
fn a_position_servo_settles_to_ctrl_over_gear() {
    let servos = on_both("position", false).replace("kv = 3.0", "kv = 20.0");
    let (m, mut s) = spec_model(&cart_rod(0.0, 0.05, &servos));
    controls(&mut s, [0.0, 0.0, 0.35, 1.2]);
    for _ in 0..800 {
        step(&m, &mut s, 0.05).unwrap();
    }
    let (x, q) = (s.outputs().joints[0].q[0], s.outputs().joints[1].q[0]);
    eprintln!("settled: rail {x} (want 0.7), hinge {q} (want -0.6)");
    assert!((x - 0.35 / 0.5).abs() < 1e-9, "{x}");
    assert!((q - 1.2 / -2.0).abs() < 1e-9, "{q}");
}

/// A rotor (no gravity) driven by a position servo far from its target: the force is clamped
/// at forcerange's bound 0.5, so the joint receives gear · 0.5 = 1 N·m, the same motion as a
/// plain motor at ctrl 0.5 to round-off (1e-13 rad; with the joint's own input of 0.5 N·m the
/// two add, as they do for the motor); a control beyond ctrlrange is clamped: a motor at ctrl 9 with
/// ctrlrange [-1, 0.25] moves as one at 0.25. The angle is `τ t²/(2 I)` to the director
/// midpoint rule's phase error (1e-3 at ω h = 0.15).
#[test]
fn clamped_forces_and_controls_are_what_acts() {
    let rotor = |actuator: &str| {
        format!(
            "name = \"Rotor\"\ngravity = [0.0, 0.0, 0.0]\n[[body]]\nname = \"r\"\nmass = 1.0\n\
             inertia = [0.5, 0.5, 0.5]\n[[joint]]\nname = \"spin\"\ntype = \"revolute\"\nparent = \"world\"\n\
             child = \"r\"\naxis = [0.0, 0.0, 1.0]\nactuated = true\n[[actuator]]\nname = \"a\"\njoint = \"spin\"\n\
             gear = 2.0\n{actuator}"
        )
    };
    let run = |text: &str, u: [f64; 2]| {
        let (m, mut s) = spec_model(text);
        s.inputs_mut().copy_from_slice(&u);
        for _ in 0..20 {
            step(&m, &mut s, 0.05).unwrap();
        }
        assert!((s.outputs().work - s.outputs().energy).abs() < 1e-12);
        s.outputs().joints[0].q[0]
    };
    let servo = rotor("kind = \"position\"\nkp = 1000.0\nforcerange = [-0.5, 0.5]\n");
    let clamped = rotor("kind = \"motor\"\nctrlrange = [-1.0, 0.25]\n");
    let motor = rotor("kind = \"motor\"\n");
    for (text, u, same, torque) in [
        (&servo, [0.0, 50.0], [0.0, 0.5], 1.0),
        (&servo, [0.5, 50.0], [0.5, 0.5], 1.5),
        (&clamped, [0.0, 9.0], [0.0, 0.25], 0.5),
    ] {
        let (q, want) = (run(text, u), run(&motor, same));
        eprintln!(
            "clamped: q(1 s) = {q}, the motor's {want}, τ/(2I) = {}",
            torque
        );
        assert!((q - want).abs() < 1e-13, "{q} vs {want}");
        assert!((q - torque).abs() < 2e-3 * torque, "{q} vs {torque}");
    }
}

/// The continuous model has the same laws: its accelerations (`Operating`, which `joint.J.qdd`
/// and the linear models use) equal the integrator's (Richardson slope of one step) for every
/// law with clamps; and a servo's linear model is the analytic one, `B = g kp / I`.
#[test]
fn the_minimal_dynamics_has_the_same_laws() {
    for kind in ["motor", "position", "velocity"] {
        let text = cart_rod(-9.81, 1e-3, &on_both(kind, true));
        let u = [0.3, 0.2, 0.7, -0.45];
        let (m, mut s) = spec_model(&text);
        controls(&mut s, u);
        let op = Operating::of(&m, &s).unwrap();
        let (acc, _) = op.dynamics.accelerations(&op.q, &op.nu, &op.u).unwrap();
        let slope = |h: f64| {
            let (m, mut s) = spec_model(&text);
            controls(&mut s, u);
            let v0 = Operating::of(&m, &s).unwrap().nu;
            step(&m, &mut s, h).unwrap();
            let v1 = Operating::of(&m, &s).unwrap().nu;
            v0.iter()
                .zip(&v1)
                .map(|(a, b)| (b - a) / h)
                .collect::<Vec<_>>()
        };
        let (s1, s2) = (slope(4e-6), slope(2e-6));
        let err = acc
            .iter()
            .zip(s1.iter().zip(&s2))
            .map(|(a, (x, y))| (a - (2.0 * y - x)).abs())
            .fold(0.0, f64::max);
        eprintln!("{kind}: |q̈ − integrator| = {err:.1e}");
        assert!(err < 1e-6, "{kind}: {err:e}");
    }
    let text = "name = \"Servo\"\ngravity = [0.0, 0.0, 0.0]\n[[body]]\nname = \"r\"\nmass = 1.0\n\
                inertia = [0.5, 0.5, 0.5]\n[[joint]]\nname = \"spin\"\ntype = \"revolute\"\nparent = \"world\"\n\
                child = \"r\"\naxis = [0.0, 0.0, 1.0]\n[[actuator]]\nname = \"a\"\njoint = \"spin\"\n\
                kind = \"position\"\ngear = 2.0\nkp = 30.0\nkv = 4.0\n";
    let (m, s) = spec_model(text);
    let lin = Operating::of(&m, &s).unwrap().linearize(&[]).unwrap();
    let (g, kp, kv, i) = (2.0, 30.0, 4.0, 0.5);
    let want_a = [[0.0, 1.0], [-g * g * kp / i, -g * g * kv / i]];
    for (r, row) in want_a.iter().enumerate() {
        for (c, want) in row.iter().enumerate() {
            assert!((lin.a[(r, c)] - want).abs() < 1e-12, "A {r} {c}: {}", lin.a);
        }
    }
    assert!(
        (lin.b[(1, 0)] - g * kp / i).abs() < 1e-12 && lin.b[(0, 0)] == 0.0,
        "B {}",
        lin.b
    );
}

fn problems(actuators: &str) -> Vec<String> {
    let text = format!(
        "{}[[joint]]\nname = \"ball\"\ntype = \"spherical\"\nparent = \"rod\"\nchild = \"tip\"\n\
         [[body]]\nname = \"tip\"\nmass = 0.1\ninertia = [1e-3, 1e-3, 1e-3]\n{actuators}",
        cart_rod(-9.81, 1e-3, "")
    );
    match Spec::from_str(&text, Format::Toml, "a.toml") {
        Ok(_) => Vec::new(),
        Err(e) => e.to_string().lines().map(str::to_string).collect(),
    }
}

/// What an actuator cannot be is refused with the file, the path and the reason.
#[test]
fn the_spec_refuses_bad_actuators_by_path() {
    let cases = [
        (
            "name = \"a\"\njoint = \"hinj\"\nkind = \"motor\"\n",
            "a.toml: actuator[0].joint: no joint named \"hinj\"",
            "did you mean",
        ),
        (
            "name = \"a\"\njoint = \"ball\"\nkind = \"motor\"\n",
            "a.toml: actuator[0].joint: joint \"ball\" is spherical",
            "revolute and prismatic joints only",
        ),
        (
            "name = \"a\"\njoint = \"hinge\"\nkind = \"position\"\n",
            "a.toml: actuator[0].kp: a position servo needs kp",
            "",
        ),
        (
            "name = \"a\"\njoint = \"hinge\"\nkind = \"motor\"\nkv = 1.0\n",
            "a.toml: actuator[0].kv: a motor takes no kv",
            "",
        ),
        (
            "name = \"a\"\njoint = \"hinge\"\nkind = \"velocity\"\nkv = -1.0\n",
            "a.toml: actuator[0].kv: must be finite and >= 0",
            "",
        ),
        (
            "name = \"a\"\njoint = \"hinge\"\nkind = \"motor\"\ngear = 0.0\n",
            "a.toml: actuator[0].gear: must be finite and non-zero",
            "",
        ),
        (
            "name = \"a\"\njoint = \"hinge\"\nkind = \"motor\"\nctrlrange = [1.0, -1.0]\n",
            "a.toml: actuator[0].ctrlrange: must be [lo, hi] with finite lo < hi",
            "",
        ),
        (
            "name = \"a\"\njoint = \"hinge\"\nkind = \"motor\"\nforcerange = [1.0]\n",
            "a.toml: actuator[0].forcerange: expected 2 numbers, found 1",
            "",
        ),
        (
            "name = \"a\"\njoint = \"hinge\"\nkind = \"servo\"\n",
            "a.toml: actuator[0].kind: unknown actuator kind \"servo\"",
            "motor, position, velocity",
        ),
        (
            "name = \"a b\"\njoint = \"hinge\"\nkind = \"motor\"\n",
            "a.toml: actuator[0].name: \"a b\" is not an identifier",
            "",
        ),
    ];
    for (body, start, also) in cases {
        let found = problems(&format!("[[actuator]]\n{body}"));
        assert!(
            found
                .iter()
                .any(|l| l.starts_with(start) && l.contains(also)),
            "{start} … {also}: got {found:?}"
        );
    }
    let dup = problems(
        "[[actuator]]\nname = \"a\"\njoint = \"hinge\"\nkind = \"motor\"\n\
         [[actuator]]\nname = \"a\"\njoint = \"rail\"\nkind = \"motor\"\n",
    );
    assert!(
        dup.iter().any(|l| l.starts_with(
            "a.toml: actuator[1].name: duplicate actuator name \"a\" (also actuator[0])"
        )),
        "{dup:?}"
    );
    // and a good one passes
    let ok =
        problems("[[actuator]]\nname = \"a\"\njoint = \"hinge\"\nkind = \"velocity\"\nkv = 2.0\n");
    assert!(ok.is_empty(), "{ok:?}");
}

/// A joint's `actuatorfrcrange` clamps the sum of its actuators' generalised forces (MuJoCo's
/// joint-level clamp), not each one: a rotor driven by two motors whose sum, 2·0.6 + 1·0.5 =
/// 1.7 N·m, exceeds the range's 0.8 moves as one motor of 0.8 N·m to round-off, with `E − W` at
/// round-off; inside the range the two add. The joint's own input is not in the sum.
#[test]
fn a_joint_range_clamps_the_summed_actuator_force() {
    let rotor = |range: &str, actuators: &str| {
        format!(
            "name = \"Rotor\"\ngravity = [0.0, 0.0, 0.0]\n[[body]]\nname = \"r\"\nmass = 1.0\n\
             inertia = [0.5, 0.5, 0.5]\n[[joint]]\nname = \"spin\"\ntype = \"revolute\"\nparent = \"world\"\n\
             child = \"r\"\naxis = [0.0, 0.0, 1.0]\nactuated = true\n{range}\n{actuators}"
        )
    };
    let two = "[[actuator]]\nname = \"a\"\njoint = \"spin\"\nkind = \"motor\"\ngear = 2.0\n\
               [[actuator]]\nname = \"b\"\njoint = \"spin\"\nkind = \"motor\"\n";
    let one = "[[actuator]]\nname = \"a\"\njoint = \"spin\"\nkind = \"motor\"\n";
    let run = |text: &str, u: &[f64]| {
        let (m, mut s) = spec_model(text);
        s.inputs_mut().copy_from_slice(u);
        for _ in 0..20 {
            step(&m, &mut s, 0.05).unwrap();
        }
        let o = s.outputs();
        assert!((o.work - o.energy).abs() < 1e-14 * o.energy.max(1.0));
        o.joints[0].q[0]
    };
    let clamped = rotor("actuatorfrcrange = [-0.3, 0.8]", two);
    for (u, same) in [
        ([0.0, 0.6, 0.5], [0.0, 0.8]),   // 1.7 beyond 0.8
        ([0.0, -0.6, 0.5], [0.0, -0.3]), // −0.7 beyond −0.3
        ([0.0, 0.2, -0.1], [0.0, 0.3]),  // 0.3 inside
        ([0.5, 0.6, 0.5], [0.5, 0.8]),   // the joint's own 0.5 N·m on top
    ] {
        let (q, want) = (run(&clamped, &u), run(&rotor("", one), &same));
        assert!((q - want).abs() < 1e-13, "{u:?}: {q} vs {want}");
    }
    // refused where it cannot act, and when empty
    for (range, kind, why) in [
        ("[0.5, -0.5]", "revolute", "finite lo < hi"),
        ("[-1.0, 1.0]", "spherical", "revolute and prismatic"),
    ] {
        let text = rotor(&format!("actuatorfrcrange = {range}"), "")
            .replace("type = \"revolute\"", &format!("type = \"{kind}\""))
            .replace("actuated = true\n", "");
        let e = Spec::from_str(&text, Format::Toml, "a.toml")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("a.toml: joint[0].actuatorfrcrange") && e.contains(why),
            "{e}"
        );
    }
}
