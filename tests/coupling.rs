//! Joint couplings (`[[coupling]]`, `q_b = ratio · q_a + offset`): the closed form of a geared
//! pair, the coupling held at every step, `energy − work` and the momenta exact, a gripper on
//! a free palm that closes symmetrically, and bad couplings refused.

mod common;

use common::spec_model;
use common::trees::COUPLED;
use triad::mechanics::{step, Model, State};
use triad::spec::Spec;

/// Two disks on the world about parallel vertical axes, `b` geared to `a` (ratio −2, offset
/// 0.3), a torque of 0.5 N·m on `a`: `(I_a + r² I_b) q̈_a = τ`, so `q_a = ½ α t²`.
const GEARS: &str = r#"
name = "Gears"
gravity = [0.0, 0.0, -9.81]
[solver]
max_step = 0.05
[[body]]
name = "wheel_a"
mass = 2.0
inertia = [0.1, 0.1, 0.2]
[[body]]
name = "wheel_b"
mass = 0.5
inertia = [0.03, 0.03, 0.05]
[[joint]]
name = "a"
type = "revolute"
parent = "world"
child = "wheel_a"
axis = [0.0, 0.0, 1.0]
actuated = true
[[joint]]
name = "b"
type = "revolute"
parent = "world"
child = "wheel_b"
origin = { xyz = [0.6, 0.0, 0.0] }
axis = [0.0, 0.0, 1.0]
[[coupling]]
a = "a"
b = "b"
ratio = -2.0
offset = 0.3
"#;

/// A palm free in space with two fingers sliding towards each other along mirrored axes, the
/// right one following the left (ratio 1), and a wrist pendulum coupled to nothing; no
/// gravity, so every momentum is a first integral.
const GRIPPER: &str = r#"
name = "Gripper"
gravity = [0.0, 0.0, 0.0]
[solver]
max_step = 0.02
[[body]]
name = "palm"
mass = 1.0
com = [0.0, 0.0, 0.05]
inertia = [0.004, 0.003, 0.005]
position = [0.1, -0.2, 0.5]
orientation = [0.95, 0.1, -0.05, 0.2]
velocity = [0.1, 0.0, -0.05]
angular_velocity = [0.3, -0.2, 0.5]
[[body]]
name = "left"
mass = 0.1
com = [0.0, 0.0, -0.03]
inertia = [2e-4, 1.5e-4, 1e-4]
[[body]]
name = "right"
mass = 0.1
com = [0.0, 0.0, -0.03]
inertia = [2e-4, 1.5e-4, 1e-4]
[[joint]]
name = "finger_left"
type = "prismatic"
parent = "palm"
child = "left"
origin = { xyz = [0.0, 0.04, 0.0] }
axis = [0.0, -1.0, 0.0]
actuated = true
initial = { q = 0.002, qd = 0.01 }
[[joint]]
name = "finger_right"
type = "prismatic"
parent = "palm"
child = "right"
origin = { xyz = [0.0, -0.04, 0.0] }
axis = [0.0, 1.0, 0.0]
[[coupling]]
a = "finger_left"
b = "finger_right"
"#;

fn set_inputs(s: &mut State, u: &[f64]) {
    let n = s.inputs().len();
    s.inputs_mut().copy_from_slice(&u[..n]);
}

fn q(s: &State, j: usize) -> f64 {
    s.outputs().joints[j].q[0]
}

/// The error against the closed form at 1 s falls at the order of the scheme (2, 4) when the
/// step halves, the coupling holds at every step to round-off and `energy − work` is constant.
#[test]
fn a_geared_pair_converges_to_its_closed_form_and_holds_the_coupling() {
    let alpha = 0.5 / (0.2 + 4.0 * 0.05);
    for (order, p) in [("", 2), ("\norder = 4", 4)] {
        let mut errors = Vec::new();
        for n in [20_u32, 40] {
            let h = 1.0 / f64::from(n);
            let text = GEARS.replace("max_step = 0.05", &format!("max_step = {h}{order}"));
            let (m, mut s) = spec_model(&text);
            assert_eq!(s.inputs().len(), 1, "the follower has no input");
            set_inputs(&mut s, &[0.5]);
            let e0 = s.outputs().energy - s.outputs().work;
            let mut worst = 0.0_f64;
            for _ in 0..n {
                step(&m, &mut s, h).unwrap();
                let qa = q(&s, 0);
                worst = worst.max((q(&s, 1) - (-2.0 * qa + 0.3)).abs());
                let (wa, wb) = (s.outputs().joints[0].qd[0], s.outputs().joints[1].qd[0]);
                assert!(
                    (wb + 2.0 * wa).abs() < 1e-11 * (1.0 + wa.abs()),
                    "{wb} {wa}"
                );
            }
            let de = (s.outputs().energy - s.outputs().work - e0).abs();
            eprintln!(
                "gears order {p}, h = {h}: |q_b − r q_a − o| ≤ {worst:.2e}, |Δ(E − W)| {de:.2e}"
            );
            assert!(worst < 1e-12, "{worst:e}");
            assert!(de < 1e-13, "{de:e}");
            errors.push((q(&s, 0) - 0.5 * alpha).abs());
        }
        let rate = (errors[0] / errors[1]).log2();
        eprintln!(
            "gears order {p}: errors {:.2e} {:.2e}, rate {rate:.2}",
            errors[0], errors[1]
        );
        assert!((rate - f64::from(p)).abs() < 0.3, "{rate}");
        assert!(errors[1] < 1e-3 * 0.5 * alpha, "{errors:?}");
    }
}

