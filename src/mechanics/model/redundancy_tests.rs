//! The tree-projected rank test of `redundant_rows` keeps exactly the rows that the direct
//! Gram–Schmidt over all rows keeps: the four-bar (three of its loop rows repeat the tree's in
//! 3-D) and 30-link chains closed to the world and to an earlier body (no redundancy); and a
//! loop joint that duplicates a tree joint is dropped whole.
use super::{gram_schmidt, redundant_rows};
use crate::mechanics::model::def::{ModelDef, SolverSettings};
use crate::mechanics::model::fixtures::{chain_loop, four_bar};
use crate::mechanics::model::joint::JointGeom;
use crate::mechanics::model::runtime::Model;

fn both(def: &ModelDef) -> (Vec<Vec<bool>>, Vec<Vec<bool>>) {
    let model = Model::new(def, SolverSettings::default()).expect("model");
    let geoms: Vec<JointGeom> = def
        .joints
        .iter()
        .map(|j| JointGeom::new(j, &def.bodies).expect("geometry"))
        .collect();
    (redundant_rows(&model, &geoms), gram_schmidt(&model, &geoms))
}

fn dropped(keep: &[Vec<bool>]) -> usize {
    keep.iter().flatten().filter(|k| !**k).count()
}

#[test]
fn four_bar_drops_what_gram_schmidt_drops() {
    let (fast, direct) = both(&four_bar());
    assert_eq!(fast, direct);
    assert!(
        dropped(&fast) > 0,
        "the planar four-bar has redundant loop rows"
    );
}

#[test]
fn closed_chains_keep_every_row() {
    for to in [None, Some(3)] {
        let (fast, direct) = both(&chain_loop(30, to, 3e-4));
        assert_eq!(fast, direct, "closed to {to:?}");
        assert_eq!(dropped(&fast), 0, "closed to {to:?}");
    }
}

#[test]
fn a_duplicate_joint_is_dropped_whole() {
    let mut def = chain_loop(5, None, 3e-4);
    let mut dup = def.joints[2].clone();
    dup.name = "duplicate".into();
    dup.loop_closing = true;
    def.joints.push(dup);
    let (fast, direct) = both(&def);
    assert_eq!(fast, direct);
    let last = fast.last().expect("joints");
    assert!(last.iter().all(|k| !k), "{last:?}");
}
