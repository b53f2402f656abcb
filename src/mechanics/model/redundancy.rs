//! Redundant constraint rows at set-up (models with loop-closing joints).
//!
//! In twist coordinates (`[φ̇ · lc⁻¹… , ω]` per body: the linear columns scaled by the
//! characteristic length `lc` so that lengths and angles weigh alike) every joint row is a
//! vector `a` of length `6 N`. The rows of the spanning tree's joints are independent; a loop
//! row is kept when its component orthogonal to the span of the tree rows and of the loop rows
//! kept before it is above `1e-9 |a|`, and dropped (reported by the caller) otherwise.
//!
//! Computed without forming that span: with `A` the tree rows, the orthogonal projection of a
//! loop row onto `null(A)` solves
//!
//! ```text
//! [ I   Aᵀ ] [ y ]   [ aᵀ ]
//! [ A   0  ] [ λ ] = [ 0  ]          y = aᵀ − Aᵀλ,  A y = 0
//! ```
//!
//! which has the block-tree structure of the Newton matrix (identity body blocks, the rows of
//! each tree joint with its child, couplings along tree edges), so the O(N) tree elimination
//! of `solver` factors it once and every loop row costs one O(N) solve. The component of a
//! loop row orthogonal to the tree rows and the kept loop rows is that of `y` orthogonal to the
//! kept rows' projections (span(T ∪ L) = span(T) ⊕ span(P⊥L)), found by Gram–Schmidt over the
//! k loop rows: O(N k + N k²) in all, where the Gram–Schmidt over all rows cost O(N³) (24 s
//! for a 400-link chain closed by one joint). That direct Gram–Schmidt remains as the fallback
//! when the tree rows are themselves singular, and as the test oracle.
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use crate::mechanics::linalg::tree::{factor_tree, solve_factored, Block, NMAX};

use super::joint::JointGeom;
use super::loops::row_twists;
use super::runtime::Model;

/// Relative size below which a row's new component counts as zero.
const RANK_TOL: f64 = 1e-9;

/// [`row_twists`] of `g` at `q` with the linear columns times `lc`.
fn twist_rows(g: &JointGeom, q: &[f64], lc: f64) -> Vec<([f64; 6], [f64; 6])> {
    let scale = |mut t: [f64; 6]| {
        t[..3].iter_mut().for_each(|x| *x *= lc);
        t
    };
    row_twists(g, q)
        .into_iter()
        .map(|(pa, ch)| (scale(pa), scale(ch)))
        .collect()
}

/// Which rows to keep (`keep[j][k]`): all of them for a tree; with loops, the loop rows that
/// are independent of the tree rows and of the loop rows before them (module docs).
pub(crate) fn redundant_rows(model: &Model, geoms: &[JointGeom]) -> Vec<Vec<bool>> {
    let def = model.def();
    let mut keep: Vec<Vec<bool>> = geoms.iter().map(|g| vec![true; g.rows.len()]).collect();
    if !def.joints.iter().any(|j| j.loop_closing) {
        return keep;
    }
    let nb = def.bodies.len();
    let (q, lc) = (&model.q0, model.lc);
    // the tree KKT [I Aᵀ; A 0], one supernode per body with its tree joint's rows
    let mut blocks: Vec<Block> = (0..nb)
        .map(|b| Block::new(6 + model.tree_joint[b].map_or(0, |j| geoms[j].rows.len())))
        .collect();
    for b in 0..nb {
        let blk = &mut blocks[b];
        for i in 0..6 {
            blk.d[i * NMAX + i] = 1.0;
        }
        let Some(j) = model.tree_joint[b] else {
            continue;
        };
        for (k, (pa, ch)) in twist_rows(&geoms[j], q, lc).iter().enumerate() {
            for s in 0..6 {
                blk.d[(6 + k) * NMAX + s] = ch[s];
                blk.d[s * NMAX + 6 + k] = ch[s];
                if model.parent[b].is_some() {
                    blk.u[(6 + k) * 6 + s] = pa[s];
                    blk.l[s * NMAX + 6 + k] = pa[s];
                }
            }
        }
    }
    if !factor_tree(&mut blocks, &model.order, &model.parent) {
        return gram_schmidt(model, geoms);
    }
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for (j, g) in geoms.iter().enumerate() {
        if !def.joints[j].loop_closing {
            continue;
        }
        for (k, (pa, ch)) in twist_rows(g, q, lc).iter().enumerate() {
            for blk in &mut blocks {
                blk.r.fill(0.0);
            }
            blocks[g.child].r[..6].copy_from_slice(ch);
            if let Some(p) = g.parent {
                for s in 0..6 {
                    blocks[p].r[s] += pa[s];
                }
            }
            let n0 = pa.iter().chain(ch).map(|x| x * x).sum::<f64>().sqrt();
            solve_factored(&mut blocks, &model.order, &model.parent);
            let mut y: Vec<f64> = blocks.iter().flat_map(|b| b.r[..6].to_vec()).collect();
            if reduce(&mut y, &basis, n0) {
                basis.push(y);
            } else {
                keep[j][k] = false;
            }
        }
    }
    keep
}

/// Removes from `r` (twice, for round-off) its components along the orthonormal `basis`;
/// true and `r` normalised if what is left is above `RANK_TOL · n0`.
fn reduce(r: &mut [f64], basis: &[Vec<f64>], n0: f64) -> bool {
    for _ in 0..2 {
        for e in basis {
            let p: f64 = r.iter().zip(e).map(|(x, y)| x * y).sum();
            r.iter_mut().zip(e).for_each(|(x, y)| *x -= p * y);
        }
    }
    let n1 = r.iter().map(|x| x * x).sum::<f64>().sqrt();
    if n0 == 0.0 || !n1.is_finite() || n1 <= RANK_TOL * n0 {
        return false;
    }
    r.iter_mut().for_each(|x| *x /= n1);
    true
}

/// The direct Gram–Schmidt over every row (tree joints first), O(N³): the fallback when the
/// tree rows are singular, and the oracle of the tests.
pub(crate) fn gram_schmidt(model: &Model, geoms: &[JointGeom]) -> Vec<Vec<bool>> {
    let def = model.def();
    let mut keep: Vec<Vec<bool>> = geoms.iter().map(|g| vec![true; g.rows.len()]).collect();
    let nb = def.bodies.len();
    let order: Vec<usize> = (0..geoms.len())
        .filter(|&j| !def.joints[j].loop_closing)
        .chain((0..geoms.len()).filter(|&j| def.joints[j].loop_closing))
        .collect();
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for j in order {
        let g = &geoms[j];
        for (k, (pa, ch)) in twist_rows(g, &model.q0, model.lc).iter().enumerate() {
            let mut r = vec![0.0; 6 * nb];
            r[6 * g.child..6 * g.child + 6].copy_from_slice(ch);
            if let Some(p) = g.parent {
                for s in 0..6 {
                    r[6 * p + s] += pa[s];
                }
            }
            let n0 = r.iter().map(|x| x * x).sum::<f64>().sqrt();
            if reduce(&mut r, &basis, n0) {
                basis.push(r);
            } else {
                keep[j][k] = false;
            }
        }
    }
    keep
}

#[cfg(test)]
#[path = "redundancy_tests.rs"]
mod tests;
