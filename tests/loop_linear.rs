//! Closed loops in independent coordinates: `triad linearize`'s exact A, B (against central
//! differences of the constrained accelerations) and Ad, Bd (against central differences of the
//! step itself), on the shipped four-bar and slider-crank.

use nalgebra::DMatrix;
use triad::mechanics::{Independent, ModelDef, Operating, SolverSettings};
use triad::sim::Simulation;

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
fn end_of(def: &ModelDef, settings: SolverSettings, op: &Operating, x: &[f64], u: &[f64], h: f64) -> Vec<f64> {
    let d = op.initial_def(def, x);
    let mut sim = Simulation::new(&d, settings, 0.0).unwrap();
    sim.state_mut().inputs_mut().copy_from_slice(u);
    sim.advance(h).unwrap();
    Operating::picked(sim.model(), sim.state(), &same(op)).unwrap().x()
}

fn step_differences(def: &ModelDef, settings: SolverSettings, op: &Operating, u: &[f64], h: f64, ex: f64, eu: f64) -> (DMatrix<f64>, DMatrix<f64>) {
    let x0 = op.x();
    let (nx, nu) = (x0.len(), u.len());
    let mut ad = DMatrix::zeros(nx, nx);
    let mut bd = DMatrix::zeros(nx, nu);
    for k in 0..nx + nu {
        let eps = if k < nx { ex } else { eu };
        let run = |s: f64| {
            let (mut x, mut uu) = (x0.clone(), u.to_vec());
            if k < nx { x[k] += s } else { uu[k - nx] += s }
            end_of(def, settings, op, &x, &uu, h)
        };
        let (p, m) = (run(eps), run(-eps));
        for r in 0..nx {
            let v = (p[r] - m[r]) / (2.0 * eps);
            if k < nx { ad[(r, k)] = v } else { bd[(r, k - nx)] = v }
        }
    }
    (ad, bd)
}

fn exact_step(def: &ModelDef, settings: SolverSettings, op: &Operating, u: &[f64], h: f64) -> (DMatrix<f64>, DMatrix<f64>) {
    let d = op.initial_def(def, &op.x());
    let mut sim = Simulation::new(&d, settings, 0.0).unwrap();
    sim.state_mut().inputs_mut().copy_from_slice(u);
    let map = sim.step_map_in(h, &same(op)).unwrap();
    (map.ad, map.bd)
}

#[test]
fn debug_four_bar() {
    let (def, settings) = lower(FOUR_BAR);
    let op = operating(&def, settings, &Independent::Auto);
    let u = vec![0.3];
    for h in [1e-3, 1e-2] {
        let (ad, bd) = exact_step(&def, settings, &op, &u, h);
        let (fa, fb) = step_differences(&def, settings, &op, &u, h, 1e-5, 1e-4);
        eprintln!("h={h} ad {ad} fd {fa} bd {bd} fd {fb}");
    }
}

#[test]
fn debug_roundtrip() {
    let (def, settings) = lower(FOUR_BAR);
    let op = operating(&def, settings, &Independent::Auto);
    let d = op.initial_def(&def, &op.x());
    let mut sim = Simulation::new(&d, settings, 0.0).unwrap();
    let model = sim.model().clone();
    let end = triad::mechanics::begin_step_map(&model, sim.state_mut(), &Independent::Auto).unwrap();
    let map = triad::mechanics::finish_step_map(&model, sim.state_mut(), &end).unwrap();
    eprintln!("roundtrip {}", map.ad);
    let (ad, _) = exact_step(&def, settings, &op, &[0.0], 1e-7);
    eprintln!("tiny {}", ad);
}
