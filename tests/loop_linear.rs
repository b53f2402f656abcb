//! Closed loops in independent coordinates, on the shipped four-bar and slider-crank and on
//! joint couplings (two coupled pendulums and slides): the exact
//! A, B against central differences of the constrained dynamics (f64), the constrained
//! accelerations against the natural-coordinate step, Ad, Bd against central differences of the
//! step itself, `(Ad − I)/h → A`, other independent coordinates giving a similar A at an
//! equilibrium, and the four-bar's gravity equilibrium a centre (imaginary eigenvalues).

use nalgebra::DMatrix;
use triad::mechanics::Quantity;
use triad::mechanics::{Independent, ModelDef, Operating, SolverSettings};
use triad::sim::Simulation;

mod common;
use common::trees::COUPLED;

const FOUR_BAR: &str = include_str!("../modelDescription/four_bar/spec.toml");
const SLIDER_CRANK: &str = include_str!("../modelDescription/slider_crank/spec.toml");

fn lower(text: &str) -> (ModelDef, SolverSettings) {
    let spec = triad::spec::Spec::from_str(text, triad::spec::Format::Toml, "test.toml")
        .unwrap_or_else(|e| panic!("{e}"));
    spec.lower().unwrap()
}

fn operating(def: &ModelDef, settings: SolverSettings, pick: &Independent) -> Operating {
    let sim = Simulation::new(def, settings, 0.0).unwrap();
    Operating::picked(sim.model(), sim.state(), pick).unwrap()
}

fn same(op: &Operating) -> Independent {
    Independent::Coords(op.loops.as_ref().unwrap().indep.clone())
}

/// The state one communication step `h` after `x` with inputs `u`.
fn end_of(
    def: &ModelDef,
    settings: SolverSettings,
    op: &Operating,
    x: &[f64],
    u: &[f64],
    h: f64,
) -> Vec<f64> {
    let d = op.initial_def(def, x);
    let mut sim = Simulation::new(&d, settings, 0.0).unwrap();
    sim.state_mut().inputs_mut().copy_from_slice(u);
    sim.advance(h).unwrap();
    Operating::picked(sim.model(), sim.state(), &same(op))
        .unwrap()
        .x()
}

fn step_differences(
    def: &ModelDef,
    settings: SolverSettings,
    op: &Operating,
    u: &[f64],
    h: f64,
    ex: f64,
    eu: f64,
) -> (DMatrix<f64>, DMatrix<f64>) {
    let x0 = op.x();
    let (nx, nu) = (x0.len(), u.len());
    let mut ad = DMatrix::zeros(nx, nx);
    let mut bd = DMatrix::zeros(nx, nu);
    for k in 0..nx + nu {
        let eps = if k < nx { ex } else { eu };
        let run = |s: f64| {
            let (mut x, mut uu) = (x0.clone(), u.to_vec());
            if k < nx {
                x[k] += s
            } else {
                uu[k - nx] += s
            }
            end_of(def, settings, op, &x, &uu, h)
        };
        let (p, m) = (run(eps), run(-eps));
        for r in 0..nx {
            let v = (p[r] - m[r]) / (2.0 * eps);
            if k < nx {
                ad[(r, k)] = v
            } else {
                bd[(r, k - nx)] = v
            }
        }
    }
    (ad, bd)
}

fn exact_step(
    def: &ModelDef,
    settings: SolverSettings,
    op: &Operating,
    u: &[f64],
    h: f64,
) -> (DMatrix<f64>, DMatrix<f64>) {
    let d = op.initial_def(def, &op.x());
    let mut sim = Simulation::new(&d, settings, 0.0).unwrap();
    sim.state_mut().inputs_mut().copy_from_slice(u);
    let map = sim.step_map_in(h, &same(op)).unwrap();
    (map.ad, map.bd)
}

/// `A` at `op` and `x`, u: `ẋ(x, u)` by the plain f64 path (completion, KKT solve).
fn xdot(op: &Operating, x: &[f64], u: &[f64]) -> Vec<f64> {
    let cl = op.loops.as_ref().unwrap();
    let (q, nu) = op.tree_of(x).unwrap();
    let nud = cl.accelerations(&op.dynamics, &q, &nu, u).unwrap();
    let mut out = cl.pick(&op.dynamics.qdot(&q, &nu));
    out.extend(cl.pick(&nud));
    out
}

fn rel(a: &DMatrix<f64>, b: &DMatrix<f64>) -> f64 {
    (a - b).norm() / b.norm().max(1e-300)
}

