//! Dense LU with partial pivoting: the small Schur complement of the bordered loop solve
//! (`border`), and the whole Newton and projection systems (`6 N + active rows` unknowns) for the
//! dense test oracle (`Model::dense`); row-major, preallocated by the caller.
// index loops over the rows and columns of a row-major matrix read closer to the formulas
#![allow(clippy::needless_range_loop)]

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
