//! Fixed-size dense kernels of the supernode factorisation (`solver`): sub-matrix load/store,
//! Gauss–Jordan inversion with partial pivoting, products. Sizes are const generics so that every
//! loop unrolls.
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

/// The `R × C` sub-matrix at `(r0, c0)` of the row-major `a` (row stride `s`).
#[inline(always)]
pub(crate) fn load<const R: usize, const C: usize>(
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
pub(crate) fn store<const R: usize, const C: usize>(
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
pub(crate) fn amax<const R: usize, const C: usize>(a: &[[f64; C]; R]) -> f64 {
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
pub(crate) fn is_zero<const R: usize, const C: usize>(a: &[[f64; C]; R]) -> bool {
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
pub(crate) fn invert<const N: usize>(a: &mut [[f64; N]; N], tiny: f64) -> bool {
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
pub(crate) fn mul<const R: usize, const C: usize, const K: usize>(
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
pub(crate) fn sub_mul<const R: usize, const C: usize, const K: usize>(
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
pub(crate) fn mul_vec<const R: usize, const C: usize>(a: &[[f64; C]; R], v: &[f64; C]) -> [f64; R] {
    let mut x = [0.0; R];
    for i in 0..R {
        for j in 0..C {
            x[i] += a[i][j] * v[j];
        }
    }
    x
}
