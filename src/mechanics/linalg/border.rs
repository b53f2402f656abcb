//! Bordered tree solve of the Newton and projection systems of models with loop-closing joints:
//! O(N·t + t³) instead of the O(N³) dense LU, `t = 6·(touched bodies) + k`.
//!
//! Split of the iteration matrix. The spanning tree (every body's 6 unknowns and the rows of its
//! tree joint) is assembled into the tree blocks exactly as for a tree: the matrix `A`, regular
//! by itself (set-up drops redundant rows tree joints first, so only loop rows are ever
//! dropped). Everything a loop-closing joint adds lives in the rows and columns of the bodies it
//! connects, the *touched* bodies (`P`: the `n × 6T` selection of their unknowns, `T` touched
//! bodies; the world touches nothing):
//!
//! * its `k` rows (all loop joints together): multiplier columns `P B_t` and constraint rows
//!   `C_t Pᵀ` (`B_t`: `6T × k`, `C_t`: `k × 6T`), right-hand side `r_c` (`k`);
//! * its body–body couplings `x_ab`, `x_ba` (Hessian terms `½ μ H` of its rows through
//!   `node_block`, and the Jacobians of its spring, damper and actuator loads). Between a tree
//!   parent and child they go into the tree blocks (`L`, `U`) like any tree coupling; between
//!   bodies that are not adjacent in the tree they form `P X Pᵀ` (`X`: `6T × 6T`).
//!
//! These off-tree couplings are kept, not dropped: they are O(μ) and O(h²·loads), dropping them
//! turns Newton into a chord-like iteration whose contraction depends on the loads, which would
//! change iteration counts and, near the acceptance threshold, results. Keeping them is cheap
//! because every border term lives on the touched bodies: with `w = X Pᵀ x + B_t μ` the system
//!
//! ```text
//! (A + P X Pᵀ) x + P B_t μ = r,      C_t Pᵀ x = r_c
//! ```
//!
//! becomes `x = y − W w` with `y = A⁻¹ r`, `W = A⁻¹ P` (`n × 6T`, 6T tree solves) and, with
//! `G = Pᵀ W` and `y_t = Pᵀ y`, the small dense system (`6T + k`, LU with partial pivoting)
//!
//! ```text
//! [ I + X G   −B_t ] [ w ]   [ X y_t         ]
//! [ C_t G       0  ] [ μ ] = [ C_t y_t − r_c ]
//! ```
//!
//! (from `w = X (y_t − G w) + B_t μ` and `C_t (y_t − G w) = r_c`). It is regular exactly when
//! the full matrix is (for `X = 0` its Schur complement is `C_t G B_t = C A⁻¹ B`). Exact, so the
//! Newton iterates equal those of the dense LU to round-off. Costs: a factorisation is
//! [`factor_tree`], `6T` tree solves and an LU of size `6T + k`; every right-hand side
//! (chord iterations) one tree solve, `n·6T` multiply–adds for `W w` and an LU solve. The
//! factors (`A`'s blocks, `W`, the LU of the small matrix) and the border matrices are kept for
//! [`Border::resolve`]; all storage is allocated by [`Border::new`].
// index loops over the rows and columns of row-major matrices read closer to the formulas
#![allow(clippy::needless_range_loop)]

use super::dense::{lu_factor, lu_solve};
use super::tree::{factor_tree, solve_factored, Block};

/// The border of a loop system and its factors (all preallocated; empty for a tree).
#[derive(Clone, Debug, Default)]
pub(crate) struct Border {
    /// Per joint: index of its first row among the loop rows (`None`: a tree joint).
    pub lrow: Vec<Option<usize>>,
    /// Per body: its index among the touched bodies.
    slot: Vec<Option<usize>>,
    /// Touched bodies (child or parent body of a loop-closing joint).
    touched: Vec<usize>,
    /// Per body: offset of its supernode's unknowns in the stacked tree unknowns.
    off: Vec<usize>,
    /// Number of loop rows `k`.
    k: usize,
    /// `6T` (body unknowns of the touched bodies).
    nt: usize,
    /// `B_t` (`6T × k`, row-major): multiplier columns of the loop rows on the touched bodies.
    pub(crate) bt: Vec<f64>,
    /// `C_t` (`k × 6T`, row-major): loop rows against the touched bodies' unknowns.
    pub(crate) ct: Vec<f64>,
    /// `X` (`6T × 6T`, row-major): body–body couplings of touched bodies not adjacent in the tree.
    pub(crate) x: Vec<f64>,
    /// Right-hand side of the loop rows (`k`; units of the assembled rows), then their
    /// solution (the multiplier updates).
    pub rc: Vec<f64>,
    /// `W = A⁻¹ P` (stacked tree unknowns × `6T`, row-major).
    pub(crate) w: Vec<f64>,
    /// LU factors of the small matrix (`6T + k` square, row-major).
    s: Vec<f64>,
    /// Its pivots.
    piv: Vec<usize>,
    /// Small right-hand side / solution `[w; μ]` (`6T + k`).
    z: Vec<f64>,
    /// The tree right-hand side saved over the solves for `W` (stacked tree unknowns).
    rsave: Vec<f64>,
}