/// The operating point at state `x` (coordinates of `op`) with inputs `u`.
fn at(def: &ModelDef, settings: SolverSettings, op: &Operating, x: &[f64], u: &[f64]) -> Operating {
    let d = op.initial_def(def, x);
    let sim = Simulation::new(&d, settings, 0.0).unwrap();
    let mut o = Operating::picked(sim.model(), sim.state(), &same(op)).unwrap();
    o.u = u.to_vec();
    o
}

const MODELS: [(&str, &str, &[f64]); 3] = [
    ("four-bar", FOUR_BAR, &[0.3]),
    ("slider-crank", SLIDER_CRANK, &[0.7, -2.0]),
    ("coupled", COUPLED, &[0.4, -0.3]),
];

/// A, B, C against central differences (step 1e-6) of the f64 evaluation (Newton completion
/// and KKT solve in f64): measured 1e-10–1e-9, bound 1e-7.
#[test]
fn a_b_agree_with_differences_of_the_constrained_dynamics() {
    for (name, text, u) in MODELS {
        let (def, settings) = lower(text);
        let mut op = operating(&def, settings, &Independent::Auto);
        op.u = u.to_vec();
        let ys = [
            Quantity::JointQ(1, 0),
            Quantity::JointQd(2, 0),
            Quantity::BodyR(1, 2),
            Quantity::JointQdd(1, 0),
        ];
        let lin = op.linearize(&ys).unwrap();
        let x0 = op.x();
        let (nx, nu) = (x0.len(), u.len());
        let mut fa = DMatrix::zeros(nx, nx);
        let mut fb = DMatrix::zeros(nx, nu);
        let mut fc = DMatrix::zeros(ys.len(), nx);
        let eps = 1e-6;
        let y_of = |x: &[f64], uu: &[f64]| -> Vec<f64> {
            let (q, nu) = op.tree_of(x).unwrap();
            let nud = op
                .loops
                .as_ref()
                .unwrap()
                .accelerations(&op.dynamics, &q, &nu, uu)
                .unwrap();
            ys.iter()
                .map(|y| op.dynamics.quantity(&q, &nu, &nud, *y))
                .collect()
        };
        for k in 0..nx + nu {
            let f = |s: f64| {
                let (mut x, mut uu) = (x0.clone(), u.to_vec());
                if k < nx {
                    x[k] += s
                } else {
                    uu[k - nx] += s
                }
                (xdot(&op, &x, &uu), y_of(&x, &uu))
            };
            let ((pa, py), (ma, my)) = (f(eps), f(-eps));
            for r in 0..nx {
                let v = (pa[r] - ma[r]) / (2.0 * eps);
                if k < nx {
                    fa[(r, k)] = v
                } else {
                    fb[(r, k - nx)] = v
                }
            }
            if k < nx {
                for r in 0..ys.len() {
                    fc[(r, k)] = (py[r] - my[r]) / (2.0 * eps);
                }
            }
        }
        let (ea, eb, ec) = (rel(&lin.a, &fa), rel(&lin.b, &fb), rel(&lin.c, &fc));
        eprintln!("{name}: |A−fd|/|fd| = {ea:.2e}, |B−fd|/|fd| = {eb:.2e}, |C−fd|/|fd| = {ec:.2e}");
        assert!(
            ea < 1e-7 && eb < 1e-7 && ec < 1e-7,
            "{name}: {ea:e} {eb:e} {ec:e}"
        );
        let x1 = xdot(&op, &x0, u);
        for (a, b) in lin.xdot0.iter().zip(&x1) {
            assert!((a - b).abs() <= 1e-12 * (1.0 + b.abs()));
        }
    }
}

