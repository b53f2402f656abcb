//! Linear models with contact and joint friction (`sticking`): the touching points' and the
//! joints' sticking bristles are states. Their continuous-time dynamics agree with the
//! integrator's (one step's slope, Richardson-extrapolated), `A` with central differences of
//! that dynamics, the eigenvalues with the closed forms of a ball resting on the ground, and a
//! box resting on its corners has `A` of rank `2n` with one zero eigenvalue per bristle (the
//! anchors: a family of equilibria) and every other mode decaying. Sliding is refused by name.

mod common;

use common::contact_models::{ball, resting_box, G, K};
use common::spec_model;
use common::trees::ROTOR;
use nalgebra::{DMatrix, DVector};
use triad::mechanics::{step, Model, Operating, Quantity, State};

/// `ẋ = (q̇, ν̇, σ̇)` of the minimal-coordinate dynamics at `x = (q, ν, σ)` (f64).
fn xdot(op: &Operating, x: &[f64]) -> Vec<f64> {
    let td = &op.dynamics;
    let n = td.n();
    let (q, nu, sigma) = (&x[..n], &x[n..2 * n], &x[2 * n..]);
    let res = td.residual_with(q, nu, &vec![0.0; n], &op.u, sigma, false);
    let nud = td
        .mass_matrix(q)
        .lu()
        .solve(&-DVector::from_vec(res))
        .unwrap();
    let mut out = td.qdot(q, nu);
    out.extend(nud.iter());
    out.extend(td.bristle_rates(q, nu));
    out
}