/// The gripper on its free palm: the fingers stay mirrored to round-off at every step, the
/// momenta are those of the start and `energy − work` is constant, at a large step and both
/// orders, with the left finger pushed by a varying force.
#[test]
fn a_gripper_on_a_free_palm_closes_symmetrically_with_exact_momenta() {
    for order in ["", "\norder = 4"] {
        let text = GRIPPER.replace("max_step = 0.02", &format!("max_step = 0.02{order}"));
        let (m, mut s) = spec_model(&text);
        let (p0, l0) = (s.outputs().p, s.outputs().l);
        let e0 = s.outputs().energy - s.outputs().work;
        let (mut sym, mut dp, mut dl, mut de) = (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
        for k in 0..300 {
            set_inputs(&mut s, &[0.3 * (0.05 * f64::from(k)).sin()]);
            step(&m, &mut s, 0.02).unwrap();
            let o = s.outputs();
            sym = sym.max((o.joints[0].q[0] - o.joints[1].q[0]).abs());
            // the fingers mirrored about the palm's y = 0 plane, in the palm frame
            let palm = &o.bodies[0];
            let yl = (palm.rot.transpose() * (o.bodies[1].r - palm.r)).y;
            let yr = (palm.rot.transpose() * (o.bodies[2].r - palm.r)).y;
            sym = sym.max((yl + yr).abs());
            dp = dp.max((o.p - p0).norm());
            dl = dl.max((o.l - l0).norm());
            de = de.max((o.energy - o.work - e0).abs());
        }
        eprintln!(
            "gripper{}: asymmetry {sym:.2e} m, |Δp| {dp:.2e}, |ΔL| {dl:.2e}, |Δ(E − W)| {de:.2e}",
            order.trim()
        );
        assert!(sym < 1e-13, "{sym:e}");
        assert!(dp < 1e-14 && dl < 1e-14, "{dp:e} {dl:e}");
        assert!(de < 1e-13, "{de:e}");
    }
}

/// Two pendulums under gravity, one following the other at half its angle, and two slides:
/// `energy − work` constant to round-off at a large step, the couplings held at every step.
#[test]
fn coupled_pendulums_keep_energy_minus_work_exact() {
    let text = COUPLED.replace(
        "actuated = true\ninitial = { q = 1.0",
        "actuated = true\ndamping = 0.05\ninitial = { q = 1.0",
    );
    assert!(text.contains("damping = 0.05"));
    for order in ["", "\norder = 4"] {
        let text = text.replace("max_step = 1e-3", &format!("max_step = 0.02{order}"));
        let (m, mut s) = spec_model(&text);
        set_inputs(&mut s, &[0.4, -0.3]);
        let e0 = s.outputs().energy - s.outputs().work;
        let (mut de, mut dc) = (0.0_f64, 0.0_f64);
        for _ in 0..500 {
            step(&m, &mut s, 0.02).unwrap();
            let o = s.outputs();
            de = de.max((o.energy - o.work - e0).abs());
            dc = dc.max((o.joints[1].q[0] - 0.5 * o.joints[0].q[0] + 0.2).abs());
            dc = dc.max((o.joints[3].q[0] + 1.5 * o.joints[2].q[0]).abs());
            assert!(o.constraint_residual < 1e-9);
        }
        eprintln!("pendulums{order}: |Δ(E − W)| ≤ {de:.2e}, coupling ≤ {dc:.2e}");
        assert!(de < 1e-12 * e0.abs().max(1.0), "{de:e}");
        assert!(dc < 1e-12, "{dc:e}");
    }
}

/// The reduced iteration borders the couplings on its tree factors (`step::reduced::couple`):
/// on the coupled pendulums and the free gripper it takes every stage itself, and its
/// trajectory is the multiplier form's to the Newton tolerance, couplings held alike.
#[test]
fn the_reduced_iteration_solves_coupled_trees_as_the_multiplier_form() {
    for (name, text, h) in [
        ("pendulums", COUPLED.to_string(), 0.01),
        ("gripper", GRIPPER.to_string(), 0.02),
    ] {
        let (reduced, mut a) = spec_model(&text);
        let mut multiplier = reduced.clone();
        multiplier.set_reduced_solver(false);
        assert!(reduced.uses_reduced_solver() && !multiplier.uses_reduced_solver());
        let mut b = State::new(&multiplier);
        let u: Vec<f64> = (0..a.inputs().len())
            .map(|k| 0.3 * (k as f64 + 1.0).cos())
            .collect();
        set_inputs(&mut a, &u);
        set_inputs(&mut b, &u);
        let (mut dq, mut fallbacks) = (0.0_f64, 0);
        for _ in 0..200 {
            fallbacks += step(&reduced, &mut a, h).expect("reduced step").fallbacks;
            step(&multiplier, &mut b, h).expect("multiplier step");
            let d = a.coordinates().iter().zip(b.coordinates());
            dq = dq.max(d.map(|(x, y)| (x - y).abs()).fold(0.0, f64::max));
        }
        eprintln!("{name}: |Δq| {dq:.2e}, {fallbacks} stages handed back");
        assert_eq!(fallbacks, 0, "{name}: stages handed to the multiplier form");
        assert!(dq < 1e-9, "{name}: trajectories differ by {dq:e}");
    }
}

/// The dense test oracle takes the same Newton iterates as the bordered solve.
#[test]
fn the_bordered_solve_equals_the_dense_oracle() {
    let (m, mut s) = spec_model(GEARS);
    let mut dense: Model = m.clone();
    dense.set_dense_solver(true);
    let mut sd = State::new(&dense);
    set_inputs(&mut s, &[0.5]);
    set_inputs(&mut sd, &[0.5]);
    for _ in 0..10 {
        step(&m, &mut s, 0.05).unwrap();
        step(&dense, &mut sd, 0.05).unwrap();
    }
    let (a, b) = (q(&s, 1), q(&sd, 1));
    assert!((a - b).abs() < 1e-13, "{a} {b}");
}

fn problems(text: &str) -> String {
    match Spec::from_str(text, triad::spec::Format::Toml, "test.toml") {
        Ok(spec) => match spec.lower() {
            Ok(_) => String::new(),
            Err(e) => e.to_string(),
        },
        Err(e) => e.to_string(),
    }
}

#[test]
fn bad_couplings_are_refused_with_their_paths() {
    let cases = [
        ("a = \"a\"\nb = \"c\"", "coupling[0].b", "no joint \"c\""),
        (
            "a = \"a\"\nb = \"a\"",
            "coupling[0]",
            "cannot follow itself",
        ),
        (
            "a = \"a\"\nb = \"b\"\nratio = 0.0",
            "coupling[0].ratio",
            "non-zero",
        ),
        (
            "a = \"a\"\nb = \"b\"\nratio = nan",
            "coupling[0].ratio",
            "finite",
        ),
        ("a = \"b\"\nb = \"a\"", "coupling[0]", "no input of its own"),
    ];
    for (body, path, what) in cases {
        let text = GEARS.replace(
            "[[coupling]]\na = \"a\"\nb = \"b\"\nratio = -2.0\noffset = 0.3",
            &format!("[[coupling]]\n{body}"),
        );
        let p = problems(&text);
        assert!(p.contains(path) && p.contains(what), "{body}: {p}");
    }
    // a follower's explicit initial state must be the leader's mapped
    let text = GEARS.replace(
        "origin = { xyz = [0.6, 0.0, 0.0] }",
        "origin = { xyz = [0.6, 0.0, 0.0] }\ninitial = { q = 1.0 }",
    );
    let p = problems(&text);
    assert!(
        p.contains("initial q = 1") && p.contains("leave it out"),
        "{p}"
    );
    // consistent is accepted
    let text = GEARS.replace(
        "origin = { xyz = [0.6, 0.0, 0.0] }",
        "origin = { xyz = [0.6, 0.0, 0.0] }\ninitial = { q = 0.3 }",
    );
    assert_eq!(problems(&text), "");
    // kinds must match
    let text = GEARS.replace(
        "name = \"b\"\ntype = \"revolute\"",
        "name = \"b\"\ntype = \"prismatic\"",
    );
    let p = problems(&text);
    assert!(p.contains("both be revolute or both prismatic"), "{p}");
    // a cycle
    let text =
        format!("{GEARS}\n[[coupling]]\na = \"b\"\nb = \"a\"\n").replace("actuated = true\n", "");
    let p = problems(&text);
    assert!(p.contains("cycle"), "{p}");
}

/// A two-finger gripper as URDF: the right finger `<mimic>`s the left with a multiplier and an
/// offset. The import couples them (the follower without an input) and the fingers follow
/// `q_r = −0.5 q_l + 0.01` while the left one is driven; a mimic of another kind stays
/// independent with a note.
#[test]
fn a_urdf_mimic_becomes_a_coupling() {
    let urdf = r#"<robot name="gripper">
  <link name="palm"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="left"><inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="right"><inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="tip"><inertial><mass value="0.05"/><inertia ixx="1e-5" iyy="1e-5" izz="1e-5" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="left_joint" type="prismatic"><parent link="palm"/><child link="left"/>
    <origin xyz="0 0.04 0"/><axis xyz="0 -1 0"/><limit lower="-0.02" upper="0.04" effort="20" velocity="1"/></joint>
  <joint name="right_joint" type="prismatic"><parent link="palm"/><child link="right"/>
    <origin xyz="0 -0.04 0"/><axis xyz="0 1 0"/><limit lower="-0.02" upper="0.04" effort="20" velocity="1"/>
    <mimic joint="left_joint" multiplier="-0.5" offset="0.01"/></joint>
  <joint name="tip_joint" type="revolute"><parent link="left"/><child link="tip"/>
    <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="5" velocity="1"/>
    <mimic joint="left_joint"/></joint>
</robot>"#;
    let (spec, outcome) =
        triad::urdf::import(urdf, "gripper.urdf", &triad::urdf::ImportOptions::default()).unwrap();
    assert_eq!(spec.coupling.len(), 1, "{:?}", spec.coupling);
    let c = &spec.coupling[0];
    assert_eq!(
        (c.a.as_str(), c.b.as_str(), c.ratio, c.offset),
        ("left_joint", "right_joint", -0.5, 0.01)
    );
    assert!(
        !spec
            .joint
            .iter()
            .find(|j| j.name == "right_joint")
            .unwrap()
            .actuated
    );
    assert!(
        outcome
            .notes
            .iter()
            .any(|n| n.contains("tip_joint") && n.contains("another kind")),
        "{:?}",
        outcome.notes
    );
    let (def, settings) = spec.lower().unwrap();
    let m = Model::new(&def, settings).unwrap();
    let mut s = State::new(&m);
    // inputs: left_joint's force and tip_joint's torque; the right finger has none
    assert_eq!(s.inputs().len(), 2);
    let names: Vec<&str> = def.joints.iter().map(|j| j.name.as_str()).collect();
    let (l, r) = (
        names.iter().position(|n| *n == "left_joint").unwrap(),
        names.iter().position(|n| *n == "right_joint").unwrap(),
    );
    assert!(
        (q(&s, r) - 0.01).abs() < 1e-15,
        "the follower starts at the offset"
    );
    s.inputs_mut()[0] = 2.0;
    let mut worst = 0.0_f64;
    for _ in 0..200 {
        step(&m, &mut s, 1e-3).unwrap();
        worst = worst.max((q(&s, r) - (-0.5 * q(&s, l) + 0.01)).abs());
    }
    assert!(q(&s, l) > 1e-3, "the driven finger moved: {}", q(&s, l));
    assert!(worst < 1e-14, "{worst:e}");
}

/// The example gripper (`examples/specs/gripper.toml`): a force above the leading finger's
/// friction closes both fingers to the stop together, mirrored, with `energy − work` exact.
#[test]
fn the_example_gripper_closes_both_fingers() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/specs/gripper.toml");
    let (m, mut s) = spec_model(&std::fs::read_to_string(path).unwrap());
    let e0 = s.outputs().energy - s.outputs().work;
    set_inputs(&mut s, &[0.0, 1.5]);
    for _ in 0..1000 {
        step(&m, &mut s, 1e-3).unwrap();
        let o = s.outputs();
        assert!((o.joints[1].q[0] - o.joints[2].q[0]).abs() < 1e-15);
    }
    let o = s.outputs();
    assert!(
        o.joints[1].q[0] > 0.039,
        "closed to the stop: {}",
        o.joints[1].q[0]
    );
    let de = (o.energy - o.work - e0).abs();
    assert!(de < 1e-12 * e0.abs(), "{de:e}");
}
