//! Steps far beyond what the motion resolves: the ten-link chain of thin rods whips its free
//! end at up to ≈ 45 rad/s, 4–9 rad per step at h = 0.1–0.2 s. Its stages fail from the
//! nodal rate, which at such steps carries a component as large as the motion and flipping
//! sign every stage (`v_{n+1} = 2Δq/h − vₙ`), and are retried from the last stages' means
//! before they are halved (`step/predictor.rs`, `Start::Means`). Before the retry the triple
//! jump failed (`Singular`) within 10 s at h = 0.1, and every composition at h = 0.2. Every
//! step taken is an EM step, so `E − E₀ − W` stays at round-off.
mod common;
use common::*;
use triad::mechanics::{step_state, SolverSettings};

#[test]
fn a_whipping_chain_completes_at_unresolved_steps() {
    for (order, stages) in [(2, 3), (4, 3), (4, 5)] {
        for h in [0.1, 0.2] {
            let s = SolverSettings {
                max_step: h,
                order,
                stages,
                ..SolverSettings::default()
            };
            let (m, mut st) = build(&chain(10), s);
            let e0 = st.outputs().energy;
            let n = (10.0 / h).round() as usize;
            let mut worst = 0.0_f64;
            for k in 0..n {
                if let Err(e) = step_state(&m, &mut st, h) {
                    panic!("h = {h}, order {order}/{stages}: step {k} failed: {e}");
                }
                st.refresh_outputs(&m);
                let o = st.outputs();
                worst = worst.max((o.energy - e0 - o.work).abs());
            }
            eprintln!("chain10 h = {h}, order {order}/{stages}: |E − E0 − W| ≤ {worst:.1e} J");
            assert!(
                worst < 1e-11,
                "h = {h}, order {order}/{stages}: {worst:e} J"
            );
        }
    }
}
