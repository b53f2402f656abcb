//! The minimal-coordinate dynamics of `tree_dynamics` against the integrator, and its exact
//! linear model against differences: every joint type, springs, dampers, stops, actuators,
//! body loads, a floating base, gravity.

mod common;

use common::spec_model;
use common::trees::{ALL_KINDS, FLOATING};
use num_dual::Dual64;
use triad::mechanics::{step, Model, Operating, Quantity, State};

fn with_inputs(text: &str, u: &[f64]) -> (Model, State) {
    let (m, mut s) = spec_model(text);
    let n = s.inputs().len();
    s.inputs_mut().copy_from_slice(&u[..n]);
    (m, s)
}

/// The rates of the joints and free bodies, as the outputs report them.
fn rates(model: &Model, state: &State) -> Vec<f64> {
    Operating::of(model, state).unwrap().nu
}

/// `ν̇` of the integrator by Richardson extrapolation of one step from the state: the step
/// is second order and symmetric, `(ν(h) − ν(0))/h = ν̇ + (h/2) ν̈ + O(h²)`.
fn integrator_accelerations(text: &str, u: &[f64], h: f64) -> Vec<f64> {
    let slope = |h: f64| {
        let (m, mut s) = with_inputs(text, u);
        let v0 = rates(&m, &s);
        step(&m, &mut s, h).unwrap();
        let v1 = rates(&m, &s);
        v0.iter()
            .zip(&v1)
            .map(|(a, b)| (b - a) / h)
            .collect::<Vec<_>>()
    };
    let (s1, s2) = (slope(h), slope(h / 2.0));
    s1.iter().zip(&s2).map(|(a, b)| 2.0 * b - a).collect()
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

#[test]
fn accelerations_agree_with_the_integrator() {
    let u = [
        0.7, -1.2, 0.4, 0.9, -0.5, 0.3, 0.2, -0.1, 0.6, 0.25, -0.35, 0.15, 0.5, -0.2, 0.1,
    ];
    for (name, text) in [("all kinds", ALL_KINDS), ("floating", FLOATING)] {
        let (m, s) = with_inputs(text, &u);
        let op = Operating::of(&m, &s).unwrap();
        let (acc, _) = op.dynamics.accelerations(&op.q, &op.nu, &op.u).unwrap();
        let want = integrator_accelerations(text, &u, 4e-6);
        let err = acc
            .iter()
            .zip(&want)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        let scale = max_abs(&want);
        assert!(
            err <= 1e-6 * scale,
            "{name}: |ν̇ − integrator| = {err:e} of {scale:e}\n{acc:?}\n{want:?}"
        );
    }
}

#[test]
fn shipped_trees_accelerate_as_they_integrate() {
    for model in [
        "pendulum",
        "double_pendulum",
        "heavy_top",
        "robot_arm",
        "space_arm",
        "free_body",
    ] {
        let path = format!(
            "{}/modelDescription/{model}/spec.toml",
            env!("CARGO_MANIFEST_DIR")
        );
        let text = std::fs::read_to_string(path).unwrap();
        let (m, s) = spec_model(&text);
        let op = Operating::of(&m, &s).unwrap();
        let (acc, _) = op.dynamics.accelerations(&op.q, &op.nu, &op.u).unwrap();
        let want = integrator_accelerations(&text, &[0.0; 16], 2e-5);
        let err = acc
            .iter()
            .zip(&want)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        let scale = max_abs(&want).max(1e-3);
        assert!(
            err <= 1e-6 * scale,
            "{model}: {err:e} of {scale:e}\n{acc:?}\n{want:?}"
        );
    }
}

/// Along the flow, `dE/dt` is the power of the inputs minus the dampers' loss: zero without
/// them, to round-off (a check of M, C and gravity together, independent of the integrator).
#[test]
fn energy_is_a_first_integral_of_the_undamped_dynamics() {
    let text = ALL_KINDS
        .replace("damping = 0.3", "")
        .replace("damping = 0.5", "")
        .replace("damping = 0.05", "")
        .replace("damping = 0.02", "");
    let (m, s) = spec_model(&text);
    let op = Operating::of(&m, &s).unwrap();
    let d = &op.dynamics;
    let (acc, _) = d.accelerations(&op.q, &op.nu, &op.u).unwrap();
    let qdot = d.qdot(&op.q, &op.nu);
    let qd: Vec<Dual64> =
        op.q.iter()
            .zip(&qdot)
            .map(|(&a, &b)| Dual64::new(a, b))
            .collect();
    let vd: Vec<Dual64> = op
        .nu
        .iter()
        .zip(&acc)
        .map(|(&a, &b)| Dual64::new(a, b))
        .collect();
    let e = d.energy(&qd, &vd);
    assert!(
        e.eps.abs() <= 1e-12 * e.re.abs().max(1.0),
        "dE/dt = {:e} (E = {})",
        e.eps,
        e.re
    );
}

/// `A, B, C, D` against central differences of the same (f64) functions.
#[test]
fn the_linear_model_matches_central_differences() {
    let u = [
        0.7, -1.2, 0.4, 0.9, -0.5, 0.3, 0.2, -0.1, 0.6, 0.25, -0.35, 0.15, 0.5, -0.2, 0.1,
    ];
    for text in [ALL_KINDS, FLOATING] {
        let (m, s) = with_inputs(text, &u);
        let op = Operating::of(&m, &s).unwrap();
        let d = &op.dynamics;
        let ys = [
            Quantity::BodyR(1, 0),
            Quantity::BodyRot(2, 1, 2),
            Quantity::BodyV(2, 2),
            Quantity::BodyW(1, 1),
            Quantity::JointQ(1, 0),
            Quantity::JointQdd(1, 0),
            Quantity::Energy,
            Quantity::L(2),
        ];
        let lin = op.linearize(&ys).unwrap();
        let n = d.n();
        let f = |x: &[f64], uu: &[f64]| {
            let (acc, _) = d.accelerations(&x[..n], &x[n..], uu).unwrap();
            let mut xd = d.qdot(&x[..n], &x[n..]);
            xd.extend_from_slice(&acc);
            let y: Vec<f64> = ys
                .iter()
                .map(|y| d.quantity(&x[..n], &x[n..], &acc, *y))
                .collect();
            (xd, y)
        };
        let x0: Vec<f64> = op.q.iter().chain(&op.nu).copied().collect();
        let eps = 1e-6;
        let mut worst = 0.0_f64;
        for col in 0..2 * n + op.u.len() {
            let (mut xp, mut xm, mut up, mut um) =
                (x0.clone(), x0.clone(), op.u.clone(), op.u.clone());
            if col < 2 * n {
                xp[col] += eps;
                xm[col] -= eps;
            } else {
                up[col - 2 * n] += eps;
                um[col - 2 * n] -= eps;
            }
            let ((fp, yp), (fm, ym)) = (f(&xp, &up), f(&xm, &um));
            for r in 0..2 * n {
                let fd = (fp[r] - fm[r]) / (2.0 * eps);
                let ex = if col < 2 * n {
                    lin.a[(r, col)]
                } else {
                    lin.b[(r, col - 2 * n)]
                };
                worst = worst.max((fd - ex).abs() / (1.0 + ex.abs()));
            }
            for r in 0..ys.len() {
                let fd = (yp[r] - ym[r]) / (2.0 * eps);
                let ex = if col < 2 * n {
                    lin.c[(r, col)]
                } else {
                    lin.d[(r, col - 2 * n)]
                };
                worst = worst.max((fd - ex).abs() / (1.0 + ex.abs()));
            }
        }
        // central differences at 1e-6 carry ~1e-10·|f|/|ex| of round-off (the stop's 500 N·m
        // terms) and O(1e-12·f''') of truncation: 1e-5 is their accuracy here
        assert!(worst < 1e-5, "worst relative difference {worst:e}");
    }
}

/// The composite-rigid-body mass matrix is `∂res/∂ν̇` of the inverse dynamics, column by column.
#[test]
fn the_mass_matrix_is_the_inverse_dynamics_slope() {
    for text in [ALL_KINDS, FLOATING] {
        let (m, s) = spec_model(text);
        let op = Operating::of(&m, &s).unwrap();
        let d = &op.dynamics;
        let n = d.n();
        let mm = d.mass_matrix(&op.q);
        let (zero, u0) = (vec![0.0; n], vec![0.0; d.n_inputs()]);
        let mut e = vec![0.0; n];
        for i in 0..n {
            e[i] = 1.0;
            let col = d.residual(&op.q, &zero, &e, &u0, true);
            e[i] = 0.0;
            for r in 0..n {
                let (a, b) = (mm[(r, i)], col[r]);
                assert!(
                    (a - b).abs() <= 1e-13 * (1.0 + b.abs()),
                    "M[{r},{i}] = {a} vs {b}"
                );
            }
        }
    }
}
