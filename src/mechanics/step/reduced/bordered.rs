//! The workspace of the couplings' bordered solve in the reduced iteration (`couple`): per
//! coupling its row value, its columns on the coupled joints' rates and its rows on the body
//! twists, set by each evaluation, and the factors of the Schur matrix `S = G J⁻¹ E`.

use super::maps::V6;
use crate::mechanics::model::runtime::{CouplingRt, Model};

/// One coupling's entries of the bordered solve, set by each evaluation.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Slot {
    /// The row's value `g_c` at the iterate (rad or m).
    pub g: f64,
    /// Its column per joint (following joint first): `(child body, entries, wrench)`, the
    /// entries either the reaction's wrench on the child for unit multiplier (`wrench`, the
    /// node path: `S̄ᵀ` is applied at factorisation) or already the rates' (joint space).
    pub col: [(usize, V6, bool); 2],
    /// Its rows `G_c` on the body twists: `(body, row)` for the two joints' children and
    /// parents (`usize::MAX`: the world).
    pub row: [(usize, V6); 4],
}

impl Slot {
    /// Sets the column and the rows of coupling `cp` on its joint `j` (child `b`, parent `a`,
    /// `None`: the world): `col` (a wrench on the child if `wrench`, else the rates' entries)
    /// and the rows on the child's and the parent's twists.
    pub fn put(
        &mut self,
        (cp, j): (&CouplingRt, usize),
        (b, a): (usize, Option<usize>),
        (col, wrench): (V6, bool),
        [row_b, row_a]: [V6; 2],
    ) {
        // the following joint's entries first (`CouplingRt::weighted`)
        let k = usize::from(cp.b != j);
        self.col[k] = (b, col, wrench);
        self.row[2 * k] = (b, row_b);
        self.row[2 * k + 1] = (a.unwrap_or(usize::MAX), row_a);
    }
}

/// Per-model coupling data of the reduced iteration (empty without couplings).
#[derive(Clone, Debug, Default)]
pub(crate) struct Couplings {
    /// The couplings acting on each joint: `(coupling, weight)`.
    pub on_joint: Vec<Vec<(usize, f64)>>,
    /// Each coupling's entries.
    pub slots: Vec<Slot>,
    /// `z_d` per coupling: body twists of the unit column's solve.
    pub z: Vec<Vec<V6>>,
    /// The Schur matrix `S` (row-major `k × k`), LU-factored in place.
    pub schur: Vec<f64>,
    /// Row permutation of the LU.
    pub perm: Vec<usize>,
    /// The reduced residual kept across the column solves and the tree solve.
    pub keep: Vec<V6>,
    /// The children of coupled joints (each once).
    pub bodies: Vec<usize>,
    /// Whether each body is among `bodies`.
    pub coupled: Vec<bool>,
    /// The reduced columns `e_d` on the children's rates, per coupling.
    pub e: Vec<[(usize, V6); 2]>,
    /// Right-hand side, then `δμ`.
    pub rhs: Vec<f64>,
}

impl Couplings {
    /// Workspace for `model`'s couplings.
    pub fn new(model: &Model) -> Self {
        let k = model.couplings.len();
        if k == 0 {
            return Self::default();
        }
        let nb = model.bodies.len();
        let mut on_joint = vec![Vec::new(); model.joints.len()];
        let mut coupled = vec![false; nb];
        let mut bodies = Vec::new();
        for c in 0..k {
            for (j, w) in model.couplings[c].weighted() {
                on_joint[j].push((c, w));
                let b = model.joints[j].child;
                if !coupled[b] {
                    coupled[b] = true;
                    bodies.push(b);
                }
            }
        }
        Self {
            on_joint,
            slots: vec![
                Slot {
                    g: 0.0,
                    col: [(0, [0.0; 6], false); 2],
                    row: [(usize::MAX, [0.0; 6]); 4],
                };
                k
            ],
            z: vec![vec![[0.0; 6]; nb]; k],
            schur: vec![0.0; k * k],
            perm: vec![0; k],
            keep: vec![[0.0; 6]; nb],
            bodies,
            coupled,
            e: vec![[(0, [0.0; 6]); 2]; k],
            rhs: vec![0.0; k],
        }
    }
}
