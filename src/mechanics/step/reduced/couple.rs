//! Joint couplings `q_b = r q_a + o` in the reduced iteration: a bordered solve on the tree
//! factors, one multiplier `μ_c` per coupling (`step::coupling`'s row and reaction).
//!
//! The reaction `μ_c w D_j` of coupling `c` on its joint `j` (`w = 1` for the following
//! joint, `−r` for the leading one) is a load of constant size on the joint, evaluated with
//! the joint's own loads (`eval`), so its `μ ∂D/∂x` blocks join the tree matrix `J`. Its
//! multiplier column in the reduced equations is `P̄ᵀ w D_j`: `S̄_jᵀ` of the reaction's
//! wrench on the child (on every other rate it is zero to round-off: `D_j` is the midpoint
//! gradient of rigid-motion invariants of the pair, so the pair's net wrench vanishes). With
//! `z₀ = −J⁻¹ R` (the tree solve, defects included), `z_d = −J⁻¹ e_d` for each column `e_d`
//! (at factorisation), and the rows `G_c = ∂g_c/∂x` on the body twists:
//!
//! ```text
//! S δμ = −(g + G z₀),   S_cd = G_c z_d,   δx = z₀ + Σ_d δμ_d z_d,   μ ← μ + δμ
//! ```
//!
//! The residual that judges the first update (`iterate`) is the rates' residual after the
//! multipliers' update, `R + Σ_d δμ_d e_d` on the coupled joints' rates: the reduced
//! equations are linear in `μ`, so a poorly predicted multiplier (the predictor holds `λ`
//! from the last stage) costs no second iteration.
//!
//! This is the multiplier form's solution of the same equations restricted to the tree's
//! null space, so the converged stage is the multiplier form's: the reaction's work is
//! `−μ e₀` (the stage-start defect, at round-off) and it preserves the momenta. Cost per
//! factorisation: one O(N) tree solve per coupling and a `k × k` LU; per iteration
//! `O(k (N + k))`.

use super::super::work::Work;
use super::maps::V6;
use super::tree::solve;
use super::work::RedWork;
use crate::mechanics::model::runtime::Model;

fn dot6(a: &V6, b: &V6) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// `G_c x` for body twists `x`.
fn row_times(row: &[(usize, V6); 4], x: &[V6]) -> f64 {
    row.iter()
        .filter(|(b, _)| *b != usize::MAX)
        .map(|(b, r)| dot6(r, &x[*b]))
        .sum()
}

/// After a factorisation: the column solves `z_d` and the factored Schur matrix; false if it
/// is singular. Leaves `rw.res` as it found it.
pub(crate) fn factor(model: &Model, rw: &mut RedWork) -> bool {
    let k = model.couplings.len();
    if k == 0 {
        return true;
    }
    let mut cp = std::mem::take(&mut rw.cpl);
    cp.keep.copy_from_slice(&rw.res);
    for d in 0..k {
        for x in rw.res.iter_mut().chain(rw.c.iter_mut()) {
            *x = [0.0; 6];
        }
        for (slot, &(b, v, wrench)) in cp.slots[d].col.iter().enumerate() {
            let mut e = v;
            if wrench {
                rw.fp[b].st_mul(&v, &mut e);
            }
            for (r, v) in rw.res[b].iter_mut().zip(e) {
                *r += v;
            }
            cp.e[d][slot] = (b, e);
        }
        solve(model, rw);
        cp.z[d].copy_from_slice(&rw.dx);
    }
    rw.res.copy_from_slice(&cp.keep);
    for c in 0..k {
        for d in 0..k {
            cp.schur[k * c + d] = row_times(&cp.slots[c].row, &cp.z[d]);
        }
    }
    let ok = lu(&mut cp.schur, &mut cp.perm, k);
    rw.cpl = cp;
    ok
}

/// After a tree solve (`rw.dx = z₀`): the multipliers' update and the body twists of the
/// bordered solution.
pub(crate) fn correct(model: &Model, ws: &mut Work, rw: &mut RedWork) {
    let k = model.couplings.len();
    if k == 0 {
        return;
    }
    let cp = &mut rw.cpl;
    for c in 0..k {
        cp.rhs[c] = -(cp.slots[c].g + row_times(&cp.slots[c].row, &rw.dx));
    }
    lu_solve(&cp.schur, &cp.perm, k, &mut cp.rhs);
    for d in 0..k {
        let dm = cp.rhs[d];
        ws.mu[model.couplings[d].row] += dm;
        for (x, z) in rw.dx.iter_mut().zip(&cp.z[d]) {
            for i in 0..6 {
                x[i] += dm * z[i];
            }
        }
    }
}

/// Before a tree solve: keeps the coupled joints' reduced residual (`rw.res` of their
/// children), which the solve overwrites.
pub(crate) fn keep(rw: &mut RedWork) {
    let cp = &mut rw.cpl;
    for &b in &cp.bodies {
        cp.keep[b] = rw.res[b];
    }
}

