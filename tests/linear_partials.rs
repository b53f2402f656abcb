//! The analytic linear model (`tree_partials`: Carpentier–Mansard derivatives of the residual
//! and articulated-body solves) against the dual-number passes it replaces, to round-off:
//! every joint kind it covers, springs, dampers, stops on and off their limits, clamped inputs,
//! actuators with gains and clamps, body torques and forces, rotors, fixed joints, branches,
//! the shipped trees and the chains of the benches; and the models it leaves to the duals.

mod common;

use common::spec_model;
use common::trees::{ALL_KINDS, FLOATING, ROTOR};
use nalgebra::DMatrix;
use num_dual::Dual64;
use triad::mechanics::{Model, Operating, Quantity, SolverSettings, State};

/// `ALL_KINDS` with its spherical joint a revolute one (the analytic path covers the rest),
/// a stop engaged on j1, an actuator pair on j2 and a fixed branch.
fn all_kinds_covered() -> String {
    ALL_KINDS
        .replace(
            "type = \"spherical\"",
            "type = \"revolute\"\naxis = [0.3, -0.2, 1.0]",
        )
        .replace(
            "initial = { quat = [0.9, 0.2, -0.3, 0.1], w = [0.5, -1.0, 2.0] }",
            "initial = { q = -0.35, qd = 1.7 }",
        )
        .replace(
            "stiffness = 2.0\n",
            "stiffness = 2.0\nlower = -1.0\nupper = 0.3\nstop_damping = 2.5\neffort = 0.5\n",
        )
        + r#"
[[body]]
name = "g"
mass = 0.2
com = [0.05, 0.0, 0.0]
inertia = [0.001, 0.002, 0.0015]
[[joint]]
name = "weld"
type = "fixed"
parent = "c"
child = "g"
origin = { xyz = [0.1, 0.2, 0.0], rpy = [0.3, 0.0, 0.1] }
[[body]]
name = "h"
mass = 0.35
com = [0.0, 0.04, -0.05]
inertia = [0.002, 0.003, 0.001]
[[joint]]
name = "branch"
type = "prismatic"
parent = "g"
child = "h"
axis = [0.0, 1.0, 1.0]
armature = 0.01
damping = 0.2
initial = { q = 0.1, qd = -0.4 }
[[actuator]]
name = "servo"
joint = "j2"
kind = "position"
gear = 0.5
kp = 40.0
kv = 3.0
forcerange = [-3.0, 3.0]
[[actuator]]
name = "push"
joint = "branch"
kind = "velocity"
kv = 0.8
"#
}

/// The largest entry of `a − b` relative to the largest of `b` (1 when `b` is zero).
fn rel(a: &DMatrix<f64>, b: &DMatrix<f64>) -> f64 {
    assert_eq!(a.shape(), b.shape());
    let scale = b.amax().max(1.0);
    (a - b).amax() / scale
}

/// Linearises `op` both ways with outputs `ys` and checks they agree.
fn agree(name: &str, op: &Operating, ys: &[Quantity], analytic: bool) {
    let d = &op.dynamics;
    assert_eq!(d.has_analytic_linearization(), analytic, "{name}: path");
    let fast = d.linearize(&op.q, &op.nu, &op.u, ys).unwrap();
    let slow = d.linearize_by_duals(&op.q, &op.nu, &op.u, ys).unwrap();
    for (what, a, b) in [
        ("A", &fast.a, &slow.a),
        ("B", &fast.b, &slow.b),
        ("C", &fast.c, &slow.c),
        ("D", &fast.d, &slow.d),
    ] {
        let e = rel(a, b);
        assert!(e < 1e-12, "{name}: {what} differs by {e:e}");
    }
    for (what, a, b) in [
        ("xdot0", &fast.xdot0, &slow.xdot0),
        ("y0", &fast.y0, &slow.y0),
    ] {
        let scale = b.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
        let e = a
            .iter()
            .zip(b)
            .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(e < 1e-12 * scale, "{name}: {what} differs by {e:e}");
    }
}

fn operating(model: &Model, state: &State) -> Operating {
    Operating::of(model, state).unwrap()
}

