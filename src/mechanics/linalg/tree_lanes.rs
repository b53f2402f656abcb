//! [`solve_factored`](super::solve_factored) for `LANES` right-hand sides at once: the same
//! eliminations on each lane, so that a supernode's factors are loaded once per group of
//! columns and the products run on the compiler's vector lanes (the step's tangent map solves
//! one column per state and input, `step::tangent`).
//!
//! ```text
//! leaves to root   t = K⁻¹ f,  μ = S⁻¹ (g − C t),  x = t − K⁻¹B μ,   r_p −= L (x, μ)
//! root to leaves   r −= Y x_p
//! ```
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use super::super::small_mat::load;
use super::{Block, NMAX};

/// Columns solved together.
pub const LANES: usize = 4;

/// One supernode's right-hand sides (then solutions): `NMAX` rows of `LANES` columns.
pub type Lanes = [[f64; LANES]; NMAX];

/// `a x` for `x` with `LANES` columns (the first `C` rows of `x`).
#[inline(always)]
fn mul_lanes<const R: usize, const C: usize>(
    a: &[[f64; C]; R],
    x: &[[f64; LANES]],
) -> [[f64; LANES]; R] {
    let mut out = [[0.0; LANES]; R];
    for i in 0..R {
        for k in 0..C {
            let aik = a[i][k];
            for l in 0..LANES {
                out[i][l] += aik * x[k][l];
            }
        }
    }
    out
}

/// Forward elimination of a supernode with `M` joint rows; returns `L (x, μ)` for the parent.
#[inline(always)]
fn forward_block<const M: usize>(b: &Block, r: &mut Lanes, has_parent: bool) -> [[f64; LANES]; 6] {
    let ki: [[f64; 6]; 6] = load(&b.d, 0, 0, NMAX);
    let mut x = mul_lanes(&ki, &r[..6]);
    let mut g = [[0.0; LANES]; M];
    if M > 0 {
        let c: [[f64; 6]; M] = load(&b.d, 6, 0, NMAX);
        let si: [[f64; M]; M] = load(&b.d, 6, 6, NMAX);
        let kb: [[f64; M]; 6] = load(&b.d, 0, 6, NMAX);
        let ct = mul_lanes(&c, &x);
        let mut h = [[0.0; LANES]; M];
        for i in 0..M {
            for l in 0..LANES {
                h[i][l] = r[6 + i][l] - ct[i][l];
            }
        }
        g = mul_lanes(&si, &h);
        let kg = mul_lanes(&kb, &g);
        for i in 0..6 {
            for l in 0..LANES {
                x[i][l] -= kg[i][l];
            }
        }
        r[6..6 + M].copy_from_slice(&g);
    }
    r[..6].copy_from_slice(&x);
    if !has_parent {
        return [[0.0; LANES]; 6];
    }
    let lx: [[f64; 6]; 6] = load(&b.l, 0, 0, NMAX);
    let lm: [[f64; M]; 6] = load(&b.l, 0, 6, NMAX);
    let mut ly = mul_lanes(&lx, &x);
    let lg = mul_lanes(&lm, &g);
    for i in 0..6 {
        for l in 0..LANES {
            ly[i][l] += lg[i][l];
        }
    }
    ly
}

/// Back substitution of a supernode with `M` joint rows: `r ← r − Y x_p`.
#[inline(always)]
fn back_block<const M: usize>(b: &Block, r: &mut Lanes, xp: &[[f64; LANES]; 6]) {
    let y: [[f64; 6]; 6] = load(&b.u, 0, 0, 6);
    let yx = mul_lanes(&y, xp);
    for i in 0..6 {
        for l in 0..LANES {
            r[i][l] -= yx[i][l];
        }
    }
    if M > 0 {
        let y: [[f64; 6]; M] = load(&b.u, 6, 0, 6);
        let ym = mul_lanes(&y, xp);
        for i in 0..M {
            for l in 0..LANES {
                r[6 + i][l] -= ym[i][l];
            }
        }
    }
}

/// A supernode factored whole (`n = N`): `r ← D⁻¹ r`, returns `L r`.
#[inline(always)]
fn forward_whole<const N: usize>(b: &Block, r: &mut Lanes, has_parent: bool) -> [[f64; LANES]; 6] {
    let di: [[f64; N]; N] = load(&b.d, 0, 0, NMAX);
    let x = mul_lanes(&di, &r[..N]);
    r[..N].copy_from_slice(&x);
    if !has_parent {
        return [[0.0; LANES]; 6];
    }
    let l: [[f64; N]; 6] = load(&b.l, 0, 0, NMAX);
    mul_lanes(&l, &x)
}

/// Solves the factored tree system (after [`factor_tree`](super::factor_tree)) for the
/// right-hand sides `r` (one [`Lanes`] per supernode, by body index); on return `r` holds
/// the solutions. The factors are read, not changed.
pub fn solve_factored_lanes(
    blocks: &[Block],
    order: &[usize],
    parent: &[Option<usize>],
    r: &mut [Lanes],
) {
    for &c in order.iter().rev() {
        let b = &blocks[c];
        let has = parent[c].is_some();
        let ly = if b.whole {
            by_size!(
                b.n,
                forward_whole(b, &mut r[c], has),
                unreachable!("supernode size")
            )
        } else {
            by_rows!(
                b.n - 6,
                forward_block(b, &mut r[c], has),
                unreachable!("supernode size")
            )
        };
        if let Some(p) = parent[c] {
            for i in 0..6 {
                for l in 0..LANES {
                    r[p][i][l] -= ly[i][l];
                }
            }
        }
    }
    for &c in order {
        if let Some(p) = parent[c] {
            let xp: [[f64; LANES]; 6] = std::array::from_fn(|i| r[p][i]);
            let b = &blocks[c];
            by_rows!(
                b.n - 6,
                back_block(b, &mut r[c], &xp),
                unreachable!("supernode size")
            );
        }
    }
}
