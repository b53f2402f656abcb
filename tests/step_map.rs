//! The discrete-time linear model of a communication step (`Simulation::step_map`) against
//! central differences of the step itself: every joint type, springs, dampers, actuators, body
//! loads, rotors (armature), a floating base, orders 2 and 4, several sub-steps per
//! communication step.

mod common;

use common::step_diff::{end_of, lower, minus, report};
use common::trees::{with_armature, ALL_KINDS, FLOATING};
use nalgebra::DMatrix;
use triad::math::Vec3;
use triad::sim::Simulation;

/// Central differences of the step's map in x and u, with steps `eps`.
fn differences(text: &str, u: &[f64], h: f64, eps: f64) -> (DMatrix<f64>, DMatrix<f64>) {
    let (def, settings) = lower(text);
    let sim = Simulation::new(&def, settings, 0.0).unwrap();
    let op = sim.operating().unwrap();
    let x0: Vec<f64> = op.q.iter().chain(&op.nu).copied().collect();
    let (nx, nu) = (x0.len(), u.len());
    let mut ad = DMatrix::zeros(nx, nx);
    let mut bd = DMatrix::zeros(nx, nu);
    for k in 0..nx + nu {
        let run = |s: f64| {
            let (mut x, mut uu) = (x0.clone(), u.to_vec());
            if k < nx {
                x[k] += s;
            } else {
                uu[k - nx] += s;
            }
            end_of(&def, settings, &op, &x, &uu, h)
        };
        let (p, m) = (run(eps), run(-eps));
        let d = minus(&def, &p, &m);
        for r in 0..nx {
            let v = d[r] / (2.0 * eps);
            if k < nx {
                ad[(r, k)] = v;
            } else {
                bd[(r, k - nx)] = v;
            }
        }
    }
    (ad, bd)
}

fn exact(text: &str, u: &[f64], h: f64) -> (DMatrix<f64>, DMatrix<f64>) {
    let (def, settings) = lower(text);
    let mut sim = Simulation::new(&def, settings, 0.0).unwrap();
    sim.state_mut().inputs_mut().copy_from_slice(u);
    let map = sim.step_map(h).unwrap();
    (map.ad, map.bd)
}

/// The solver variants: order 2, order 4 (triple jump and Suzuki's five stages), and
/// error-controlled steps (their sizes held at the accepted ones).
const SOLVERS: [(&str, &str); 4] = [
    ("order 2", "max_step = 1e-3"),
    ("order 4", "max_step = 2e-3\norder = 4"),
    (
        "order 4, 5 stages",
        "max_step = 2e-3\norder = 4\nstages = 5",
    ),
    ("error control", "max_step = 2e-3\nrtol = 1e-6\natol = 1e-8"),
];

/// The inputs of the two models (the first `m` of them).
const U: [f64; 15] = [
    0.7, -1.2, 0.4, 0.9, -0.5, 0.3, 0.2, -0.1, 0.6, 0.25, -0.35, 0.15, 0.5, -0.2, 0.1,
];

