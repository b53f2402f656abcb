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
//! The diagonal block has the saddle-point form `D = [K B; C E]`: `K` (6 × 6) the body block
//! (inertia plus O(h²) terms plus the Schur updates `−L Y` of the children, regular for
//! positive masses and inertias), `B` (6 × m) the multiplier columns, `C` (m × 6) the
//! constraint rows and `E = 0` (m × m; kept general). It is not symmetric. [`factor_tree`]
//! factors `K` and the m × m Schur complement `S = E − C K⁻¹ B` (both with partial pivoting,
//! fixed sizes through const generics), forms `Y = D⁻¹ U` and updates the parent's `K` by
//! `−L Y`; [`solve_factored`] then solves for any number of right-hand sides with the stored
//! factors (forward `y = D⁻¹ r`, `r_p −= L y`, back `x = y − Y x_p`); [`solve_tree`] does both.
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
///
/// Before [`factor_tree`] the matrices hold the assembled iteration matrix (unknowns of the
/// supernode: `x_b` (6) then `μ` (m), `n = 6 + m`):
/// `d = D = [K B; C E]` (`K` 6 × 6 body–body, `B` 6 × m multiplier columns, `C` m × 6
/// constraint rows, `E` m × m, zero in the Newton and projection systems), `u = U`, `l = L`.
/// After it, `d`, `u` and `piv` hold the factors (see [`factor_tree`]); `l` and `n` are kept;
/// `r` is never read or written by the factorisation.
#[derive(Clone, Debug)]
pub struct Block {
    /// Size `n = 6 + m` (`6 ≤ n ≤` [`NMAX`]).
    pub n: usize,
    /// Diagonal block `D`, row-major, stride [`NMAX`]; its factors after [`factor_tree`].
    pub d: [f64; NMAX * NMAX],
    /// `U`: rows of this supernode, columns of the parent's `x` (stride 6); `D⁻¹ U` after
    /// [`factor_tree`].
    pub u: [f64; NMAX * 6],
    /// `L`: the parent's body rows, columns of this supernode (stride [`NMAX`]).
    pub l: [f64; 6 * NMAX],
    /// Right-hand side, then the solution.
    pub r: [f64; NMAX],
    /// Row interchanges of the factors: `K` in `0..6`, the Schur complement `S` in `6..n`.
    pub piv: [u8; NMAX],
}