/// The constrained accelerations are the natural-coordinate step's: from (q, ν) and from
/// (q, −ν) one step of h each, `a(h) = (ν(h) + ν'(h)) / 2h = ν̇ + O(h²)` (time symmetry; the
/// models have no dampers), extrapolated `(4 a(h/2) − a(h)) / 3` from h = 2e-4, Newton
/// tolerance 1e-13. Measured relative error 1e-13–1e-12, bound 1e-9.
#[test]
fn constrained_accelerations_agree_with_the_step() {
    for (name, text, u) in MODELS {
        let (def, mut settings) = lower(text);
        settings.tolerance = 1e-13;
        let mut op = operating(&def, settings, &Independent::Auto);
        op.u = u.to_vec();
        let x0 = op.x();
        let k = x0.len() / 2;
        let nud = op.accelerations().unwrap();
        let run = |sign: f64, h: f64| -> Vec<f64> {
            let mut x = x0.clone();
            for v in &mut x[k..] {
                *v *= sign;
            }
            let mut s = settings;
            s.max_step = h;
            let d = op.initial_def(&def, &x);
            let mut sim = Simulation::new(&d, s, 0.0).unwrap();
            sim.state_mut().inputs_mut().copy_from_slice(u);
            sim.advance(h).unwrap();
            Operating::picked(sim.model(), sim.state(), &same(&op))
                .unwrap()
                .nu
        };
        let a = |h: f64| -> Vec<f64> {
            let (p, m) = (run(1.0, h), run(-1.0, h));
            p.iter().zip(&m).map(|(a, b)| (a + b) / (2.0 * h)).collect()
        };
        let (a1, a2) = (a(2e-4), a(1e-4));
        let fd: Vec<f64> = a1
            .iter()
            .zip(&a2)
            .map(|(x, y)| (4.0 * y - x) / 3.0)
            .collect();
        let err = nud
            .iter()
            .zip(&fd)
            .map(|(a, b)| (a - b).powi(2))
            .sum::<f64>()
            .sqrt()
            / nud.iter().map(|a| a * a).sum::<f64>().sqrt();
        eprintln!("{name}: ν̇ {nud:?} step {fd:?}: relative {err:.2e}");
        assert!(err < 1e-9, "{name}: {err:e}");
    }
}

/// Ad, Bd against central differences of the step (1e-5 in x, 1e-4 in u), orders 2 and 4,
/// one and several sub-steps: measured agreement 2e-11–2e-9, bound 3e-8 (as for trees).
#[test]
fn step_map_agrees_with_differences_of_the_step() {
    for (name, text, u) in MODELS {
        for (line, order) in [
            ("max_step = 1e-3", "order = 2"),
            ("max_step = 2e-3", "order = 4"),
        ] {
            let (def, settings) = lower(
                &text
                    .replace("max_step = 1e-3", line)
                    .replace("order = 2", order),
            );
            let op = operating(&def, settings, &Independent::Auto);
            for h in [1e-3, 1e-2] {
                let (ad, bd) = exact_step(&def, settings, &op, u, h);
                let (fa, fb) = step_differences(&def, settings, &op, u, h, 1e-5, 1e-4);
                let (ea, eb) = (rel(&ad, &fa), rel(&bd, &fb));
                eprintln!("{name}, {line}, {order}, h={h}: |Ad−fd|/|fd| = {ea:.2e}, |Bd−fd|/|fd| = {eb:.2e}");
                assert!(
                    ea < 3e-8 && eb < 3e-8,
                    "{name} {line} h={h}: {ea:e} {eb:e}\n{ad}{fa}{bd}{fb}"
                );
            }
        }
    }
}

/// `e(h) = |(Ad − I)/h − A| / |A|` falls as h (one sub-step per step, off equilibrium):
/// measured ratios e(h)/e(h/2) of 2.00 (four-bar) and 1.96–1.98 (slider-crank).
#[test]
fn step_map_tends_to_the_continuous_model() {
    for (name, text, u) in MODELS {
        let (def, settings) = lower(&text.replace("max_step = 1e-3", "max_step = 1.0"));
        let mut op = operating(&def, settings, &Independent::Auto);
        op.u = u.to_vec();
        let a = op.linearize(&[]).unwrap().a;
        let nx = a.nrows();
        let err = |h: f64| {
            let (ad, _) = exact_step(&def, settings, &op, u, h);
            ((ad - DMatrix::identity(nx, nx)) / h - &a).norm() / a.norm()
        };
        let (e1, e2, e3) = (err(4e-3), err(2e-3), err(1e-3));
        eprintln!(
            "{name}: e(h) = {e1:.3e}, {e2:.3e}, {e3:.3e}: ratios {:.2}, {:.2}",
            e1 / e2,
            e2 / e3
        );
        for r in [e1 / e2, e2 / e3] {
            assert!(
                (1.9..2.1).contains(&r),
                "{name}: ratio {r}: {e1:e} {e2:e} {e3:e}"
            );
        }
    }
}

fn eigenvalues(a: &DMatrix<f64>) -> Vec<(f64, f64)> {
    let mut ev: Vec<(f64, f64)> = a
        .clone()
        .complex_eigenvalues()
        .iter()
        .map(|z| (z.re, z.im))
        .collect();
    ev.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.total_cmp(&y.1)));
    ev
}