/// Central differences of the step agree with the exact map to their own accuracy: with steps
/// of 1e-5 in x and 1e-4 in u (where truncation and round-off of the differences balance:
/// measured, the agreement is 1e-11–1e-9 there and worse at steps 10× smaller or larger).
#[test]
fn step_map_agrees_with_differences_of_the_step() {
    let (rotors, floating_rotors) = (with_armature(ALL_KINDS), with_armature(FLOATING));
    for (name, text) in [
        ("all kinds", ALL_KINDS),
        ("floating", FLOATING),
        ("all kinds with rotors", rotors.as_str()),
        ("floating with rotors", floating_rotors.as_str()),
    ] {
        for (solver, line) in SOLVERS {
            let text = text.replace("max_step = 1e-3", line);
            let (def, settings) = lower(&text);
            let m = Simulation::new(&def, settings, 0.0)
                .unwrap()
                .model()
                .inputs()
                .len();
            let u = &U[..m];
            for h in [1e-3, 1e-2] {
                let (ad, bd) = exact(&text, u, h);
                let (fa, _) = differences(&text, u, h, 1e-5);
                // under error control with rotors a difference of 1e-4 in u changes which
                // steps the controller accepts (the map is not smooth there): measured 7e-3 at
                // 1e-4, 2.6e-9 at 1e-5
                let eu = if solver == "error control" && name.contains("rotors") {
                    1e-5
                } else {
                    1e-4
                };
                let (_, fb) = differences(&text, u, h, eu);
                let ea = report(&format!("{name} {solver} Ad h={h}"), &ad, &fa);
                let eb = report(&format!("{name} {solver} Bd h={h}"), &bd, &fb);
                eprintln!(
                    "{name}, {solver}, h={h}: |Ad−fd|/|fd| = {ea:.2e}, |Bd−fd|/|fd| = {eb:.2e}"
                );
                // error control starts a run with steps of max_step·rtol^(1/2) (2e-6 s here),
                // and the round-off of the tangent grows with the number and shortness of the
                // sub-steps (module docs of step::tangent): measured 1.1e-7 there, and 1.3e-6
                // with rotors (their load's share of the swapped Jacobian is corrected by a
                // difference of two rates of the size of the column)
                let bound = match (solver, name.contains("rotors")) {
                    ("error control", false) => 1e-6,
                    ("error control", true) => 3e-6,
                    _ => 3e-8,
                };
                assert!(
                    ea < bound && eb < bound,
                    "{name} {solver} h={h}: {ea:e} {eb:e}"
                );
            }
        }
    }
}

/// As h → 0 the step's map tends to the flow's variational map,
/// `Ad = I + hA + (h²/2)(A² + Ȧ) + O(h³)` (Ȧ: A changes along the trajectory off an equilibrium), so `e(h) = |(Ad − I)/h − A|`
/// falls as h: measured e(h)/e(h/2) = 2.00 on a model of every joint type but spherical (its
/// rotation vectors are perturbations about the moving orientation at the step's end, which
/// adds a transport term to that limit), with springs, dampers and inputs, off equilibrium.
#[test]
fn step_map_tends_to_the_continuous_model() {
    let text = ALL_KINDS
        .replace(
            "type = \"spherical\"",
            "type = \"revolute\"\naxis = [0.0, 1.0, 0.0]",
        )
        .replace(
            "initial = { quat = [0.9, 0.2, -0.3, 0.1], w = [0.5, -1.0, 2.0] }",
            "initial = { q = 0.3, qd = -0.8 }",
        )
        .replace("max_step = 1e-3", "max_step = 1.0");
    let (def, settings) = lower(&text);
    let sim = Simulation::new(&def, settings, 0.0).unwrap();
    let m = sim.model().inputs().len();
    let u = &U[..m];
    let mut s0 = Simulation::new(&def, settings, 0.0).unwrap();
    s0.state_mut().inputs_mut().copy_from_slice(u);
    let op = s0.operating().unwrap();
    let lin = op.linearize(&[]).unwrap();
    let a = &lin.a;
    let nx = a.nrows();
    let err = |h: f64| {
        let (ad, _) = exact(&text, u, h);
        let d = (ad - DMatrix::identity(nx, nx)) / h - a;
        d.norm() / a.norm()
    };
    let (e1, e2, e3) = (err(4e-3), err(2e-3), err(1e-3));
    eprintln!(
        "e(h) = {e1:.3e}, {e2:.3e}, {e3:.3e}: ratios {:.2}, {:.2}",
        e1 / e2,
        e2 / e3
    );
    for r in [e1 / e2, e2 / e3] {
        assert!((1.9..2.1).contains(&r), "ratio {r}: {e1:e} {e2:e} {e3:e}");
    }
}

