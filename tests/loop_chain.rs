//! Long closed chains through the bordered tree solve: a 50-link chain closed by a loop-closing
//! revolute (to the world, and to an earlier body, which couples bodies that are not adjacent
//! in the tree) runs 1000 steps (h = 1e-3, order 2, conservative: gravity only) with the energy
//! conserved to 1e-12 relative and the constraints held to 1e-10, taking the same Newton
//! iterations and factorisations, step by step, as the dense LU oracle.

mod common;
use common::*;
use triad::mechanics::{step_state, ModelDef, State};

/// Per-step (iterations, factorisations), the largest relative energy change and constraint
/// residual (checked every 10 steps and at the end), and the final energy.
fn run(def: &ModelDef, dense: bool, steps: usize) -> (Vec<(usize, usize)>, f64, f64, f64) {
    let h = 1e-3;
    let (mut m, _) = build(def, settings(h, 2));
    m.set_dense_solver(dense);
    assert_eq!(m.uses_dense_solver(), dense);
    let mut s = State::new(&m);
    let e0 = s.outputs().energy;
    let (mut de, mut cr) = (0.0_f64, s.outputs().constraint_residual);
    let mut counts = Vec::with_capacity(steps);
    for i in 0..steps {
        let st = step_state(&m, &mut s, h).expect("step");
        counts.push((st.iterations, st.factorizations));
        if i % 10 == 9 || i + 1 == steps {
            s.refresh_outputs(&m);
            de = de.max((s.outputs().energy - e0).abs() / e0.abs());
            cr = cr.max(s.outputs().constraint_residual);
        }
    }
    (counts, de, cr, s.outputs().energy)
}

fn check(def: &ModelDef, name: &str) {
    let (m, _) = build(def, settings(1e-3, 2));
    assert!(
        !m.uses_dense_solver(),
        "loops must not use the dense solver"
    );
    assert!(
        m.notes().iter().all(|n| !n.contains("redundant")),
        "{:?}",
        m.notes()
    );
    let (cb, deb, crb, eb) = run(def, false, 1000);
    let (cd, ded, crd, ed) = run(def, true, 1000);
    let its = |c: &[(usize, usize)]| c.iter().map(|x| x.0).sum::<usize>();
    eprintln!(
        "{name}: bordered {} iterations, energy {deb:.1e}, constraints {crb:.1e}; dense {} iterations, energy {ded:.1e}, constraints {crd:.1e}; final energies differ by {:.1e}",
        its(&cb),
        its(&cd),
        (eb - ed).abs() / ed.abs()
    );
    assert!(deb <= tol(1e-12), "{name}: energy drift {deb:e}");
    assert!(crb <= tol(1e-10), "{name}: constraint residual {crb:e}");
    let first = cb.iter().zip(&cd).position(|(a, b)| a != b);
    assert!(
        first.is_none(),
        "{name}: iteration counts differ from the dense oracle first at step {first:?}"
    );
}

#[test]
fn chain50_closed_to_world_conserves_energy_like_dense() {
    check(&chain_loop(50, None, 0.0, 0.0), "chain50 → world");
}

#[test]
fn chain50_closed_to_an_earlier_body_conserves_energy_like_dense() {
    check(&chain_loop(50, Some(10), 0.0, 0.0), "chain50 → link11");
}