/// A model, its inputs at rest and the other independent joints to pick.
type Case = (
    &'static str,
    &'static [f64],
    &'static [&'static [&'static str]],
);

/// At an equilibrium (the inputs holding the initial pose at rest) every choice of
/// independent coordinates gives a similar A: the same eigenvalues (to 1e-9 relative).
#[test]
fn other_coordinates_give_the_same_eigenvalues() {
    let cases: [Case; 2] = [
        (FOUR_BAR, &[0.0], &[&["crank_coupler"], &["rocker_pivot"]]),
        (SLIDER_CRANK, &[0.0, 0.0], &[&["crank_rod"], &["guide"]]),
    ];
    for (text, u0, picks) in cases {
        let (def, settings) = lower(text);
        let op = operating(&def, settings, &Independent::Auto);
        // at rest, the first input holding the pose: u = −ν̇(u0) / (∂ν̇/∂u)
        let mut x = op.x();
        let k = x.len() / 2;
        x[k..].fill(0.0);
        let rest = at(&def, settings, &op, &x, u0);
        let lin = rest.linearize(&[]).unwrap();
        let mut u = u0.to_vec();
        u[0] -= lin.xdot0[k] / lin.b[(k, 0)];
        let eq = at(&def, settings, &op, &x, &u);
        let base = eq.linearize(&[]).unwrap();
        let xd = base.xdot0.iter().map(|v| v.abs()).fold(0.0, f64::max);
        assert!(xd < 1e-10, "not at rest: {:?}", base.xdot0);
        let ev0 = eigenvalues(&base.a);
        for names in picks {
            let pick = Independent::Joints(names.iter().map(|s| s.to_string()).collect());
            let d = op.initial_def(&def, &x);
            let sim = Simulation::new(&d, settings, 0.0).unwrap();
            let mut other = Operating::picked(sim.model(), sim.state(), &pick).unwrap();
            other.u = u.clone();
            assert_ne!(
                other.loops.as_ref().unwrap().indep,
                eq.loops.as_ref().unwrap().indep
            );
            let ev = eigenvalues(&other.linearize(&[]).unwrap().a);
            let scale = ev0.iter().map(|z| z.0.hypot(z.1)).fold(0.0, f64::max);
            for (a, b) in ev0.iter().zip(&ev) {
                let d = (a.0 - b.0).hypot(a.1 - b.1);
                assert!(d <= 1e-9 * scale, "{names:?}: {ev0:?} vs {ev:?}");
            }
            eprintln!("{names:?}: eigenvalues {ev:?} (auto: {ev0:?})");
        }
    }
}

/// The four-bar hanging at its stable gravity equilibrium (no input, found by continuation
/// in the crank angle and bisection of ν̇) is a conservative pendulum: A's eigenvalues are
/// a pure imaginary pair ±iω.
#[test]
fn four_bar_equilibrium_is_a_centre() {
    let (def, settings) = lower(FOUR_BAR);
    let op0 = operating(&def, settings, &Independent::Auto);
    let acc = |op: &Operating| op.linearize(&[]).unwrap().xdot0[1];
    // continuation in 5° steps from the initial crank angle, at rest
    let mut x = op0.x();
    x[1] = 0.0;
    let mut op = at(&def, settings, &op0, &x, &[0.0]);
    let mut prev = acc(&op);
    let step = std::f64::consts::PI / 36.0;
    let mut bracket = None;
    for _ in 0..72 {
        let mut xn = op.x();
        xn[0] += step;
        let next = at(&def, settings, &op, &xn, &[0.0]);
        let a = acc(&next);
        // ν̇ falls through 0: a restoring (stable) equilibrium
        if prev > 0.0 && a <= 0.0 {
            bracket = Some((op.clone(), next.clone()));
            break;
        }
        prev = a;
        op = next;
    }
    let (mut lo, hi) = bracket.expect("a stable equilibrium within one turn");
    let (mut a, mut b) = (lo.x()[0], hi.x()[0]);
    for _ in 0..60 {
        let m = 0.5 * (a + b);
        let mid = at(&def, settings, &lo, &[m, 0.0], &[0.0]);
        if acc(&mid) > 0.0 {
            a = m;
            lo = mid;
        } else {
            b = m;
        }
    }
    let eq = at(&def, settings, &lo, &[0.5 * (a + b), 0.0], &[0.0]);
    let lin = eq.linearize(&[]).unwrap();
    let ev = eigenvalues(&lin.a);
    eprintln!(
        "four-bar equilibrium at crank {:.6} rad: xdot {:?}, eigenvalues {ev:?}",
        eq.x()[0],
        lin.xdot0
    );
    assert!(lin.xdot0[1].abs() < 1e-9);
    for (re, im) in &ev {
        assert!(re.abs() <= 1e-9 * im.abs() && im.abs() > 0.1, "{ev:?}");
    }
}
