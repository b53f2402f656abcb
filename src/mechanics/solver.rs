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
//! inverts `K` and the m × m Schur complement `S = E − C K⁻¹ B` (Gauss–Jordan with partial
//! pivoting; fixed sizes through const generics, so that every loop unrolls), forms
//! `Y = D⁻¹ U` and updates the parent's `K` by `−L Y`; [`solve_factored`] then solves for any number of right-hand sides with the stored
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
/// After it, `d` holds `[K⁻¹, K⁻¹B; C, S⁻¹]` (`K` with the children's Schur updates,
/// `S = E − C K⁻¹ B`), `u` holds `Y = D⁻¹ U` (unchanged for a root); `l` and `n` are kept; `r`
/// is never read or written by the factorisation.
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
    let mut x = [[0.0; C]; R];
    for i in 0..R {
        x[i].copy_from_slice(&a[(r0 + i) * s + c0..(r0 + i) * s + c0 + C]);
    }
    x
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

/// Largest `|entry|` (NaN entries are skipped; a comparison select vectorises where
/// `f64::max` does not).
#[inline(always)]
fn amax<const R: usize, const C: usize>(a: &[[f64; C]; R]) -> f64 {
    let mut m = 0.0_f64;
    for row in a {
        for &v in row {
            let v = v.abs();
            m = if v > m { v } else { m };
        }
    }
    m
}

/// True if every entry is finite (the sum is: NaN and infinities propagate).
#[inline(always)]
fn finite<const R: usize, const C: usize>(a: &[[f64; C]; R]) -> bool {
    let mut s = 0.0;
    for row in a {
        for &v in row {
            s += v;
        }
    }
    s.is_finite()
}

/// True if every entry is zero.
#[inline(always)]
fn is_zero<const R: usize, const C: usize>(a: &[[f64; C]; R]) -> bool {
    let mut z = true;
    for row in a {
        for &v in row {
            z &= v == 0.0;
        }
    }
    z
}

/// In-place inverse by Gauss–Jordan elimination with partial (row) pivoting; false if a pivot
/// is not above `tiny` or the inverse is not finite. Every update runs over full fixed-length
/// rows, so the loops unroll and vectorise.
#[inline(always)]
fn invert<const N: usize>(a: &mut [[f64; N]; N], tiny: f64) -> bool {
    let mut piv = [0usize; N];
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
        piv[k] = p;
        a.swap(k, p);
        let mut rk = a[k];
        let inv = 1.0 / rk[k];
        rk[k] = 1.0;
        for j in 0..N {
            rk[j] *= inv;
        }
        for i in 0..N {
            if i != k {
                let f = a[i][k];
                a[i][k] = 0.0;
                for j in 0..N {
                    a[i][j] -= f * rk[j];
                }
            }
        }
        a[k] = rk;
    }
    // row interchanges of A are column interchanges of A⁻¹, undone in reverse order
    for k in (0..N).rev() {
        let p = piv[k];
        if p != k {
            for row in a.iter_mut() {
                row.swap(k, p);
            }
        }
    }
    finite(a)
}

/// `A B` for `A` `R × C`, `B` `C × K`.
#[inline(always)]
fn mul<const R: usize, const C: usize, const K: usize>(
    a: &[[f64; C]; R],
    b: &[[f64; K]; C],
) -> [[f64; K]; R] {
    let mut x = [[0.0; K]; R];
    for i in 0..R {
        for l in 0..C {
            let f = a[i][l];
            for c in 0..K {
                x[i][c] += f * b[l][c];
            }
        }
    }
    x
}

/// `x −= A B` for `A` `R × C`, `B` `C × K`.
#[inline(always)]
fn sub_mul<const R: usize, const C: usize, const K: usize>(
    x: &mut [[f64; K]; R],
    a: &[[f64; C]; R],
    b: &[[f64; K]; C],
) {
    for i in 0..R {
        for l in 0..C {
            let f = a[i][l];
            for c in 0..K {
                x[i][c] -= f * b[l][c];
            }
        }
    }
}

