//! Elimination of the reduced Newton matrix `P̄ᵀ K Q` over the tree, leaves to root, in the
//! manner of the articulated-body recursion (unsymmetric: `P̄` at the midpoint, `Q` at the
//! iterate). With `x_c = A x_p + S u_c` (maps `Q`) and the child's equations `S̄ᵀ W_c + R_c = 0`,
//! `W_c = K_c x_c + K_cp x_p + b_c` (`K_c` articulated, `b_c` the bias of its eliminated
//! subtree):
//!
//! ```text
//! D = S̄ᵀ K_c S,  Y = D⁻¹ S̄ᵀ (K_c A + K_cp),  H = Āᵀ K_c + K_pc
//! u_c = −Y x_p − D⁻¹ (S̄ᵀ b_c + R_c)
//! K_p += H A − (H S) Y + Āᵀ K_cp,   b_p += −H S D⁻¹ (S̄ᵀ b_c + R_c) + Āᵀ b_c
//! ```
//!
//! All blocks are 6 × 6 at most (`f ≤ 6` rates per joint), so one factorisation is O(N). The
//! factors are kept for chord iterations (`solve` with a new reduced residual).
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use super::super::model::Model;
use super::maps::{Map, V6};
use super::RedWork;
use crate::math::Vec3;

type M6 = [[f64; 6]; 6];

fn mat_vec(k: &M6, x: &V6) -> V6 {
    std::array::from_fn(|i| (0..6).map(|j| k[i][j] * x[j]).sum())
}

/// `X A` for the map's `A = [I −ê; 0 Z]` (row `i`: `[x_f, e × x_f + Z x_m]`).
fn right_a(x: &M6, m: &Map) -> M6 {
    let mut out = *x;
    for i in 0..6 {
        let xf = Vec3::new(x[i][0], x[i][1], x[i][2]);
        let mut r = m.e.cross(&xf);
        if m.z {
            r += Vec3::new(x[i][3], x[i][4], x[i][5]);
        }
        out[i][3..6].copy_from_slice(r.as_slice());
    }
    out
}

/// `Āᵀ X` (each column through [`Map::at_mul`]).
fn left_at(m: &Map, x: &M6) -> M6 {
    let mut out = [[0.0; 6]; 6];
    for c in 0..6 {
        let col: V6 = std::array::from_fn(|i| x[i][c]);
        let t = m.at_mul(&col);
        for i in 0..6 {
            out[i][c] = t[i];
        }
    }
    out
}

/// In-place inverse of the leading `n × n` block (Gauss–Jordan, partial pivoting); false if
/// a pivot is not above `1e-14` times the largest entry or the result is not finite.
fn invert(a: &mut M6, n: usize) -> bool {
    let big = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .fold(0.0_f64, |m, (i, j)| m.max(a[i][j].abs()));
    if n == 0 {
        return true;
    }
    if !(big.is_finite() && big > 0.0) {
        return false;
    }
    let mut piv = [0usize; 6];
    for k in 0..n {
        let mut p = k;
        for i in k + 1..n {
            if a[i][k].abs() > a[p][k].abs() {
                p = i;
            }
        }
        let pivot = a[p][k].abs();
        if pivot.is_nan() || pivot <= 1e-14 * big {
            return false;
        }
        piv[k] = p;
        a.swap(k, p);
        let inv = 1.0 / a[k][k];
        a[k][k] = 1.0;
        for j in 0..n {
            a[k][j] *= inv;
        }
        let rk = a[k];
        for i in 0..n {
            if i != k {
                let f = a[i][k];
                a[i][k] = 0.0;
                for j in 0..n {
                    a[i][j] -= f * rk[j];
                }
            }
        }
    }
    for k in (0..n).rev() {
        let p = piv[k];
        if p != k {
            for row in a.iter_mut().take(n) {
                row.swap(k, p);
            }
        }
    }
    a.iter()
        .take(n)
        .all(|r| r[..n].iter().all(|x| x.is_finite()))
}

