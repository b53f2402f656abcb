//! Linear algebra of the Newton step: small dense LU with partial pivoting, the tree block
//! elimination (Baraff's linear-time method) and a dense fallback for systems with loops.
//!
//! Tree structure: the unknowns of supernode `b` are body `b`'s increment `x_b = (δφ, δθ)` (6)
//! followed by the scaled multipliers `μ` of its active tree-joint rows (`m_b ≤ 6`). Every
//! coupling of the iteration matrix runs along a tree edge (child `c`, parent `p`):
//! `D_c` (diagonal block, `n_c × n_c`), `U_c` (rows of supernode `c`, columns `x_p`, `n_c × 6`)
//! and `L_c` (body rows of `p`, columns of supernode `c`, `6 × n_c`). Eliminating leaves to
//! root costs O(N) with fixed-size blocks (at most 12 × 12).
//!
//! Systems with loop-closing joints use one dense LU with partial pivoting over all unknowns
//! (`6 N + active rows`, preallocated in the workspace): O(N³), meant for the small closed
//! linkages (four-bars, parallel mechanisms) this tool targets; redundant loop rows are dropped
//! at set-up so that the matrix stays regular.
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

/// Largest supernode size: 6 body unknowns + 6 joint rows.
pub const NMAX: usize = 12;

/// LU factorisation in place of the `n × n` matrix `a` (row-major, row stride `s`) with partial
/// pivoting; returns false when a pivot is below `rel` times the largest entry (singular).
pub fn lu_factor(a: &mut [f64], n: usize, s: usize, piv: &mut [usize], rel: f64) -> bool {
    let mut amax = 0.0_f64;
    for i in 0..n {
        for j in 0..n {
            amax = amax.max(a[i * s + j].abs());
        }
    }
    if !(amax.is_finite() && amax > 0.0) {
        return false;
    }
    let tiny = rel * amax;
    for k in 0..n {
        // pivot search in column k
        let mut p = k;
        let mut best = a[k * s + k].abs();
        for i in k + 1..n {
            let v = a[i * s + k].abs();
            if v > best {
                best = v;
                p = i;
            }
        }
        if best <= tiny || !best.is_finite() {
            return false;
        }
        piv[k] = p;
        if p != k {
            for j in 0..n {
                a.swap(k * s + j, p * s + j);
            }
        }
        let inv = 1.0 / a[k * s + k];
        for i in k + 1..n {
            let f = a[i * s + k] * inv;
            if f != 0.0 {
                a[i * s + k] = f;
                for j in k + 1..n {
                    a[i * s + j] -= f * a[k * s + j];
                }
            } else {
                a[i * s + k] = 0.0;
            }
        }
    }
    true
}

/// Solves `A x = b` in place (`b` becomes `x`) with the factors of [`lu_factor`].
pub fn lu_solve(a: &[f64], n: usize, s: usize, piv: &[usize], b: &mut [f64]) {
    for k in 0..n {
        let p = piv[k];
        if p != k {
            b.swap(k, p);
        }
    }
    for i in 0..n {
        let mut acc = b[i];
        for j in 0..i {
            acc -= a[i * s + j] * b[j];
        }
        b[i] = acc;
    }
    for i in (0..n).rev() {
        let mut acc = b[i];
        for j in i + 1..n {
            acc -= a[i * s + j] * b[j];
        }
        b[i] = acc / a[i * s + i];
    }
}

/// One supernode's blocks and right-hand side (all preallocated, fixed size).
#[derive(Clone, Debug)]
pub struct Block {
    /// Size `n = 6 + m`.
    pub n: usize,
    /// Diagonal block `D`, row-major, stride [`NMAX`].
    pub d: [f64; NMAX * NMAX],
    /// `U`: rows of this supernode, columns of the parent's `x` (stride 6).
    pub u: [f64; NMAX * 6],
    /// `L`: the parent's body rows, columns of this supernode (stride [`NMAX`]).
    pub l: [f64; 6 * NMAX],
    /// Right-hand side, then the solution.
    pub r: [f64; NMAX],
}

impl Block {
    /// An empty block of size `n`.
    #[must_use]
    pub fn new(n: usize) -> Self {
        Self {
            n,
            d: [0.0; NMAX * NMAX],
            u: [0.0; NMAX * 6],
            l: [0.0; 6 * NMAX],
            r: [0.0; NMAX],
        }
    }