#[test]
fn every_covered_kind_and_load_matches_the_duals() {
    let text = all_kinds_covered();
    let (m, mut s) = spec_model(&text);
    let u = [
        0.7, -1.2, 0.4, 0.9, -0.5, 0.3, 0.2, -0.1, 0.6, 0.25, -0.35, 0.15, 0.5, -0.2, 0.1, 0.3,
    ];
    let k = s.inputs().len();
    s.inputs_mut().copy_from_slice(&u[..k]);
    let ys = [
        Quantity::BodyR(3, 0),
        Quantity::BodyW(5, 2),
        Quantity::JointQdd(1, 0),
        Quantity::JointQdd(3, 1),
        Quantity::Energy,
        Quantity::L(1),
    ];
    agree("all kinds", &operating(&m, &s), &ys, true);
    // the servo's force on its clamp, the stop off its limit
    let mut s2 = s.clone();
    s2.inputs_mut()[k - 2] = 50.0;
    agree("clamped", &operating(&m, &s2), &ys, true);
}

#[test]
fn shipped_trees_and_bench_chains_match_the_duals() {
    for model in [
        "pendulum",
        "double_pendulum",
        "robot_arm",
        "heavy_top",
        "free_body",
    ] {
        let path = format!(
            "{}/modelDescription/{model}/spec.toml",
            env!("CARGO_MANIFEST_DIR")
        );
        let (m, s) = spec_model(&std::fs::read_to_string(path).unwrap());
        let op = operating(&m, &s);
        let analytic = !matches!(model, "heavy_top" | "free_body");
        agree(model, &op, &[Quantity::Energy], analytic);
    }
    for n in [1, 2, 10, 20] {
        let m = Model::new(&common::chain(n), SolverSettings::default()).unwrap();
        let s = State::new(&m);
        agree(&format!("chain{n}"), &operating(&m, &s), &[], true);
    }
    let (m, s) = spec_model(&format!("{ROTOR}armature = 0.03\ndamping = 0.1\n"));
    agree("rotor", &operating(&m, &s), &[], true);
}

#[test]
fn spherical_joints_and_free_bodies_keep_the_duals() {
    for (name, text) in [("all kinds", ALL_KINDS), ("floating", FLOATING)] {
        let (m, s) = spec_model(text);
        agree(name, &operating(&m, &s), &[], false);
    }
}

/// On long chains the mass matrix is ill-conditioned (cond ≈ 4·10⁷ for 100 links), and the two
/// paths' `ν̇₀` (LU against articulated-body solves) differ by round-off times that; the
/// analytic `A` is checked there by its backward error instead: at its own `ν̇₀`, the duals'
/// `∂res/∂(q, ν)` and the mass matrix, `M X + ∂res/∂(q, ν) = 0` and `M ν̇₀ + res = 0`.
#[test]
fn long_chains_solve_the_duals_equations_to_round_off() {
    for n in [30, 100] {
        let m = Model::new(&common::chain(n), SolverSettings::default()).unwrap();
        let op = operating(&m, &State::new(&m));
        let d = &op.dynamics;
        assert!(d.has_analytic_linearization());
        let lin = d.linearize(&op.q, &op.nu, &op.u, &[]).unwrap();
        let nud0 = &lin.xdot0[n..];
        let mm = d.mass_matrix(&op.q);
        let nud: Vec<Dual64> = nud0.iter().map(|&x| Dual64::from(x)).collect();
        let lift = |x: &[f64], s: Option<usize>| -> Vec<Dual64> {
            let mut v: Vec<Dual64> = x.iter().map(|&x| Dual64::from(x)).collect();
            if let Some(i) = s {
                v[i] = v[i].derivative();
            }
            v
        };
        let mut r = DMatrix::zeros(n, 2 * n);
        for col in 0..2 * n {
            let qd = lift(&op.q, (col < n).then_some(col));
            let vd = lift(&op.nu, (col >= n).then(|| col - n));
            let res = d.residual(&qd, &vd, &nud, &lift(&op.u, None), false);
            for i in 0..n {
                r[(i, col)] = res[i].eps;
            }
        }
        let x = lin.a.rows(n, n).into_owned();
        let e = (&mm * &x + &r).amax() / (mm.amax() * x.amax());
        assert!(e < 1e-14, "chain{n}: backward error of A {e:e}");
        let res0 = d.residual(&op.q, &op.nu, &vec![0.0; n], &op.u, false);
        let v = DMatrix::from_column_slice(n, 1, nud0);
        let e =
            (&mm * &v + DMatrix::from_column_slice(n, 1, &res0)).amax() / (mm.amax() * v.amax());
        assert!(e < 1e-14, "chain{n}: backward error of ν̇₀ {e:e}");
    }
}