/// After [`correct`]: the largest scaled reduced residual on the coupled joints' rates with
/// the multipliers updated, `R + Σ_d δμ_d e_d` (moments times the child's moment scale,
/// forces times its force scale).
pub(crate) fn residual(model: &Model, rw: &mut RedWork) -> f64 {
    let cp = &mut rw.cpl;
    for (d, e) in cp.e.iter().enumerate() {
        for &(b, v) in e {
            for (r, x) in cp.keep[b].iter_mut().zip(v) {
                *r += cp.rhs[d] * x;
            }
        }
    }
    let mut res = 0.0_f64;
    for &b in &cp.bodies {
        let (m, br) = (&rw.fp[b], &model.bodies[b]);
        for k in 0..m.f() {
            let s = if k < m.fr { br.ms } else { br.fs };
            res = res.max((cp.keep[b][k] * s).abs());
        }
    }
    res
}

/// In-place LU with partial pivoting of the row-major `n × n` matrix `a`; false if a pivot
/// is zero or not finite.
fn lu(a: &mut [f64], perm: &mut [usize], n: usize) -> bool {
    for (i, p) in perm.iter_mut().enumerate() {
        *p = i;
    }
    for col in 0..n {
        let piv = (col..n)
            .max_by(|&x, &y| a[n * x + col].abs().total_cmp(&a[n * y + col].abs()))
            .unwrap_or(col);
        let pv = a[n * piv + col];
        if !(pv.is_finite() && pv != 0.0) {
            return false;
        }
        if piv != col {
            for j in 0..n {
                a.swap(n * piv + j, n * col + j);
            }
            perm.swap(piv, col);
        }
        for r in col + 1..n {
            let f = a[n * r + col] / pv;
            a[n * r + col] = f;
            for j in col + 1..n {
                a[n * r + j] -= f * a[n * col + j];
            }
        }
    }
    true
}

/// Solves with the factors of [`lu`]: `b ← A⁻¹ b`.
fn lu_solve(a: &[f64], perm: &[usize], n: usize, b: &mut [f64]) {
    apply_perm(perm, b);
    for i in 0..n {
        for j in 0..i {
            b[i] -= a[n * i + j] * b[j];
        }
    }
    for i in (0..n).rev() {
        for j in i + 1..n {
            b[i] -= a[n * i + j] * b[j];
        }
        b[i] /= a[n * i + i];
    }
}

/// `b ← P b` (`(P b)_i = b_{perm_i}`) in place by following the permutation's cycles.
fn apply_perm(perm: &[usize], b: &mut [f64]) {
    let n = perm.len();
    for start in 0..n {
        // each cycle is walked from its smallest index
        let mut i = perm[start];
        while i > start {
            i = perm[i];
        }
        if i < start {
            continue;
        }
        let first = b[start];
        let mut cur = start;
        loop {
            let next = perm[cur];
            if next == start {
                b[cur] = first;
                break;
            }
            b[cur] = b[next];
            cur = next;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{apply_perm, lu, lu_solve};

    #[test]
    fn lu_solves_a_pivoting_system() {
        for n in [1, 3, 20] {
            // a row permutation of a diagonally dominant matrix, small on the diagonal: the
            // elimination must pivot (zero where n = 1: singular)
            let a: Vec<f64> = (0..n * n)
                .map(|i| {
                    let (r, c) = (i / n, i % n);
                    if n == 1 {
                        0.0
                    } else if c == (r + 1) % n {
                        n as f64 + 1.0
                    } else {
                        0.5 * ((i + 1) as f64).sin()
                    }
                })
                .collect();
            let x: Vec<f64> = (0..n).map(|i| i as f64 - 1.5).collect();
            let mut b: Vec<f64> = (0..n)
                .map(|i| (0..n).map(|j| a[n * i + j] * x[j]).sum())
                .collect();
            let mut f = a.clone();
            let mut perm = vec![0; n];
            if n == 1 {
                // a zero 1 × 1 matrix is singular
                assert!(!lu(&mut f, &mut perm, n));
                continue;
            }
            assert!(lu(&mut f, &mut perm, n));
            lu_solve(&f, &perm, n, &mut b);
            for i in 0..n {
                assert!((b[i] - x[i]).abs() < 1e-10, "n {n}: {} vs {}", b[i], x[i]);
            }
        }
    }

    #[test]
    fn perm_is_applied_by_cycles() {
        let perm = [2, 0, 1, 4, 3, 5];
        let mut b = [10.0, 11.0, 12.0, 13.0, 14.0, 15.0];
        apply_perm(&perm, &mut b);
        assert_eq!(b, [12.0, 10.0, 11.0, 14.0, 13.0, 15.0]);
    }
}