    /// Zeroes the used parts of the matrices and the right-hand side.
    pub fn clear(&mut self) {
        let n = self.n;
        for i in 0..n {
            self.d[i * NMAX..i * NMAX + n].fill(0.0);
        }
        self.u[..n * 6].fill(0.0);
        for i in 0..6 {
            self.l[i * NMAX..i * NMAX + n].fill(0.0);
        }
        self.r.fill(0.0);
    }
}

/// Width of the augmented rows `[D | U | r]`.
const W: usize = NMAX + 7;

/// Gaussian elimination with partial pivoting of the augmented `N × (N + K)` system held in
/// `a` (row stride [`W`]); on return columns `N..N + K` hold `D⁻¹ [U | r]`. Returns false for a
/// pivot below `1e-14` times the largest entry of `D`. Sizes are compile-time constants so that
/// the loops unroll and vectorise (one instance per supernode size, see [`eliminate_block`]).
fn eliminate<const N: usize, const K: usize>(a: &mut [f64; NMAX * W]) -> bool {
    // largest |entry| (NaN entries are skipped, as by `f64::max`; a comparison select
    // vectorises where `f64::max` does not)
    let mut amax = 0.0_f64;
    for i in 0..N {
        for j in 0..N {
            let v = a[i * W + j].abs();
            amax = if v > amax { v } else { amax };
        }
    }
    if !(amax.is_finite() && amax > 0.0) {
        return false;
    }
    let tiny = 1e-14 * amax;
    for c in 0..N {
        // pivot search in column c
        let mut p = c;
        let mut best = a[c * W + c].abs();
        for i in c + 1..N {
            let v = a[i * W + c].abs();
            if v > best {
                best = v;
                p = i;
            }
        }
        if best <= tiny || !best.is_finite() {
            return false;
        }
        if p != c {
            for j in c..N + K {
                a.swap(c * W + j, p * W + j);
            }
        }
        let mut piv = [0.0; W];
        piv[c + 1..N + K].copy_from_slice(&a[c * W + c + 1..c * W + N + K]);
        let inv = 1.0 / a[c * W + c];
        for i in c + 1..N {
            let f = a[i * W + c] * inv;
            if f != 0.0 {
                for j in c + 1..N + K {
                    a[i * W + j] -= f * piv[j];
                }
            }
        }
    }
    // back substitution on the K right-hand columns
    for i in (0..N).rev() {
        let mut row = [0.0; K];
        row.copy_from_slice(&a[i * W + N..i * W + N + K]);
        for l in i + 1..N {
            let f = a[i * W + l];
            if f != 0.0 {
                for j in 0..K {
                    row[j] -= f * a[l * W + N + j];
                }
            }
        }
        let inv = 1.0 / a[i * W + i];
        for j in 0..K {
            a[i * W + N + j] = row[j] * inv;
        }
    }
    true
}

/// [`eliminate`] for a run-time size `n` (6 ≤ n ≤ [`NMAX`]) and `k` ∈ {1, 7} right-hand columns.
fn eliminate_block(a: &mut [f64; NMAX * W], n: usize, k: usize) -> bool {
    macro_rules! dispatch {
        ($($n:literal),*) => {
            match (n, k) {
                $(($n, 7) => eliminate::<$n, 7>(a), ($n, _) => eliminate::<$n, 1>(a),)*
                _ => false,
            }
        };
    }
    dispatch!(6, 7, 8, 9, 10, 11, 12)
}

