//! Initial rates that violate the loop velocity constraints are replaced, at set-up, by their
//! M-orthogonal projection onto the admissible velocities (least change in kinetic energy),
//! computed with the bordered tree solve; it matches the dense SVD of
//! `loops::project_loop_velocities` on the four-bar and on a 30-link chain closed to an earlier
//! body, and the model notes it.
use crate::mechanics::model::def::{JointInitial, ModelDef, SolverSettings};
use crate::mechanics::model::fixtures::{chain_loop, four_bar};
use crate::mechanics::model::kinematics::initial_configuration;
use crate::mechanics::model::loops::project_loop_velocities;
use crate::mechanics::model::runtime::Model;

fn assert_projected_like_the_oracle(def: &ModelDef) {
    let (q0, mut v0) = initial_configuration(def).expect("configuration");
    assert!(
        project_loop_velocities(def, &q0, &mut v0).expect("oracle"),
        "the rates should violate the loop"
    );
    let model = Model::new(def, SolverSettings::default()).expect("model");
    let scale = v0.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let diff = model
        .v0
        .iter()
        .zip(&v0)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(diff <= 1e-12 * scale, "{diff:e} (scale {scale:e})");
    assert!(
        model.notes().iter().any(|n| n.contains("projected")),
        "{:?}",
        model.notes()
    );
}

#[test]
fn four_bar_rates_are_projected_like_the_dense_oracle() {
    assert_projected_like_the_oracle(&four_bar());
}

#[test]
fn closed_chain_rates_are_projected_like_the_dense_oracle() {
    let mut def = chain_loop(30, Some(3), 3e-4);
    for (k, j) in def
        .joints
        .iter_mut()
        .enumerate()
        .filter(|(_, j)| !j.loop_closing)
    {
        if let JointInitial::Coords { qd, .. } = &mut j.initial {
            qd[0] = 0.3 + 0.1 * (k as f64).sin();
        }
    }
    assert_projected_like_the_oracle(&def);
}
