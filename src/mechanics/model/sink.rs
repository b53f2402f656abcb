//! Where the rows and bodies of the model land in the linear system of a Newton update or a
//! velocity projection: the tree blocks (spanning tree: each body's 6 unknowns with the rows of
//! its tree joint), the border of a loop system (rows and off-tree couplings of loop-closing
//! joints, `linalg::border`), or, for the dense test oracle (`Model::dense`), one dense matrix.
// index loops over the rows and columns of fixed-size blocks read closer to the layout
#![allow(clippy::needless_range_loop)]

use crate::mechanics::linalg::border::Border;
use crate::mechanics::linalg::tree::{Block, NMAX};

use super::runtime::Model;

/// Where the Jacobian and the joint rows' right-hand sides go: the tree blocks (spanning tree),
/// the border (rows and off-tree couplings of loop-closing joints, see `border`), or, for the
/// dense test oracle (`Model::dense`), one dense matrix.
pub(crate) struct Sink<'a> {
    /// The model (tree structure, row offsets).
    pub model: &'a Model,
    /// Tree blocks.
    pub blocks: &'a mut [Block],
    /// Border of the loop-closing joints (empty for a tree).
    pub border: &'a mut Border,
    /// Dense matrix (oracle only), row-major `nd × nd`.
    pub dense: &'a mut [f64],
    /// Dense right-hand side (oracle only).
    pub drhs: &'a mut [f64],
    /// Dense dimension.
    pub nd: usize,
}

impl Sink<'_> {
    /// Adds the 6 × 6 block (rows of body `a`, columns `x_b`).
    pub(crate) fn body_body(&mut self, a: usize, b: usize, blk: &[f64; 36]) {
        if self.model.dense {
            let nd = self.nd;
            for r in 0..6 {
                for s in 0..6 {
                    self.dense[(6 * a + r) * nd + 6 * b + s] += blk[r * 6 + s];
                }
            }
        } else if a == b {
            let d = &mut self.blocks[a].d;
            for r in 0..6 {
                for s in 0..6 {
                    d[r * NMAX + s] += blk[r * 6 + s];
                }
            }
        } else if self.model.parent[b] == Some(a) {
            let l = &mut self.blocks[b].l;
            for r in 0..6 {
                for s in 0..6 {
                    l[r * NMAX + s] += blk[r * 6 + s];
                }
            }
        } else if self.model.parent[a] == Some(b) {
            let u = &mut self.blocks[a].u;
            for r in 0..6 {
                for s in 0..6 {
                    u[r * 6 + s] += blk[r * 6 + s];
                }
            }
        } else {
            // a loop-closing joint between bodies not adjacent in the tree
            self.border.add_coupling(a, b, blk);
        }
    }

    /// Offset of row group `j`'s first row in the multiplier vector and its tree child: the
    /// rows of joint `j`, or for `j ≥` the number of joints those of coupling `j − joints`
    /// (always in the border; no tree child).
    fn group(&self, j: usize) -> (usize, usize) {
        let m = self.model;
        match m.joints.get(j) {
            Some(jt) => (jt.row0, jt.child),
            None => (m.couplings[j - m.joints.len()].row, usize::MAX),
        }
    }

    /// Adds column `col` (6 body rows of `a`) for multiplier `k` of row group `j` (a joint,
    /// or a coupling after the joints: [`Self::group`]).
    pub(crate) fn body_mu(&mut self, a: usize, j: usize, k: usize, col: &[f64; 6]) {
        let (row0, child) = self.group(j);
        if self.model.dense {
            let nd = self.nd;
            let c = 6 * self.model.bodies.len() + row0 + k;
            for r in 0..6 {
                self.dense[(6 * a + r) * nd + c] += col[r];
            }
        } else if let Some(l) = self.border.lrow[j] {
            self.border.add_col(a, l + k, col);
        } else if a == child {
            let d = &mut self.blocks[a].d;
            for r in 0..6 {
                d[r * NMAX + 6 + k] += col[r];
            }
        } else {
            let l = &mut self.blocks[child].l;
            for r in 0..6 {
                l[r * NMAX + 6 + k] += col[r];
            }
        }
    }

    /// Adds row `k` of row group `j` (a joint, or a coupling: [`Self::group`]) against `x_b`.
    pub(crate) fn mu_body(&mut self, j: usize, k: usize, b: usize, row: &[f64; 6]) {
        let (row0, child) = self.group(j);
        if self.model.dense {
            let nd = self.nd;
            let r = 6 * self.model.bodies.len() + row0 + k;
            for s in 0..6 {
                self.dense[r * nd + 6 * b + s] += row[s];
            }
        } else if let Some(l) = self.border.lrow[j] {
            self.border.add_row(l + k, b, row);
        } else if b == child {
            let d = &mut self.blocks[b].d;
            for s in 0..6 {
                d[(6 + k) * NMAX + s] += row[s];
            }
        } else {
            let u = &mut self.blocks[child].u;
            for s in 0..6 {
                u[(6 + k) * 6 + s] += row[s];
            }
        }
    }
}

impl Sink<'_> {
    /// Sets the right-hand side of row `k` of row group `j` (a joint, or a coupling:
    /// [`Self::group`]) to `v`.
    pub(crate) fn rhs_row(&mut self, j: usize, k: usize, v: f64) {
        let (row0, child) = self.group(j);
        if self.model.dense {
            self.drhs[6 * self.model.bodies.len() + row0 + k] = v;
        } else if let Some(l) = self.border.lrow[j] {
            self.border.rc[l + k] = v;
        } else {
            self.blocks[child].r[6 + k] = v;
        }
    }
}