/// Tree block elimination: `order` lists bodies parents first, `parent[b]` the tree parent.
/// On return each `blocks[b].r` holds supernode `b`'s solution. Returns false if a diagonal
/// block is singular.
pub fn solve_tree(blocks: &mut [Block], order: &[usize], parent: &[Option<usize>]) -> bool {
    let mut a = [0.0; NMAX * W];
    // leaves to root: D_c⁻¹ [U_c | r_c], Schur update of the parent's body block
    for &c in order.iter().rev() {
        let has_parent = parent[c].is_some();
        let k = if has_parent { 7 } else { 1 };
        let (upd, rupd) = {
            let b = &mut blocks[c];
            let n = b.n;
            for i in 0..n {
                let row = &mut a[i * W..i * W + n + k];
                row[..n].copy_from_slice(&b.d[i * NMAX..i * NMAX + n]);
                if has_parent {
                    row[n..n + 6].copy_from_slice(&b.u[i * 6..i * 6 + 6]);
                    row[n + 6] = b.r[i];
                } else {
                    row[n] = b.r[i];
                }
            }
            if !eliminate_block(&mut a, n, k) {
                return false;
            }
            if !has_parent {
                for i in 0..n {
                    b.r[i] = a[i * W + n];
                }
                continue;
            }
            for i in 0..n {
                b.u[i * 6..i * 6 + 6].copy_from_slice(&a[i * W + n..i * W + n + 6]);
                b.r[i] = a[i * W + n + 6];
            }
            // L Y (6 × 6) and L y (6)
            let mut upd = [0.0; 36];
            let mut rupd = [0.0; 6];
            for i in 0..6 {
                for kk in 0..n {
                    let lik = b.l[i * NMAX + kk];
                    if lik != 0.0 {
                        for j in 0..6 {
                            upd[i * 6 + j] += lik * b.u[kk * 6 + j];
                        }
                        rupd[i] += lik * b.r[kk];
                    }
                }
            }
            (upd, rupd)
        };
        if let Some(p) = parent[c] {
            let bp = &mut blocks[p];
            for i in 0..6 {
                for j in 0..6 {
                    bp.d[i * NMAX + j] -= upd[i * 6 + j];
                }
                bp.r[i] -= rupd[i];
            }
        }
    }
    // root to leaves: z_c = y_c − Y_c x_p (roots are already solved)
    for &c in order {
        if let Some(p) = parent[c] {
            let xp: [f64; 6] = std::array::from_fn(|k| blocks[p].r[k]);
            let b = &mut blocks[c];
            for i in 0..b.n {
                let mut acc = 0.0;
                for j in 0..6 {
                    acc += b.u[i * 6 + j] * xp[j];
                }
                b.r[i] -= acc;
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tree elimination reproduces a dense solve of the same system.
    #[test]
    fn tree_matches_dense() {
        // chain 0 ← 1 ← 2 plus 3 attached to 1; sizes 6+5, 6+5, 6+3, 6+0 (3 is treated as a child)
        let parent = [None, Some(0), Some(1), Some(1)];
        let sizes = [11, 11, 9, 6];
        let order = [0, 1, 2, 3];
        let mut seed = 1u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        let mut blocks: Vec<Block> = sizes.iter().map(|&n| Block::new(n)).collect();
        for (c, b) in blocks.iter_mut().enumerate() {
            for i in 0..b.n {
                for j in 0..b.n {
                    b.d[i * NMAX + j] = rnd() + if i == j { 4.0 } else { 0.0 };
                }
                b.r[i] = rnd();
            }
            if parent[c].is_some() {
                for i in 0..b.n {
                    for j in 0..6 {
                        b.u[i * 6 + j] = rnd();
                        b.l[j * NMAX + i] = rnd();
                    }
                }
            }
        }
        // dense copy
        let off: Vec<usize> = sizes
            .iter()
            .scan(0, |s, &n| {
                let o = *s;
                *s += n;
                Some(o)
            })
            .collect();
        let nt: usize = sizes.iter().sum();
        let mut a = vec![0.0; nt * nt];
        let mut rhs = vec![0.0; nt];
        for (c, b) in blocks.iter().enumerate() {
            for i in 0..b.n {
                rhs[off[c] + i] = b.r[i];
                for j in 0..b.n {
                    a[(off[c] + i) * nt + off[c] + j] = b.d[i * NMAX + j];
                }
            }
            if let Some(p) = parent[c] {
                for i in 0..b.n {
                    for j in 0..6 {
                        a[(off[c] + i) * nt + off[p] + j] = b.u[i * 6 + j];
                        a[(off[p] + j) * nt + off[c] + i] = b.l[j * NMAX + i];
                    }
                }
            }
        }
        let mut piv = vec![0; nt];
        assert!(lu_factor(&mut a, nt, nt, &mut piv, 1e-14));
        lu_solve(&a, nt, nt, &piv, &mut rhs);
        assert!(solve_tree(&mut blocks, &order, &parent));
        for (c, b) in blocks.iter().enumerate() {
            for i in 0..b.n {
                assert!((b.r[i] - rhs[off[c] + i]).abs() < 1e-12, "{c} {i}");
            }
        }
    }
}