fn max_abs(v: impl IntoIterator<Item = f64>) -> f64 {
    v.into_iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// `(ν, σ)` of the state as the linear model reads them (σ: the bristles on the tangent axes).
fn rates_and_bristles(m: &Model, s: &State) -> Vec<f64> {
    let op = Operating::of(m, s).unwrap();
    let mut out = op.nu.clone();
    out.extend_from_slice(op.dynamics.sticking().sigma0());
    out
}

/// `(ν̇, σ̇)` of the integrator: one step's slope, Richardson-extrapolated (the step is second
/// order and symmetric).
fn integrator_rates(m: &Model, s0: &State, h: f64) -> Vec<f64> {
    let slope = |h: f64| {
        let mut s = s0.clone();
        let a = rates_and_bristles(m, &s);
        step(m, &mut s, h).unwrap();
        let b = rates_and_bristles(m, &s);
        a.iter()
            .zip(&b)
            .map(|(a, b)| (b - a) / h)
            .collect::<Vec<_>>()
    };
    let (s1, s2) = (slope(h), slope(h / 2.0));
    s1.iter().zip(&s2).map(|(a, b)| 2.0 * b - a).collect()
}

/// The ball (pressed in, moving, spinning) and the box under loads, 5 steps of 0.1 ms into
/// the motion (the bristles loaded): name, model, state, inputs.
fn loaded() -> Vec<(&'static str, Model, State, Vec<f64>)> {
    [
        (
            "ball",
            ball([0.002, -0.001, 0.003], [0.03, 0.01, -0.5]),
            vec![0.7, -0.4, 1.0],
        ),
        (
            "box",
            resting_box(),
            vec![1.5, -0.8, 2.0, 0.05, -0.03, 0.02],
        ),
    ]
    .into_iter()
    .map(|(name, text, u)| {
        let (m, mut s) = spec_model(&text);
        s.inputs_mut().copy_from_slice(&u);
        for _ in 0..5 {
            step(&m, &mut s, 1e-4).unwrap();
        }
        (name, m, s, u)
    })
    .collect()
}

/// In contact and moving (pressed in, sliding slowly under the bristle, spinning), with the
/// bristle loaded by earlier steps: the accelerations and the bristles' rates of the linear
/// model's dynamics are the integrator's as h → 0 (to 1e-6 of their size), so the
/// continuous-time limits of the step's laws (`sticking`'s formulas) are right.
#[test]
fn the_dynamics_with_contact_is_the_integrators_limit() {
    for (name, m, s, _) in loaded() {
        assert!(
            max_abs(s.contact_bristles().iter().copied()) > 1e-7,
            "{name}: the bristles are loaded"
        );
        let op = Operating::of(&m, &s).unwrap();
        let n = op.dynamics.n();
        let x = op.x();
        let f = xdot(&op, &x);
        let want = integrator_rates(&m, &s, 2e-6);
        let got = &f[n..];
        let err = max_abs(got.iter().zip(&want).map(|(a, b)| a - b));
        let scale = max_abs(want.iter().copied());
        eprintln!("{name}: |(ν̇, σ̇) − integrator| = {err:.2e} of {scale:.2e}");
        assert!(err <= 1e-6 * scale, "{name}: {got:?}\n{want:?}");
    }
}

/// `A`, `B` (σ columns and rows included) are the exact derivatives of that dynamics: central
/// differences agree to their own accuracy (1e-7 relative).
#[test]
fn a_and_b_are_the_derivatives_of_the_dynamics() {
    for (name, m, s, u) in loaded() {
        let op = Operating::of(&m, &s).unwrap();
        let lin = op.linearize(&[]).unwrap();
        let x = op.x();
        let nx = x.len();
        assert_eq!(lin.a.nrows(), nx);
        let mut fd = DMatrix::zeros(nx, nx);
        for j in 0..nx {
            let e = 1e-6 * (1.0 + x[j].abs());
            let (mut xp, mut xm) = (x.clone(), x.clone());
            xp[j] += e;
            xm[j] -= e;
            let (fp, fm) = (xdot(&op, &xp), xdot(&op, &xm));
            for i in 0..nx {
                fd[(i, j)] = (fp[i] - fm[i]) / (2.0 * e);
            }
        }
        let rel = (&lin.a - &fd).norm() / fd.norm();
        eprintln!("{name}: |A − differences| / |A| = {rel:.2e} ({nx} states)");
        assert!(rel < 1e-7, "{name}: {rel:e}");
        // B: the inputs enter affinely
        let mut op_u = op.clone();
        let mut fdb = DMatrix::zeros(nx, u.len());
        for j in 0..u.len() {
            op_u.u = op.u.clone();
            op_u.u[j] += 1.0;
            let fp = xdot(&op_u, &x);
            op_u.u[j] -= 2.0;
            let fm = xdot(&op_u, &x);
            for i in 0..nx {
                fdb[(i, j)] = (fp[i] - fm[i]) / 2.0;
            }
        }
        let rel_b = (&lin.b - &fdb).norm() / fdb.norm();
        assert!(rel_b < 1e-12, "{name}: B {rel_b:e}");
    }
}

fn eigenvalues(a: &DMatrix<f64>) -> Vec<nalgebra::Complex<f64>> {
    let mut ev: Vec<_> = a.complex_eigenvalues().iter().copied().collect();
    ev.sort_by(|x, y| x.re.total_cmp(&y.re).then(x.im.total_cmp(&y.im)));
    ev
}

/// The ball at rest: x = (r, θ, v, ω, σ) with σ = `contact.shell.s[1]`, `[2]`. Its modes are
/// the closed forms of a sphere on a spring and a bristle: bouncing `λ = −c/2m ± i√(k/m − …)`
/// with `c = k d x = m g d`; rolling on the bristle, whose point sees the mass
/// `1/m* = 1/m + r²/I`, `λ = −c/2m* ± i√(k/m* − (c/2m*)²)` (twice: x and y). Every other
/// eigenvalue is 0: the ball's turns θ meet no stiffness and the bristle's anchor is free (rank
/// 2n − 3 = 9).
#[test]
fn a_resting_ball_has_the_closed_form_modes() {
    let (m, s) = spec_model(&ball([0.0; 3], [0.0; 3]));
    let op = Operating::of(&m, &s).unwrap();
    let names = op.state_names(&m);
    assert_eq!(names[12..], ["contact.shell.s[1]", "contact.shell.s[2]"]);
    let lin = op.linearize(&[]).unwrap();
    assert!(max_abs(lin.xdot0.iter().copied()) < 1e-9, "{:?}", lin.xdot0);
    let (mass, inertia, r, d) = (1.0, 0.004, 0.1, 0.5);
    let c = mass * G * d;
    let mstar = 1.0 / (1.0 / mass + r * r / inertia);
    let modes = |mm: f64| {
        let re = -c / (2.0 * mm);
        (re, (K / mm - re * re).sqrt())
    };
    let ev = eigenvalues(&lin.a);
    let (bounce, roll) = (modes(mass), modes(mstar));
    let near = |re: f64, im: f64| {
        ev.iter()
            .filter(|e| {
                (e.re - re).abs() < 1e-9 * K.sqrt() && (e.im.abs() - im).abs() < 1e-9 * K.sqrt()
            })
            .count()
    };
    assert_eq!(near(bounce.0, bounce.1), 2, "{ev:?}");
    assert_eq!(near(roll.0, roll.1), 4, "{ev:?}");
    let zeros = ev.iter().filter(|e| e.norm() < 1e-6 * K.sqrt()).count(); // Jordan blocks: √ε
    assert_eq!(zeros, 8, "{ev:?}");
    assert_eq!(lin.a.rank(1e-9 * lin.a.norm()), 9);
}

/// A box resting on its four lower corners holds every coordinate (normal springs: height, roll,
/// pitch; bristles: x, y, yaw): `A` has rank 2n = 12 of its 2n + 8 states, exactly 8 zero
/// eigenvalues (the anchors of the 8 bristle components: every placement is an equilibrium)
/// and every other mode decays (Re λ < 0).
#[test]
fn a_resting_box_has_the_right_rank_and_decaying_modes() {
    let (m, s) = spec_model(&resting_box());
    let op = Operating::of(&m, &s).unwrap();
    let names = op.state_names(&m);
    assert_eq!(names.len(), 20);
    assert_eq!(names[12], "contact.block.s[1,1]");
    let lin = op.linearize(&[]).unwrap();
    assert!(max_abs(lin.xdot0.iter().copied()) < 1e-9, "{:?}", lin.xdot0);
    let ev = eigenvalues(&lin.a);
    let scale = ev.iter().fold(0.0_f64, |m, e| m.max(e.norm()));
    let zeros = ev.iter().filter(|e| e.norm() < 1e-10 * scale).count();
    assert_eq!(zeros, 8, "{ev:?}");
    assert!(
        ev.iter().all(|e| e.norm() < 1e-10 * scale || e.re < -1e-3),
        "{ev:?}"
    );
    assert_eq!(lin.a.rank(1e-10 * lin.a.norm()), 12);
}

/// Sliding has no continuous-time limit: refused by name, for a contact (the ball thrown
/// sideways without spin slides at the cone) and for joint friction (a joint whose bristle is
/// loaded past the limit).
#[test]
fn sliding_is_refused_by_name() {
    let (m, s) = spec_model(&ball([1.0, 0.0, 0.0], [0.0; 3]));
    let e = Operating::of(&m, &s).unwrap_err().to_string();
    assert!(e.contains("contact.shell (point 1) slides"), "{e}");
    // the rotor's bristle: loaded to 0.5 N·m at once, it slides
    let text = format!("{ROTOR}friction = 0.5\n");
    let (m, mut s) = spec_model(&text);
    s.inputs_mut()[0] = 0.8;
    for _ in 0..50 {
        step(&m, &mut s, 1e-3).unwrap();
    }
    let e = Operating::of(&m, &s).unwrap_err().to_string();
    assert!(e.contains("joint.shaft slides"), "{e}");
}

/// Joint friction sticking: the rotor at rest under a torque below breakaway has the bristle
/// `joint.shaft.s` as a state; the bristle spring `k = C/δ` and damper `c = kτ` give the modes
/// of `I θ̈ + c θ̇ + k θ = 0` (I = 0.04 kg·m²), and the zero of the anchor.
#[test]
fn joint_friction_sticks_as_a_spring_and_damper() {
    let text = format!("{ROTOR}friction = 0.5\n");
    let (m, s) = spec_model(&text);
    let op = Operating::of(&m, &s).unwrap();
    assert_eq!(
        op.state_names(&m),
        ["joint.shaft.q", "joint.shaft.qd", "joint.shaft.s"]
    );
    let lin = op.linearize(&[]).unwrap();
    let (k, i): (f64, f64) = (0.5 / 1e-4, 0.04);
    let c = k * 1e-3;
    let re = -c / (2.0 * i);
    let im = (k / i - re * re).sqrt();
    let ev = eigenvalues(&lin.a);
    assert!(ev[2].norm() < 1e-9, "{ev:?}");
    for e in &ev[..2] {
        assert!(
            (e.re - re).abs() < 1e-9 * im && (e.im.abs() - im).abs() < 1e-9 * im,
            "{ev:?}"
        );
    }
}

/// The contact forces as outputs (`contact.C.f[i]`, `Quantity::ContactForce`): at rest they
/// carry the weight (the ball's and the box's `m g` up, nothing sideways), and in motion, with
/// loaded bristles, their rows of `C` are the derivatives (central differences of the same
/// force, 1e-7 relative; the bristle columns included).
#[test]
fn contact_forces_are_outputs_with_exact_rows() {
    for (text, mass) in [(ball([0.0; 3], [0.0; 3]), 1.0), (resting_box(), 2.0)] {
        let (m, s) = spec_model(&text);
        let op = Operating::of(&m, &s).unwrap();
        let ys: Vec<Quantity> = (0..3).map(|i| Quantity::ContactForce(0, i)).collect();
        let lin = op.linearize(&ys).unwrap();
        let weight = mass * G;
        assert!(lin.y0[0].abs() < 1e-9 * weight && lin.y0[1].abs() < 1e-9 * weight);
        assert!((lin.y0[2] - weight).abs() < 1e-9 * weight, "{:?}", lin.y0);
    }
    for (name, m, s, _) in loaded() {
        let op = Operating::of(&m, &s).unwrap();
        let ys: Vec<Quantity> = (0..3).map(|i| Quantity::ContactForce(0, i)).collect();
        let lin = op.linearize(&ys).unwrap();
        let x = op.x();
        let n = op.dynamics.n();
        let force = |x: &[f64]| -> Vec<f64> {
            let (q, nu, sigma) = (&x[..n], &x[n..2 * n], &x[2 * n..]);
            ys.iter()
                .map(|y| op.dynamics.quantity_with(q, nu, &vec![0.0; n], sigma, *y))
                .collect()
        };
        let mut fd = DMatrix::zeros(3, x.len());
        for j in 0..x.len() {
            let e = 1e-6 * (1.0 + x[j].abs());
            let (mut xp, mut xm) = (x.clone(), x.clone());
            xp[j] += e;
            xm[j] -= e;
            let (fp, fm) = (force(&xp), force(&xm));
            for i in 0..3 {
                fd[(i, j)] = (fp[i] - fm[i]) / (2.0 * e);
            }
        }
        let rel = (&lin.c - &fd).norm() / fd.norm();
        eprintln!("{name}: |C − differences| / |C| = {rel:.2e}");
        assert!(rel < 1e-7, "{name}: {rel:e}");
        assert!(
            lin.d.norm() <= 1e-12 * lin.c.norm(),
            "{name}: D {}",
            lin.d.norm()
        );
    }
}