impl Block {
    /// An empty block of size `n` (`6 ≤ n ≤` [`NMAX`]).
    #[must_use]
    pub fn new(n: usize) -> Self {
        assert!((6..=NMAX).contains(&n), "supernode size {n} out of 6..=12");
        Self {
            n,
            d: [0.0; NMAX * NMAX],
            u: [0.0; NMAX * 6],
            l: [0.0; 6 * NMAX],
            r: [0.0; NMAX],
            piv: [0; NMAX],
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

/// Relative pivot threshold of the supernode factorisations.
const REL: f64 = 1e-14;

/// The `R × C` sub-matrix at `(r0, c0)` of the row-major `a` (row stride `s`).
#[inline(always)]
fn load<const R: usize, const C: usize>(
    a: &[f64],
    r0: usize,
    c0: usize,
    s: usize,
) -> [[f64; C]; R] {
    std::array::from_fn(|i| std::array::from_fn(|j| a[(r0 + i) * s + c0 + j]))
}

/// Writes `x` at `(r0, c0)` of the row-major `a` (row stride `s`).
#[inline(always)]
fn store<const R: usize, const C: usize>(
    a: &mut [f64],
    r0: usize,
    c0: usize,
    s: usize,
    x: &[[f64; C]; R],
) {
    for i in 0..R {
        a[(r0 + i) * s + c0..(r0 + i) * s + c0 + C].copy_from_slice(&x[i]);
    }
}

/// Largest `|entry|` (NaN is propagated as infinity so that it fails the finiteness checks).
#[inline(always)]
fn amax<const R: usize, const C: usize>(a: &[[f64; C]; R]) -> f64 {
    let mut m = 0.0_f64;
    for row in a {
        for &v in row {
            let v = if v.is_nan() { f64::INFINITY } else { v.abs() };
            m = if v > m { v } else { m };
        }
    }
    m
}

/// In-place LU factorisation with partial pivoting (`P A = L U`, unit `L` below the diagonal);
/// `piv[k]` is the row swapped with row `k` at step `k`. False for a pivot not above `tiny`
/// or not finite.
#[inline(always)]
fn lu<const N: usize>(a: &mut [[f64; N]; N], piv: &mut [u8; N], tiny: f64) -> bool {
    for k in 0..N {
        let mut p = k;
        let mut best = a[k][k].abs();
        for i in k + 1..N {
            let v = a[i][k].abs();
            if v > best {
                best = v;
                p = i;
            }
        }
        if !(best > tiny && best.is_finite()) {
            return false;
        }
        piv[k] = p as u8;
        a.swap(k, p);
        let pr = a[k];
        let inv = 1.0 / pr[k];
        for i in k + 1..N {
            let f = a[i][k] * inv;
            a[i][k] = f;
            for j in k + 1..N {
                a[i][j] -= f * pr[j];
            }
        }
    }
    true
}

/// Solves `A X = B` in place (`K` right-hand columns, `x` holds `B` then `X`) with [`lu`]'s
/// factors.
#[inline(always)]
fn lu_solve_mat<const N: usize, const K: usize>(
    a: &[[f64; N]; N],
    piv: &[u8; N],
    x: &mut [[f64; K]; N],
) {
    for k in 0..N {
        x.swap(k, piv[k] as usize);
    }
    for i in 1..N {
        for j in 0..i {
            let f = a[i][j];
            let xj = x[j];
            for c in 0..K {
                x[i][c] -= f * xj[c];
            }
        }
    }
    for i in (0..N).rev() {
        for j in i + 1..N {
            let f = a[i][j];
            let xj = x[j];
            for c in 0..K {
                x[i][c] -= f * xj[c];
            }
        }
        let inv = 1.0 / a[i][i];
        for c in 0..K {
            x[i][c] *= inv;
        }
    }
}

/// Solves `A x = b` in place with [`lu`]'s factors.
#[inline(always)]
fn lu_solve_vec<const N: usize>(a: &[[f64; N]; N], piv: &[u8; N], x: &mut [f64; N]) {
    for k in 0..N {
        x.swap(k, piv[k] as usize);
    }
    for i in 1..N {
        let mut acc = x[i];
        for j in 0..i {
            acc -= a[i][j] * x[j];
        }
        x[i] = acc;
    }
    for i in (0..N).rev() {
        let mut acc = x[i];
        for j in i + 1..N {
            acc -= a[i][j] * x[j];
        }
        x[i] = acc / a[i][i];
    }
}

/// `x −= A y` for `A` `R × C`.
#[inline(always)]
fn sub_mul<const R: usize, const C: usize, const K: usize>(
    x: &mut [[f64; K]; R],
    a: &[[f64; C]; R],
    y: &[[f64; K]; C],
) {
    for i in 0..R {
        for l in 0..C {
            let f = a[i][l];
            for c in 0..K {
                x[i][c] -= f * y[l][c];
            }
        }
    }
}

/// Factors supernode `b` (`m = M` joint rows) in place and, if `has_parent`, replaces `U` by
/// `Y = D⁻¹ U` and returns the parent's Schur update `L Y` (6 × 6); `None` if singular.
///
/// `D = [K B; C E]` is eliminated through `K`: `K = P_K⁻¹ L_K U_K`, `S = E − C K⁻¹ B`
/// (m × m) `= P_S⁻¹ L_S U_S`. Stored in `d`: the LU of `K` (rows/columns `0..6`), `K⁻¹ B`
/// (rows `0..6`, columns `6..n`), `C` (kept, rows `6..n`, columns `0..6`), the LU of `S`
/// (rows and columns `6..n`); pivots in `piv`.
#[inline(always)]
fn factor_block<const M: usize>(b: &mut Block, has_parent: bool) -> Option<[[f64; 6]; 6]> {
    let mut k: [[f64; 6]; 6] = load(&b.d, 0, 0, NMAX);
    let mut kb: [[f64; M]; 6] = load(&b.d, 0, 6, NMAX);
    let c: [[f64; 6]; M] = load(&b.d, 6, 0, NMAX);
    let mut s: [[f64; M]; M] = load(&b.d, 6, 6, NMAX);
    let kmax = amax(&k);
    if !(kmax.is_finite() && kmax > 0.0) {
        return None;
    }
    let mut pk = [0u8; 6];
    if !lu(&mut k, &mut pk, REL * kmax) {
        return None;
    }
    lu_solve_mat(&k, &pk, &mut kb);
    // S = E − C K⁻¹B; pivots are judged against the size of the terms before cancellation
    sub_mul(&mut s, &c, &kb);
    let sref = amax(&s).max(6.0 * amax(&c) * amax(&kb));
    if !sref.is_finite() {
        return None;
    }
    let mut ps = [0u8; M];
    if !lu(&mut s, &mut ps, REL * sref) {
        return None;
    }
    store(&mut b.d, 0, 0, NMAX, &k);
    store(&mut b.d, 0, 6, NMAX, &kb);
    store(&mut b.d, 6, 6, NMAX, &s);
    b.piv[..6].copy_from_slice(&pk);
    b.piv[6..6 + M].copy_from_slice(&ps);
    let mut upd = [[0.0; 6]; 6];
    if has_parent {
        // Y_μ = S⁻¹ (U_μ − C K⁻¹ U_x), Y_x = K⁻¹ U_x − K⁻¹B Y_μ
        let mut yx: [[f64; 6]; 6] = load(&b.u, 0, 0, 6);
        lu_solve_mat(&k, &pk, &mut yx);
        let mut ym: [[f64; 6]; M] = load(&b.u, 6, 0, 6);
        sub_mul(&mut ym, &c, &yx);
        lu_solve_mat(&s, &ps, &mut ym);
        sub_mul(&mut yx, &kb, &ym);
        store(&mut b.u, 0, 0, 6, &yx);
        store(&mut b.u, 6, 0, 6, &ym);
        // L Y = L_x Y_x + L_μ Y_μ
        let lx: [[f64; 6]; 6] = load(&b.l, 0, 0, NMAX);
        let lm: [[f64; M]; 6] = load(&b.l, 0, 6, NMAX);
        for i in 0..6 {
            for l in 0..6 {
                let f = lx[i][l];
                for j in 0..6 {
                    upd[i][j] += f * yx[l][j];
                }
            }
            for l in 0..M {
                let f = lm[i][l];
                for j in 0..6 {
                    upd[i][j] += f * ym[l][j];
                }
            }
        }
    }
    Some(upd)
}

/// Forward step of the solve for supernode `b` (`m = M`): `r ← D⁻¹ r` with the stored
/// factors; returns `L r` (the parent's right-hand side update; meaningless for a root).
#[inline(always)]
fn forward_block<const M: usize>(b: &mut Block) -> [f64; 6] {
    let k: [[f64; 6]; 6] = load(&b.d, 0, 0, NMAX);
    let pk: [u8; 6] = std::array::from_fn(|i| b.piv[i]);
    let mut x: [f64; 6] = std::array::from_fn(|i| b.r[i]);
    lu_solve_vec(&k, &pk, &mut x);
    let mut g: [f64; M] = std::array::from_fn(|i| b.r[6 + i]);
    if M > 0 {
        // μ = S⁻¹ (g − C K⁻¹ f), x = K⁻¹ f − K⁻¹B μ
        let c: [[f64; 6]; M] = load(&b.d, 6, 0, NMAX);
        let s: [[f64; M]; M] = load(&b.d, 6, 6, NMAX);
        let kb: [[f64; M]; 6] = load(&b.d, 0, 6, NMAX);
        let ps: [u8; M] = std::array::from_fn(|i| b.piv[6 + i]);
        for i in 0..M {
            for l in 0..6 {
                g[i] -= c[i][l] * x[l];
            }
        }
        lu_solve_vec(&s, &ps, &mut g);
        for i in 0..6 {
            for j in 0..M {
                x[i] -= kb[i][j] * g[j];
            }
        }
        b.r[6..6 + M].copy_from_slice(&g);
    }
    b.r[..6].copy_from_slice(&x);
    let lx: [[f64; 6]; 6] = load(&b.l, 0, 0, NMAX);
    let lm: [[f64; M]; 6] = load(&b.l, 0, 6, NMAX);
    std::array::from_fn(|i| {
        let mut acc = 0.0;
        for j in 0..6 {
            acc += lx[i][j] * x[j];
        }
        for j in 0..M {
            acc += lm[i][j] * g[j];
        }
        acc
    })
}

/// Back substitution of supernode `b` (`n = 6 + M`): `r ← r − Y x_p`.
#[inline(always)]
fn back_block<const M: usize>(b: &mut Block, xp: &[f64; 6]) {
    for i in 0..6 + M {
        let mut acc = b.r[i];
        for j in 0..6 {
            acc -= b.u[i * 6 + j] * xp[j];
        }
        b.r[i] = acc;
    }
}

/// Calls `$f::<m>($args)` for the run-time row count `$m` ∈ 0..=6 of a supernode.
macro_rules! by_rows {
    ($m:expr, $f:ident ( $($arg:expr),* ), $other:expr) => {
        match $m {
            0 => $f::<0>($($arg),*),
            1 => $f::<1>($($arg),*),
            2 => $f::<2>($($arg),*),
            3 => $f::<3>($($arg),*),
            4 => $f::<4>($($arg),*),
            5 => $f::<5>($($arg),*),
            6 => $f::<6>($($arg),*),
            _ => $other,
        }
    };
}

/// Factors the tree system in place (leaves to root). `order` lists bodies parents first,
/// `parent[b]` is the tree parent. Each supernode's diagonal block (after the Schur updates of
/// its children) is eliminated through its body block `K` (see [`Block`]); on return
/// `blocks[b].d`, `.u` (now `D⁻¹ U`) and `.piv` hold the factors that [`solve_factored`]
/// uses, `.l` is unchanged and `.r` is neither read nor written. Returns false (factors
/// unusable) if a pivot of `K` or of the Schur complement `S = E − C K⁻¹ B` is below `1e-14`
/// times the size of its matrix (non-finite entries included).
pub fn factor_tree(blocks: &mut [Block], order: &[usize], parent: &[Option<usize>]) -> bool {
    for &c in order.iter().rev() {
        let p = parent[c];
        let b = &mut blocks[c];
        let m = b.n.wrapping_sub(6);
        let Some(upd) = by_rows!(m, factor_block(b, p.is_some()), None) else {
            return false;
        };
        if let Some(p) = p {
            let d = &mut blocks[p].d;
            for i in 0..6 {
                for j in 0..6 {
                    d[i * NMAX + j] -= upd[i][j];
                }
            }
        }
    }
    true
}

/// Solves the tree system factored by [`factor_tree`] for the right-hand side held in every
/// `blocks[b].r` (length `n_b`, units of the assembled rows); the solution (`x_b`, then `μ`)
/// replaces it. Reads only the stored factors, so it may be called any number of times per
/// factorisation with new right-hand sides. `order` and `parent` as for [`factor_tree`].
pub fn solve_factored(blocks: &mut [Block], order: &[usize], parent: &[Option<usize>]) {
    // leaves to root: y_c = D_c⁻¹ r_c, r_p −= L_c y_c
    for &c in order.iter().rev() {
        let b = &mut blocks[c];
        let ly = by_rows!(b.n - 6, forward_block(b), unreachable!("supernode size"));
        if let Some(p) = parent[c] {
            let r = &mut blocks[p].r;
            for i in 0..6 {
                r[i] -= ly[i];
            }
        }
    }
    // root to leaves: x_c = y_c − Y_c x_p (roots are already solved)
    for &c in order {
        if let Some(p) = parent[c] {
            let xp: [f64; 6] = std::array::from_fn(|k| blocks[p].r[k]);
            let b = &mut blocks[c];
            by_rows!(b.n - 6, back_block(b, &xp), unreachable!("supernode size"));
        }
    }
}

/// Tree block elimination: [`factor_tree`] then [`solve_factored`]. On return each
/// `blocks[b].r` holds supernode `b`'s solution and the blocks hold the factors. Returns false
/// if a diagonal block is singular (the right-hand sides are then left unsolved).
pub fn solve_tree(blocks: &mut [Block], order: &[usize], parent: &[Option<usize>]) -> bool {
    if !factor_tree(blocks, order, parent) {
        return false;
    }
    solve_factored(blocks, order, parent);
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Deterministic uniform numbers in `[−½, ½)`.
    struct Rng(u64);

    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((self.0 >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        }
    }

    /// A random tree system with supernode sizes `6 + ms[b]`: `K` diagonally dominant, random
    /// `C`, `U`; if `general`, random `B`, `L` and μμ block `E`, else the real pattern: `E = 0`
    /// and `B`, `L_μ` close to the transposes of `C`, `U_μ` (not equal: the matrix is not
    /// symmetric).
    /// Returns the blocks (right-hand sides set) and the dense copy `(a, nt, offsets)`.
    fn system(
        parent: &[Option<usize>],
        ms: &[usize],
        general: bool,
        rng: &mut Rng,
    ) -> (Vec<Block>, Vec<f64>, usize, Vec<usize>) {
        let mut blocks: Vec<Block> = ms.iter().map(|&m| Block::new(6 + m)).collect();
        for (c, b) in blocks.iter_mut().enumerate() {
            for i in 0..b.n {
                for j in 0..b.n {
                    let v = if i < 6 && j < 6 {
                        rng.next() + if i == j { 4.0 } else { 0.0 }
                    } else if i >= 6 && j >= 6 && !general {
                        0.0
                    } else {
                        rng.next()
                    };
                    b.d[i * NMAX + j] = v;
                }
                b.r[i] = rng.next();
            }
            if !general {
                // as in the Newton matrix: independent joint rows (C of full rank, here a
                // perturbed unit matrix: joint gradients are close to orthonormal) and
                // B = Cᵀ + a small non-symmetric part (gradients at q̄ and at q)
                for k in 6..b.n {
                    b.d[k * NMAX + (k + 3 * c) % 6] += 2.0;
                }
                for i in 0..6 {
                    for j in 6..b.n {
                        b.d[i * NMAX + j] = b.d[j * NMAX + i] + 0.05 * rng.next();
                    }
                }
            }
            if parent[c].is_some() {
                // as in the Newton matrix: body–body couplings O(h²), the joint rows' parent
                // columns U_μ O(1), the parent's multiplier columns L_μ ≈ U_μᵀ (so that the
                // Schur updates of the parent's K are close to positive semi-definite)
                for i in 0..b.n {
                    let s = if i < 6 && !general { 0.05 } else { 1.0 };
                    for j in 0..6 {
                        b.u[i * 6 + j] = s * rng.next();
                        b.l[j * NMAX + i] = if i >= 6 && !general {
                            b.u[i * 6 + j] + 0.05 * rng.next()
                        } else {
                            s * rng.next()
                        };
                    }
                }
            }
        }
        let off: Vec<usize> = blocks
            .iter()
            .scan(0, |s, b| {
                let o = *s;
                *s += b.n;
                Some(o)
            })
            .collect();
        let nt: usize = blocks.iter().map(|b| b.n).sum();
        let mut a = vec![0.0; nt * nt];
        for (c, b) in blocks.iter().enumerate() {
            for i in 0..b.n {
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
        (blocks, a, nt, off)
    }

    /// Dense solution of `a x = r` for the right-hand sides held in the blocks.
    fn dense_solve(a: &[f64], nt: usize, off: &[usize], blocks: &[Block]) -> Dense {
        let mut f = a.to_vec();
        let mut rhs = vec![0.0; nt];
        for (c, b) in blocks.iter().enumerate() {
            rhs[off[c]..off[c] + b.n].copy_from_slice(&b.r[..b.n]);
        }
        let mut x = rhs.clone();
        let mut piv = vec![0; nt];
        assert!(lu_factor(&mut f, nt, nt, &mut piv, 1e-14));
        lu_solve(&f, nt, nt, &piv, &mut x);
        Dense {
            a: a.to_vec(),
            rhs,
            x,
        }
    }

    /// A dense system, its right-hand side and its LU solution.
    struct Dense {
        a: Vec<f64>,
        rhs: Vec<f64>,
        x: Vec<f64>,
    }

    /// Max norm.
    fn norm(v: &[f64]) -> f64 {
        v.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
    }

    /// Relative residual `‖A x − r‖ / (‖A‖ ‖x‖ + ‖r‖)` (max norms).
    fn residual(d: &Dense, x: &[f64]) -> f64 {
        let nt = d.rhs.len();
        let amax = (0..nt)
            .map(|i| norm(&d.a[i * nt..(i + 1) * nt]) * nt as f64)
            .fold(0.0, f64::max);
        let res: Vec<f64> = (0..nt)
            .map(|i| (0..nt).map(|j| d.a[i * nt + j] * x[j]).sum::<f64>() - d.rhs[i])
            .collect();
        norm(&res) / (amax * norm(x) + norm(&d.rhs))
    }

    /// The tree solution in the blocks is backward stable (relative residual at round-off) and
    /// agrees with the dense LU solution.
    fn assert_close(blocks: &[Block], off: &[usize], d: &Dense) {
        let mut x = vec![0.0; d.rhs.len()];
        for (c, b) in blocks.iter().enumerate() {
            x[off[c]..off[c] + b.n].copy_from_slice(&b.r[..b.n]);
        }
        let (rt, rd) = (residual(d, &x), residual(d, &d.x));
        let diff: Vec<f64> = x.iter().zip(&d.x).map(|(a, b)| a - b).collect();
        assert!(rt < 1e-15, "tree residual {rt:e} (dense {rd:e})");
        assert!(norm(&diff) < 1e-12 * norm(&d.x), "{diff:?}");
    }

    /// The tree elimination reproduces a dense solve of the same system (general diagonal
    /// blocks, non-zero μμ block included).
    #[test]
    fn tree_matches_dense() {
        // chain 0 ← 1 ← 2 plus 3 attached to 1; sizes 6+5, 6+5, 6+3, 6+0
        let parent = [None, Some(0), Some(1), Some(1)];
        let mut rng = Rng(1);
        let (mut blocks, a, nt, off) = system(&parent, &[5, 5, 3, 0], true, &mut rng);
        let x = dense_solve(&a, nt, &off, &blocks);
        assert!(solve_tree(&mut blocks, &[0, 1, 2, 3], &parent));
        assert_close(&blocks, &off, &x);
    }

    /// The real `[K B; C 0]` pattern for every row count 0..=6 (3, 5, 6 and 0 at leaves,
    /// inner nodes and the root), as one tree and as single supernodes.
    #[test]
    fn saddle_blocks_match_dense() {
        // 0 (root) ← 1 ← 2 ← 3, 1 ← 4, 0 ← 5 ← 6, 5 ← 7
        let parent = [
            None,
            Some(0),
            Some(1),
            Some(2),
            Some(1),
            Some(0),
            Some(5),
            Some(5),
        ];
        let order = [0, 1, 2, 3, 4, 5, 6, 7];
        let mut rng = Rng(7);
        for ms in [
            [0, 3, 5, 6, 0, 6, 3, 5],
            [6, 5, 0, 3, 6, 1, 2, 4],
            [3, 0, 6, 5, 3, 0, 0, 6],
        ] {
            let (mut blocks, a, nt, off) = system(&parent, &ms, false, &mut rng);
            let x = dense_solve(&a, nt, &off, &blocks);
            assert!(solve_tree(&mut blocks, &order, &parent));
            assert_close(&blocks, &off, &x);
        }
        for m in 0..=6 {
            let (mut blocks, a, nt, off) = system(&[None], &[m], false, &mut rng);
            let x = dense_solve(&a, nt, &off, &blocks);
            assert!(solve_tree(&mut blocks, &[0], &[None]));
            assert_close(&blocks, &off, &x);
        }
    }

    /// One factorisation serves several right-hand sides; the factorisation leaves `r` alone.
    #[test]
    fn factor_once_solve_twice() {
        let parent = [None, Some(0), Some(1), Some(1), Some(3)];
        let order = [0, 1, 3, 4, 2];
        let mut rng = Rng(3);
        let (mut blocks, a, nt, off) = system(&parent, &[6, 5, 3, 0, 6], false, &mut rng);
        let r0: Vec<[f64; NMAX]> = blocks.iter().map(|b| b.r).collect();
        let x1 = dense_solve(&a, nt, &off, &blocks);
        assert!(factor_tree(&mut blocks, &order, &parent));
        for (b, r) in blocks.iter().zip(&r0) {
            assert_eq!(b.r, *r, "factor_tree touched r");
        }
        solve_factored(&mut blocks, &order, &parent);
        assert_close(&blocks, &off, &x1);
        // a new right-hand side, written as the assembly does (zero, then add)
        for b in &mut blocks {
            b.r.fill(0.0);
            for i in 0..b.n {
                b.r[i] += 3.0 * rng.next();
            }
        }
        let x2 = dense_solve(&a, nt, &off, &blocks);
        solve_factored(&mut blocks, &order, &parent);
        assert_close(&blocks, &off, &x2);
    }

    /// Singular blocks are reported: dependent constraint rows (`S` singular), a zero body
    /// block, a non-finite entry.
    #[test]
    fn singular_block_fails() {
        let parent = [None, Some(0)];
        let order = [0, 1];
        let mut rng = Rng(11);
        // two equal rows of C on the leaf
        let (mut blocks, ..) = system(&parent, &[3, 4], false, &mut rng);
        for j in 0..6 {
            blocks[1].d[7 * NMAX + j] = blocks[1].d[6 * NMAX + j];
        }
        assert!(!factor_tree(&mut blocks, &order, &parent));
        // zero multiplier columns on the root
        let (mut blocks, ..) = system(&parent, &[3, 4], false, &mut rng);
        for i in 0..6 {
            blocks[0].d[i * NMAX + 8] = 0.0;
        }
        assert!(!solve_tree(&mut blocks, &order, &parent));
        // zero body block
        let (mut blocks, ..) = system(&parent, &[0, 2], false, &mut rng);
        blocks[1].d.fill(0.0);
        assert!(!factor_tree(&mut blocks, &order, &parent));
        // NaN
        let (mut blocks, ..) = system(&parent, &[2, 2], false, &mut rng);
        blocks[0].d[6 * NMAX + 1] = f64::NAN;
        assert!(!factor_tree(&mut blocks, &order, &parent));
    }
}
