//! Linear algebra of the Newton step: the tree block elimination (Baraff's linear-time method);
//! systems with loop-closing joints border it (`border`).
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
//! Systems with loop-closing joints factor their spanning tree here and eliminate the loop rows
//! (and the couplings of loop joints between bodies not adjacent in the tree) by a small dense
//! Schur complement (`border`): O(N·t + t³). The dense LU over all unknowns (`dense`, O(N³))
//! remains only as the test oracle (`Model::dense`).
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

pub use super::dense::{lu_factor, lu_solve};
use super::small_mat::{amax, invert, is_zero, load, mul, mul_vec, store, sub_mul};

/// Largest supernode size: 6 body unknowns + 6 joint rows.
pub const NMAX: usize = 12;

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
    /// Factor the whole diagonal block `D` (Gauss–Jordan with partial pivoting over all `n`
    /// unknowns) instead of eliminating through `K`: for a body whose own mass matrix is
    /// singular or small next to what its joints carry (`K` singular or ill-conditioned
    /// while `D` is regular). After [`factor_tree`], `d` then holds `D⁻¹`.
    pub whole: bool,
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
            whole: false,
        }
    }

    /// Zeroes the used parts of the matrices and the right-hand side.
    pub fn clear(&mut self) {
        // whole rows (stride NMAX): one contiguous fill per matrix instead of one per row
        let n = self.n;
        self.d[..n * NMAX].fill(0.0);
        self.u[..n * 6].fill(0.0);
        self.l.fill(0.0);
        self.r.fill(0.0);
    }
}

/// Relative pivot threshold of the supernode factorisations.
const REL: f64 = 1e-14;

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

/// [`factor_block`] for a block factored whole (`n = N`): `d ← D⁻¹`, `U ← Y = D⁻¹ U` and the
/// parent's update `L Y` if `has_parent`; `None` if a pivot is not above `1e-14 |D|`.
#[inline(always)]
fn factor_whole<const N: usize>(b: &mut Block, has_parent: bool) -> Option<[[f64; 6]; 6]> {
    let mut di: [[f64; N]; N] = load(&b.d, 0, 0, NMAX);
    let dmax = amax(&di);
    if !(dmax.is_finite() && dmax > 0.0 && invert(&mut di, REL * dmax)) {
        return None;
    }
    store(&mut b.d, 0, 0, NMAX, &di);
    if !has_parent {
        return Some([[0.0; 6]; 6]);
    }
    let u: [[f64; 6]; N] = load(&b.u, 0, 0, 6);
    let y = mul(&di, &u);
    store(&mut b.u, 0, 0, 6, &y);
    let l: [[f64; N]; 6] = load(&b.l, 0, 0, NMAX);
    Some(mul(&l, &y))
}

/// [`forward_block`] for a block factored whole (`n = N`): `r ← D⁻¹ r`, returns `L r`.
#[inline(always)]
fn forward_whole<const N: usize>(b: &mut Block, has_parent: bool) -> [f64; 6] {
    let di: [[f64; N]; N] = load(&b.d, 0, 0, NMAX);
    let r: [f64; N] = b.r[..N].try_into().unwrap_or([0.0; N]);
    let x = mul_vec(&di, &r);
    b.r[..N].copy_from_slice(&x);
    if !has_parent {
        return [0.0; 6];
    }
    let l: [[f64; N]; 6] = load(&b.l, 0, 0, NMAX);
    mul_vec(&l, &x)
}

/// Calls `$f::<n>($args)` for the run-time supernode size `$n` ∈ 6..=12.
macro_rules! by_size {
    ($n:expr, $f:ident ( $($arg:expr),* ), $other:expr) => {
        match $n {
            6 => $f::<6>($($arg),*),
            7 => $f::<7>($($arg),*),
            8 => $f::<8>($($arg),*),
            9 => $f::<9>($($arg),*),
            10 => $f::<10>($($arg),*),
            11 => $f::<11>($($arg),*),
            12 => $f::<12>($($arg),*),
            _ => $other,
        }
    };
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
        let upd = if b.whole {
            by_size!(b.n, factor_whole(b, p.is_some()), None)
        } else {
            by_rows!(m, factor_block(b, p.is_some()), None)
        };
        let Some(upd) = upd else {
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
        let ly = if b.whole {
            by_size!(
                b.n,
                forward_whole(b, parent[c].is_some()),
                unreachable!("supernode size")
            )
        } else {
            by_rows!(
                b.n - 6,
                forward_block(b, parent[c].is_some()),
                unreachable!("supernode size")
            )
        };
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

#[path = "tree_lanes.rs"]
pub(crate) mod lanes;

#[cfg(test)]
#[path = "tree_tests.rs"]
mod tests;
