//! The reduced iteration (joint increments, discrete null-space method, theory.md §4.5)
//! solves the same equations as the multiplier form: `P̄ᵀ r(Φ(u)) = 0` ⟺ `r = −G(q̄)ᵀλ`,
//! `g(q) = 0`. Trajectories of both agree to the Newton tolerance.
mod common;
use triad::mechanics::{step_state, Model, SolverSettings, State};

fn pair(def: &triad::mechanics::ModelDef, h: f64) -> (Model, Model) {
    let s = SolverSettings { max_step: h, order: 2, tolerance: 1e-10, max_iterations: 20 };
    let m = Model::new(def, s).unwrap();
    let mut m2 = m.clone();
    m2.set_reduced_solver(false);
    assert!(m.uses_reduced_solver() && !m2.uses_reduced_solver());
    (m, m2)
}

#[test]
fn debug_dp() {
    let (m, m2) = pair(&common::double_pendulum(), 1e-3);
    let (mut a, mut b) = (State::new(&m), State::new(&m2));
    for k in 0..5 {
        let sa = step_state(&m, &mut a, 1e-3).unwrap();
        let sb = step_state(&m2, &mut b, 1e-3).unwrap();
        let d = a.coordinates().iter().zip(b.coordinates()).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
        eprintln!("{k}: {:?} {:?} diff {d:e}", sa, sb);
    }
}
