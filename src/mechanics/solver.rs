//! Linear algebra of the Newton step: small dense LU with partial pivoting, the tree block
//! elimination (Baraff's linear-time method) and a dense fallback for systems with loops.
//!
//! Tree structure: the unknowns of supernode `b` are body `b`'s increment `x_b = (δφ, δθ)` (6)
//! followed by the scaled multipliers `μ` of its active tree-joint rows (`m_b ≤ 6`). Every
//! coupling of the iteration matrix runs along a tree edge (child `c`, parent `p`):
//! `D_c` (diagonal block, `n_c × n_c`), `U_c` (rows of supernode `c`, columns `x_p`, `n_c × 6`)
//! and `L_c` (body rows of `p`, columns of supernode `c`, `6 × n_c`). Eliminating leaves to
//! root costs O(N) with fixed-size blocks (at most 12 × 12).

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

/// Solves `A X = B` for the `n × 6` block `B` (row-major, stride 6) in place.
fn lu_solve6(a: &[f64], n: usize, s: usize, piv: &[usize], b: &mut [f64; NMAX * 6]) {
    for k in 0..n {
        let p = piv[k];
        if p != k {
            for c in 0..6 {
                b.swap(k * 6 + c, p * 6 + c);
            }
        }
    }
    for i in 0..n {
        for j in 0..i {
            let f = a[i * s + j];
            if f != 0.0 {
                for c in 0..6 {
                    b[i * 6 + c] -= f * b[j * 6 + c];
                }
            }
        }
    }
    for i in (0..n).rev() {
        for j in i + 1..n {
            let f = a[i * s + j];
            if f != 0.0 {
                for c in 0..6 {
                    b[i * 6 + c] -= f * b[j * 6 + c];
                }
            }
        }
        let inv = 1.0 / a[i * s + i];
        for c in 0..6 {
            b[i * 6 + c] *= inv;
        }
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
    /// Pivots of `D`.
    pub piv: [usize; NMAX],
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
            piv: [0; NMAX],
        }
    }

    /// Zeroes matrices and right-hand side.
    pub fn clear(&mut self) {
        self.d.fill(0.0);
        self.u.fill(0.0);
        self.l.fill(0.0);
        self.r.fill(0.0);
    }
}

/// Tree block elimination: `order` lists bodies parents first, `parent[b]` the tree parent.
/// On return each `blocks[b].r` holds supernode `b`'s solution. Returns false if a diagonal
/// block is singular.
pub fn solve_tree(blocks: &mut [Block], order: &[usize], parent: &[Option<usize>]) -> bool {
    // leaves to root: factor D_c, Schur update of the parent's body block
    for &c in order.iter().rev() {
        let (n, ok) = {
            let b = &mut blocks[c];
            let n = b.n;
            (n, lu_factor(&mut b.d, n, NMAX, &mut b.piv, 1e-14))
        };
        if !ok {
            return false;
        }
        let Some(p) = parent[c] else {
            let b = &mut blocks[c];
            let mut r = b.r;
            lu_solve(&b.d, n, NMAX, &b.piv, &mut r[..n]);
            b.r = r;
            continue;
        };
        // y = D⁻¹ r, Y = D⁻¹ U (stored back into r and u)
        let (l, upd, rupd) = {
            let b = &mut blocks[c];
            let mut r = b.r;
            lu_solve(&b.d, n, NMAX, &b.piv, &mut r[..n]);
            b.r = r;
            let mut u = b.u;
            lu_solve6(&b.d, n, NMAX, &b.piv, &mut u);
            b.u = u;
            // L Y (6 × 6) and L y (6)
            let mut upd = [0.0; 36];
            let mut rupd = [0.0; 6];
            for i in 0..6 {
                for k in 0..n {
                    let lik = b.l[i * NMAX + k];
                    if lik != 0.0 {
                        for j in 0..6 {
                            upd[i * 6 + j] += lik * b.u[k * 6 + j];
                        }
                        rupd[i] += lik * b.r[k];
                    }
                }
            }
            (b.l, upd, rupd)
        };
        let _ = l;
        let bp = &mut blocks[p];
        for i in 0..6 {
            for j in 0..6 {
                bp.d[i * NMAX + j] -= upd[i * 6 + j];
            }
            bp.r[i] -= rupd[i];
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