/// `A v` for `A` `R × C`.
#[inline(always)]
fn mul_vec<const R: usize, const C: usize>(a: &[[f64; C]; R], v: &[f64; C]) -> [f64; R] {
    let mut x = [0.0; R];
    for i in 0..R {
        for j in 0..C {
            x[i] += a[i][j] * v[j];
        }
    }
    x
}

/// Factors supernode `b` (`m = M` joint rows) in place and, if `has_parent`, replaces `U` by
/// `Y = D⁻¹ U` and returns the parent's Schur update `L Y` (6 × 6); `None` if singular.
///
/// `D = [K B; C E]` is eliminated through `K`: with `S = E − C K⁻¹ B` (m × m),
/// `D⁻¹ [f; g] = [t − K⁻¹B μ; μ]`, `t = K⁻¹ f`, `μ = S⁻¹ (g − C t)`. Stored in `d`: `K⁻¹`
/// (rows and columns `0..6`), `K⁻¹ B` (rows `0..6`, columns `6..n`), `C` (kept, rows `6..n`,
/// columns `0..6`) and `S⁻¹` (rows and columns `6..n`). The explicit inverses (Gauss–Jordan
/// with partial pivoting) make every later product a fixed-size loop; `K` (inertia plus
/// positive semi-definite child updates) and `S` are well conditioned for regular models.
#[inline(always)]
fn factor_block<const M: usize>(b: &mut Block, has_parent: bool) -> Option<[[f64; 6]; 6]> {
    let mut ki: [[f64; 6]; 6] = load(&b.d, 0, 0, NMAX);
    let bm: [[f64; M]; 6] = load(&b.d, 0, 6, NMAX);
    let c: [[f64; 6]; M] = load(&b.d, 6, 0, NMAX);
    let mut s: [[f64; M]; M] = load(&b.d, 6, 6, NMAX);
    let kmax = amax(&ki);
    if !(kmax.is_finite() && kmax > 0.0 && invert(&mut ki, REL * kmax)) {
        return None;
    }
    let kb = mul(&ki, &bm);
    // S = E − C K⁻¹B; pivots are judged against the size of the terms before cancellation
    sub_mul(&mut s, &c, &kb);
    if M > 0 {
        let sref = amax(&s).max(6.0 * amax(&c) * amax(&kb));
        if !(sref.is_finite() && invert(&mut s, REL * sref)) {
            return None;
        }
    }
    store(&mut b.d, 0, 0, NMAX, &ki);
    store(&mut b.d, 0, 6, NMAX, &kb);
    store(&mut b.d, 6, 6, NMAX, &s);
    if !has_parent {
        return Some([[0.0; 6]; 6]);
    }
    // Y_μ = S⁻¹ (U_μ − C K⁻¹ U_x), Y_x = K⁻¹ U_x − K⁻¹B Y_μ; the body–body couplings U_x,
    // L_x vanish in the projection system, whose products are then skipped
    let ux: [[f64; 6]; 6] = load(&b.u, 0, 0, 6);
    let mut yx = [[0.0; 6]; 6];
    let mut um: [[f64; 6]; M] = load(&b.u, 6, 0, 6);
    if !is_zero(&ux) {
        yx = mul(&ki, &ux);
        sub_mul(&mut um, &c, &yx);
    }
    let ym = mul(&s, &um);
    sub_mul(&mut yx, &kb, &ym);
    store(&mut b.u, 0, 0, 6, &yx);
    store(&mut b.u, 6, 0, 6, &ym);
    // L Y = L_x Y_x + L_μ Y_μ
    let lx: [[f64; 6]; 6] = load(&b.l, 0, 0, NMAX);
    let lm: [[f64; M]; 6] = load(&b.l, 0, 6, NMAX);
    let mut upd = mul(&lm, &ym);
    if !is_zero(&lx) {
        let ux = mul(&lx, &yx);
        for i in 0..6 {
            for j in 0..6 {
                upd[i][j] += ux[i][j];
            }
        }
    }
    Some(upd)
}