/// Factors the Newton matrix assembled by the last Jacobian pass (`rw.kd` is overwritten by
/// the articulated blocks); false if a joint's `D` is singular.
pub(crate) fn factor(model: &Model, rw: &mut RedWork) -> bool {
    for &b in model.order.iter().rev() {
        let (m, mb) = (rw.q[b], rw.p[b]);
        rw.fq[b] = m;
        rw.fp[b] = mb;
        let k = rw.kd[b];
        let f = m.f();
        // K S (columns) and D = S̄ᵀ K S
        let mut ks = [[0.0; 6]; 6];
        let mut d = [[0.0; 6]; 6];
        let xc = rw.xc[b];
        for c in 0..f {
            let sc = m.s_col(c);
            ks[c] = mat_vec(&k, &sc);
            let mut col = [0.0; 6];
            mb.st_mul(&ks[c], &mut col);
            for r in 0..f {
                d[r][c] = col[r] + (0..6).map(|i| xc[r][i] * sc[i]).sum::<f64>();
            }
        }
        if !invert(&mut d, f) {
            return false;
        }
        rw.dinv[b] = d;
        let Some(p) = model.parent[b] else { continue };
        let coupled = rw.coupled[b];
        let mut ka = right_a(&k, &m);
        if coupled {
            for i in 0..6 {
                for j in 0..6 {
                    ka[i][j] += rw.kcp[b][i][j];
                }
            }
        }
        // G = S̄ᵀ (K A + K_cp) (f × 6), Y = D⁻¹ G
        let mut g = [[0.0; 6]; 6];
        for c in 0..6 {
            let col: V6 = std::array::from_fn(|i| ka[i][c]);
            let mut t = [0.0; 6];
            mb.st_mul(&col, &mut t);
            for r in 0..f {
                g[r][c] = t[r];
            }
        }
        // + X_c A + X_p (geometric stiffness of the joint equations)
        let xca = right_a(&xc, &m);
        for r in 0..f {
            for c in 0..6 {
                g[r][c] += xca[r][c] + rw.xp[b][r][c];
            }
        }
        let mut y = [[0.0; 6]; 6];
        for r in 0..f {
            for l in 0..f {
                let s = d[r][l];
                for c in 0..6 {
                    y[r][c] += s * g[l][c];
                }
            }
        }
        rw.y[b] = y;
        // H = Āᵀ K + K_pc
        let mut hm = left_at(&mb, &k);
        if coupled {
            for i in 0..6 {
                for j in 0..6 {
                    hm[i][j] += rw.kpc[b][i][j];
                }
            }
        }
        rw.hm[b] = hm;
        // K_p += H A − (H S) Y + Āᵀ K_cp
        let mut upd = right_a(&hm, &m);
        for c in 0..f {
            let hs = mat_vec(&hm, &m.s_col(c));
            for i in 0..6 {
                for j in 0..6 {
                    upd[i][j] -= hs[i] * y[c][j];
                }
            }
        }
        if coupled {
            let t = left_at(&mb, &rw.kcp[b]);
            for i in 0..6 {
                for j in 0..6 {
                    upd[i][j] += t[i][j];
                }
            }
        }
        for i in 0..6 {
            for j in 0..6 {
                rw.kd[p][i][j] += upd[i][j];
            }
        }
    }
    true
}

/// Solves with the factors of the last [`factor`] for the reduced residual `rw.res`: writes
/// `δu = −J⁻¹ R` to `rw.res` (zero beyond each joint's rates) and the body twists to `rw.dx`.
pub(crate) fn solve(model: &Model, rw: &mut RedWork) {
    for x in &mut rw.bias {
        *x = [0.0; 6];
    }
    for &b in model.order.iter().rev() {
        let (m, mb) = (&rw.fq[b], &rw.fp[b]);
        let f = m.f();
        let mut e = [0.0; 6];
        mb.st_mul(&rw.bias[b], &mut e);
        for k in 0..f {
            e[k] += rw.res[b][k];
        }
        let mut yv = [0.0; 6];
        for r in 0..f {
            for l in 0..f {
                yv[r] += rw.dinv[b][r][l] * e[l];
            }
        }
        rw.yv[b] = yv;
        if let Some(p) = model.parent[b] {
            let t = m.s_mul(&yv);
            let ht = mat_vec(&rw.hm[b], &t);
            let ab = mb.at_mul(&rw.bias[b]);
            for k in 0..6 {
                rw.bias[p][k] += ab[k] - ht[k];
            }
        }
    }
    for &b in &model.order {
        let m = rw.fq[b];
        let f = m.f();
        let mut du = [0.0; 6];
        for k in 0..f {
            du[k] = -rw.yv[b][k];
        }
        let mut x = [0.0; 6];
        if let Some(p) = model.parent[b] {
            let xp = rw.dx[p];
            for k in 0..f {
                du[k] -= (0..6).map(|c| rw.y[b][k][c] * xp[c]).sum::<f64>();
            }
            x = m.a_mul(&xp);
        }
        let s = m.s_mul(&du);
        for k in 0..6 {
            x[k] += s[k];
        }
        rw.dx[b] = x;
        rw.res[b] = du;
    }
}