impl Border {
    /// Border layout and storage of a spanning tree with loop-closing joints: `tree_rows[b]`
    /// is the number of rows of body `b`'s tree joint (0 for a root), `loops[j]` is
    /// `Some((rows, bodies))` for a row group `j` in the border (a joint that closes a loop:
    /// its parent body, if any, and child; a coupling: the bodies of its two joints) and
    /// `None` for a tree joint.
    pub fn new(tree_rows: &[usize], loops: &[Option<(usize, Vec<usize>)>]) -> Self {
        let nb = tree_rows.len();
        let mut lrow = vec![None; loops.len()];
        let mut slot = vec![None; nb];
        let mut touched = Vec::new();
        let mut k = 0;
        for (j, lj) in loops.iter().enumerate() {
            let Some((rows, bodies)) = lj else {
                continue;
            };
            lrow[j] = Some(k);
            k += rows;
            for &b in bodies {
                if slot[b].is_none() {
                    slot[b] = Some(touched.len());
                    touched.push(b);
                }
            }
        }
        let mut off = Vec::with_capacity(nb);
        let mut n = 0;
        for rows in tree_rows {
            off.push(n);
            n += 6 + rows;
        }
        let nt = 6 * touched.len();
        let ns = nt + k;
        let n = if touched.is_empty() { 0 } else { n };
        Self {
            lrow,
            slot,
            touched,
            off,
            k,
            nt,
            bt: vec![0.0; nt * k],
            ct: vec![0.0; k * nt],
            x: vec![0.0; nt * nt],
            rc: vec![0.0; k],
            w: vec![0.0; n * nt],
            s: vec![0.0; ns * ns],
            piv: vec![0; ns],
            z: vec![0.0; ns],
            rsave: vec![0.0; n],
        }
    }

    /// Whether the model has loop-closing joints (the system is bordered).
    pub fn is_active(&self) -> bool {
        !self.touched.is_empty()
    }

    /// Zeroes the border matrices and the loop right-hand side (before an assembly).
    pub fn clear(&mut self) {
        self.bt.fill(0.0);
        self.ct.fill(0.0);
        self.x.fill(0.0);
        self.rc.fill(0.0);
    }

    /// Adds `col` (6 body rows of touched body `a`) to multiplier column `l` (a loop row).
    pub fn add_col(&mut self, a: usize, l: usize, col: &[f64; 6]) {
        if let Some(s) = self.slot[a] {
            for r in 0..6 {
                self.bt[(6 * s + r) * self.k + l] += col[r];
            }
        }
    }

    /// Adds `row` (against the 6 unknowns of touched body `b`) to loop row `l`.
    pub fn add_row(&mut self, l: usize, b: usize, row: &[f64; 6]) {
        if let Some(s) = self.slot[b] {
            let nt = self.nt;
            for c in 0..6 {
                self.ct[l * nt + 6 * s + c] += row[c];
            }
        }
    }

    /// Adds the 6 × 6 coupling `blk` (rows of body `a`, columns `x_b`, row-major) of two touched
    /// bodies that are not adjacent in the tree.
    pub fn add_coupling(&mut self, a: usize, b: usize, blk: &[f64; 36]) {
        let (Some(sa), Some(sb)) = (self.slot[a], self.slot[b]) else {
            debug_assert!(false, "off-tree coupling {a}–{b} outside the border");
            return;
        };
        let nt = self.nt;
        for r in 0..6 {
            for c in 0..6 {
                self.x[(6 * sa + r) * nt + 6 * sb + c] += blk[r * 6 + c];
            }
        }
    }

    /// `y += P X Pᵀ x`: the off-tree couplings applied to body unknowns `x` (6 per body), added
    /// to the body rows `y` (6 per body); the step's tangent multiplies the assembled matrix by
    /// a column with it (`step::tangent`).
    pub fn add_couplings_times(&self, x: &[f64], y: &mut [f64]) {
        let nt = self.nt;
        for i in 0..nt {
            let row = &self.x[i * nt..(i + 1) * nt];
            let mut acc = 0.0;
            for m in 0..nt {
                if row[m] != 0.0 {
                    acc += row[m] * x[6 * self.touched[m / 6] + m % 6];
                }
            }
            y[6 * self.touched[i / 6] + i % 6] += acc;
        }
    }