/// A deterministic pseudo-random number in (−1, 1) of `i`.
fn wiggle(i: usize) -> f64 {
    ((i as f64 + 1.0) * 12.9898).sin() * 0.5 + ((i as f64) * 78.233).cos() * 0.5
}

/// The embedding's and the read-off's tangents (analytic spatial sweeps, `model::minimal`)
/// agree with dual-number passes of the kinematics, the rate load and the inverse dynamics to
/// round-off: every joint type, a floating base, rotors; at a moving state whose nodal
/// velocities are off the tree's (as at a step's end, where `b − M ν` vanishes only projected
/// on the rates, so the rates' axes' own motion counts).
#[test]
fn embedding_and_readoff_tangents_agree_with_dual_passes() {
    use num_dual::Dual64;
    use triad::mechanics::NodalColumns;
    let rotors = with_armature(ALL_KINDS);
    for (name, text) in [
        ("all kinds", ALL_KINDS),
        ("floating", FLOATING),
        ("all kinds with rotors", rotors.as_str()),
    ] {
        let (def, settings) = lower(text);
        let mut sim = Simulation::new(&def, settings, 0.0).unwrap();
        let m = sim.model().inputs().len();
        sim.state_mut().inputs_mut().copy_from_slice(&U[..m]);
        sim.advance(0.05).unwrap();
        let op = sim.operating().unwrap();
        let td = &op.dynamics;
        let (n, nb) = (op.q.len(), def.bodies.len());
        // the embedding against a dual pass of the nodal coordinates
        let emb = td.embed_tangent(&op.q, &op.nu);
        let mut worst: f64 = 0.0;
        for col in 0..2 * n {
            let qd: Vec<Dual64> = (0..n)
                .map(|i| Dual64::new(op.q[i], f64::from(u8::from(col == i))))
                .collect();
            let vd: Vec<Dual64> = (0..n)
                .map(|i| Dual64::new(op.nu[i], f64::from(u8::from(col == n + i))))
                .collect();
            let (x, v) = td.nodal(&qd, &vd);
            for b in 0..nb {
                let mut th = Vec3::zeros();
                for i in 0..3 {
                    let o = 12 * b + 3 + 3 * i;
                    let d = Vec3::new(x[o].re, x[o + 1].re, x[o + 2].re);
                    let dd = Vec3::new(x[o].eps, x[o + 1].eps, x[o + 2].eps);
                    th += d.cross(&dd) * 0.5;
                }
                for a in 0..3 {
                    let at = col * 6 * nb + 6 * b;
                    worst = worst.max((emb.xi[at + a] - x[12 * b + a].eps).abs());
                    worst = worst.max((emb.xi[at + 3 + a] - th[a]).abs());
                }
            }
            for (k, vi) in v.iter().enumerate() {
                worst = worst.max((emb.dv[col * 12 * nb + k] - vi.eps).abs());
            }
        }
        eprintln!("{name}: embedding, largest difference {worst:.1e}");
        assert!(worst < 1e-12, "{name}: embedding {worst:e}");
        // the read-off at nodal velocities off the tree's, along arbitrary columns
        let (xq, mut xv) = td.nodal(&op.q, &op.nu);
        for (i, x) in xv.iter_mut().enumerate() {
            *x += 0.3 * wiggle(i);
        }
        let cols = 7;
        let cols = NodalColumns {
            cols,
            xi: (0..6 * nb * cols).map(|i| wiggle(i + 1000)).collect(),
            dv: (0..12 * nb * cols).map(|i| wiggle(i + 5000)).collect(),
        };
        let a = td.readoff_tangent(&op.q, &xq, &xv, &cols, None).unwrap();
        let b = td
            .readoff_tangent_by_duals(&op.q, &xq, &xv, &cols, None)
            .unwrap();
        let e = (&a - &b).norm() / b.norm();
        eprintln!("{name}: read-off, |analytic − duals|/|duals| = {e:.1e}");
        assert!(e < 1e-12, "{name}: read-off {e:e}");
    }
}