/// Forward step of the solve for supernode `b` (`m = M`): `r ← D⁻¹ r` with the stored
/// factors; returns `L r` (the parent's right-hand side update) if `has_parent`, else zero.
#[inline(always)]
fn forward_block<const M: usize>(b: &mut Block, has_parent: bool) -> [f64; 6] {
    // t = K⁻¹ f, μ = S⁻¹ (g − C t), x = t − K⁻¹B μ
    let ki: [[f64; 6]; 6] = load(&b.d, 0, 0, NMAX);
    let f: [f64; 6] = b.r[..6].try_into().unwrap_or([0.0; 6]);
    let mut x = mul_vec(&ki, &f);
    let mut g = [0.0; M];
    if M > 0 {
        let c: [[f64; 6]; M] = load(&b.d, 6, 0, NMAX);
        let si: [[f64; M]; M] = load(&b.d, 6, 6, NMAX);
        let kb: [[f64; M]; 6] = load(&b.d, 0, 6, NMAX);
        let mut h: [f64; M] = b.r[6..6 + M].try_into().unwrap_or([0.0; M]);
        let ct = mul_vec(&c, &x);
        for i in 0..M {
            h[i] -= ct[i];
        }
        g = mul_vec(&si, &h);
        let kg = mul_vec(&kb, &g);
        for i in 0..6 {
            x[i] -= kg[i];
        }
        b.r[6..6 + M].copy_from_slice(&g);
    }
    b.r[..6].copy_from_slice(&x);
    if !has_parent {
        return [0.0; 6];
    }
    let lx: [[f64; 6]; 6] = load(&b.l, 0, 0, NMAX);
    let lm: [[f64; M]; 6] = load(&b.l, 0, 6, NMAX);
    let mut ly = mul_vec(&lx, &x);
    let lg = mul_vec(&lm, &g);
    for i in 0..6 {
        ly[i] += lg[i];
    }
    ly
}

/// Back substitution of supernode `b` (`n = 6 + M`): `r ← r − Y x_p`.
#[inline(always)]
fn back_block<const M: usize>(b: &mut Block, xp: &[f64; 6]) {
    let y: [[f64; 6]; 6] = load(&b.u, 0, 0, 6);
    let yx = mul_vec(&y, xp);
    for i in 0..6 {
        b.r[i] -= yx[i];
    }
    if M > 0 {
        let y: [[f64; 6]; M] = load(&b.u, 6, 0, 6);
        let ym = mul_vec(&y, xp);
        for i in 0..M {
            b.r[6 + i] -= ym[i];
        }
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
/// `blocks[b].d` and `.u` (now `D⁻¹ U`) hold the factors that [`solve_factored`]
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
        let ly = by_rows!(
            b.n - 6,
            forward_block(b, parent[c].is_some()),
            unreachable!("supernode size")
        );
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
        let (a, nt, off) = dense_of(&blocks, parent);
        (blocks, a, nt, off)
    }

    /// The dense matrix `(a, nt, offsets)` of a tree system.
    fn dense_of(blocks: &[Block], parent: &[Option<usize>]) -> (Vec<f64>, usize, Vec<usize>) {
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
        (a, nt, off)
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
        // the projection system has no body–body couplings between bodies (U_x = L_x = 0)
        let (mut blocks, a, nt, off) = {
            let (mut blocks, ..) = system(&parent, &[5, 3, 6, 0, 5, 2, 4, 6], false, &mut rng);
            for b in &mut blocks {
                b.u[..36].fill(0.0);
                for j in 0..6 {
                    b.l[j * NMAX..j * NMAX + 6].fill(0.0);
                }
            }
            let (a, nt, off) = dense_of(&blocks, &parent);
            (blocks, a, nt, off)
        };
        let x = dense_solve(&a, nt, &off, &blocks);
        assert!(solve_tree(&mut blocks, &order, &parent));
        assert_close(&blocks, &off, &x);
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