    /// Row of `W` (and of the stacked tree unknowns) of unknown `i` of the touched body slot
    /// `i / 6`.
    fn touched_row(&self, i: usize) -> usize {
        self.off[self.touched[i / 6]] + i % 6
    }

    /// Factors the bordered system (tree blocks assembled in `blocks`, border in `self`) and
    /// solves for the assembled right-hand side (tree part in every `blocks[b].r`, loop rows in
    /// `rc`); the solution replaces it. False if `A` or the small matrix is singular (pivot
    /// below 1e-14 relative; the factors are then unusable). `order`, `parent` as for
    /// [`factor_tree`].
    pub fn factor_solve(
        &mut self,
        blocks: &mut [Block],
        order: &[usize],
        parent: &[Option<usize>],
    ) -> bool {
        if !factor_tree(blocks, order, parent) {
            return false;
        }
        let (nt, k) = (self.nt, self.k);
        let ns = nt + k;
        for (b, blk) in blocks.iter().enumerate() {
            self.rsave[self.off[b]..self.off[b] + blk.n].copy_from_slice(&blk.r[..blk.n]);
        }
        // W = A⁻¹ P, one tree solve per touched unknown
        for c in 0..nt {
            blocks.iter_mut().for_each(|b| b.r.fill(0.0));
            blocks[self.touched[c / 6]].r[c % 6] = 1.0;
            solve_factored(blocks, order, parent);
            for (b, blk) in blocks.iter().enumerate() {
                for i in 0..blk.n {
                    self.w[(self.off[b] + i) * nt + c] = blk.r[i];
                }
            }
        }
        // [I + X G, −B_t; C_t G, 0], G = Pᵀ W (rows of W at the touched unknowns)
        self.s.fill(0.0);
        for i in 0..nt {
            self.s[i * ns + i] = 1.0;
            for l in 0..k {
                self.s[i * ns + nt + l] = -self.bt[i * k + l];
            }
        }
        for i in 0..ns {
            // rows of X (top) or C_t (bottom), times G
            let coef = if i < nt {
                &self.x[i * nt..i * nt + nt]
            } else {
                &self.ct[(i - nt) * nt..(i - nt) * nt + nt]
            };
            for m in 0..nt {
                let a = coef[m];
                if a != 0.0 {
                    let g = self.touched_row(m) * nt;
                    for c in 0..nt {
                        self.s[i * ns + c] += a * self.w[g + c];
                    }
                }
            }
        }
        if !lu_factor(&mut self.s, ns, ns, &mut self.piv, 1e-14) {
            return false;
        }
        for (b, blk) in blocks.iter_mut().enumerate() {
            blk.r[..blk.n].copy_from_slice(&self.rsave[self.off[b]..self.off[b] + blk.n]);
        }
        self.resolve(blocks, order, parent);
        true
    }

    /// Solves for a new right-hand side (tree part in `blocks[b].r`, loop rows in `rc`) with
    /// the factors of the last successful [`Border::factor_solve`]; the solution replaces it.
    pub fn resolve(&mut self, blocks: &mut [Block], order: &[usize], parent: &[Option<usize>]) {
        let (nt, k) = (self.nt, self.k);
        let ns = nt + k;
        // y = A⁻¹ r
        solve_factored(blocks, order, parent);
        // [X y_t; C_t y_t − r_c]
        for i in 0..ns {
            let coef = if i < nt {
                &self.x[i * nt..i * nt + nt]
            } else {
                &self.ct[(i - nt) * nt..(i - nt) * nt + nt]
            };
            let mut acc = if i < nt { 0.0 } else { -self.rc[i - nt] };
            for m in 0..nt {
                if coef[m] != 0.0 {
                    acc += coef[m] * blocks[self.touched[m / 6]].r[m % 6];
                }
            }
            self.z[i] = acc;
        }
        lu_solve(&self.s, ns, ns, &self.piv, &mut self.z);
        // x = y − W w, μ
        let wz = &self.z[..nt];
        for (b, blk) in blocks.iter_mut().enumerate() {
            for i in 0..blk.n {
                let row = &self.w[(self.off[b] + i) * nt..(self.off[b] + i + 1) * nt];
                let dot: f64 = row.iter().zip(wz).map(|(a, b)| a * b).sum();
                blk.r[i] -= dot;
            }
        }
        self.rc.copy_from_slice(&self.z[nt..]);
    }
}
