//! Elimination of the reduced Newton matrix `P̄ᵀ K Q` over the tree, leaves to root, in the
//! manner of the articulated-body recursion (unsymmetric: `P̄` at the midpoint, `Q` at the
//! iterate). With `x_c = A x_p + S u_c + c_c` (maps `Q`, `c_c` the joint's defect,
//! `place::defects`) and the child's equations `S̄ᵀ W_c + X_c x_c + X_p x_p + R_c = 0`
//! (`X` the geometric stiffness of the joint equations), `W_c = K_c x_c + K_cp x_p + b_c`
//! (`K_c` articulated, `b_c` the bias of its eliminated subtree):
//!
//! ```text
//! D = S̄ᵀ K_c S + X_c S,  Y = D⁻¹ (S̄ᵀ (K_c A + K_cp) + X_c A + X_p),  H = Āᵀ K_c + K_pc
//! e_c = S̄ᵀ (b_c + K_c c_c) + X_c c_c + R_c,  u_c = −Y x_p − D⁻¹ e_c
//! K_p += H A − (H S) Y + Āᵀ K_cp,   b_p += −H (S D⁻¹ e_c − c_c) + Āᵀ b_c
//! ```
//!
//! All blocks are 6 × 6 at most (`f ≤ 6` rates per joint), so one factorisation is O(N). The
//! factors are kept for chord iterations (`solve` with a new reduced residual).
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use super::maps::{Map, V6};
use super::work::RedWork;
use crate::math::Vec3;
use crate::mechanics::linalg::small_mat::{self, amax, mul_vec};
use crate::mechanics::model::runtime::Model;

type M6 = [[f64; 6]; 6];

/// The twist component of each rate of a free root body (`maps::Map::free`: `S = I₆` with the
/// rotation rates first, so rate `k` is twist component `FREE[k]`).
const FREE: [usize; 6] = [3, 4, 5, 0, 1, 2];

/// Smallest pivot of a joint's `D`, relative to its largest entry.
const PIVOT: f64 = 1e-14;

#[inline]
fn dot6(a: &V6, b: &V6) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] + a[4] * b[4] + a[5] * b[5]
}

/// Row `x` times the map's `A = [I −ê; 0 Z]`: `[x_f, e × x_f + Z x_m]`.
fn right_a_row(x: &V6, m: &Map) -> V6 {
    let xf = Vec3::new(x[0], x[1], x[2]);
    let mut r = m.e.cross(&xf);
    if m.z {
        r += Vec3::new(x[3], x[4], x[5]);
    }
    [x[0], x[1], x[2], r.x, r.y, r.z]
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

/// In-place inverse of the leading `n × n` block by the supernode kernel
/// (`small_mat::invert`); false if a pivot is not above [`PIVOT`] times the largest entry.
fn invert(a: &mut M6, n: usize) -> bool {
    fn lead<const N: usize>(a: &mut M6) -> bool {
        let mut m: [[f64; N]; N] = std::array::from_fn(|i| std::array::from_fn(|j| a[i][j]));
        let big = amax(&m);
        if !(big.is_finite() && big > 0.0 && small_mat::invert(&mut m, PIVOT * big)) {
            return false;
        }
        for i in 0..N {
            a[i][..N].copy_from_slice(&m[i]);
        }
        true
    }
    match n {
        0 => true,
        1 => lead::<1>(a),
        2 => lead::<2>(a),
        3 => lead::<3>(a),
        4 => lead::<4>(a),
        5 => lead::<5>(a),
        _ => lead::<6>(a),
    }
}

/// In-place inverse of a free root's `D` like [`invert`]; where its rotation and translation
/// rates do not couple (a free body alone: inertia, gravity and its own loads keep them apart;
/// a floating tree's root couples them through its subtree) as two 3 × 3 blocks, with the
/// pivot bound of the whole.
fn invert_free(a: &mut M6) -> bool {
    let apart = (0..3).all(|i| (3..6).all(|j| a[i][j] == 0.0 && a[j][i] == 0.0));
    if !apart {
        return invert(a, 6);
    }
    let big = amax(a);
    if !(big.is_finite() && big > 0.0) {
        return false;
    }
    let mut r: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| a[i][j]));
    let mut t: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| a[3 + i][3 + j]));
    if !(small_mat::invert(&mut r, PIVOT * big) && small_mat::invert(&mut t, PIVOT * big)) {
        return false;
    }
    for i in 0..3 {
        a[i][..3].copy_from_slice(&r[i]);
        a[3 + i][3..].copy_from_slice(&t[i]);
    }
    true
}

/// Factors the Newton matrix assembled by the last Jacobian pass (`rw.kd` is overwritten by
/// the articulated blocks); false if a joint's `D` is singular.
pub(crate) fn factor(model: &Model, rw: &mut RedWork) -> bool {
    // the factored matrix's maps are kept for the chord solves (the next pass overwrites `p`,
    // and `q` in its next Jacobian pass)
    std::mem::swap(&mut rw.fq, &mut rw.q);
    std::mem::swap(&mut rw.fp, &mut rw.p);
    for &b in model.order.iter().rev() {
        let (m, mb) = (&rw.fq[b], &rw.fp[b]);
        let k = &rw.kd[b];
        let f = m.f();
        // D = S̄ᵀ K S + X_c S
        let d = &mut rw.dinv[b];
        let xc = &rw.xc[b];
        if model.tree_joint[b].is_none() {
            // a free root: S = S̄ permutes the twist (rotation rates first), D = K permuted
            for r in 0..6 {
                for c in 0..6 {
                    d[r][c] = k[FREE[r]][FREE[c]] + xc[r][FREE[c]];
                }
            }
            if !invert_free(d) {
                return false;
            }
            continue;
        }
        // the columns of S and S̄
        let mut sq = [[0.0; 6]; 6];
        let mut sp = [[0.0; 6]; 6];
        for c in 0..f {
            sq[c] = m.s_col(c);
            sp[c] = mb.s_col(c);
        }
        for c in 0..f {
            let ks = mul_vec(k, &sq[c]);
            for r in 0..f {
                d[r][c] = dot6(&sp[r], &ks) + dot6(&xc[r], &sq[c]);
            }
        }
        if !invert(d, f) {
            return false;
        }
        let Some(p) = model.parent[b] else { continue };
        let coupled = rw.coupled[b];
        // G = S̄ᵀ (K A + K_cp) + X_c A + X_p (f × 6; the geometric stiffness of the joint
        // equations), row r = (s̄_rᵀ K + X_c,r) A + s̄_rᵀ K_cp + X_p,r, Y = D⁻¹ G
        let mut g = [[0.0; 6]; 6];
        for r in 0..f {
            let mut w = xc[r];
            for i in 0..6 {
                let s = sp[r][i];
                for c in 0..6 {
                    w[c] += s * k[i][c];
                }
            }
            g[r] = right_a_row(&w, m);
            if coupled {
                for i in 0..6 {
                    let s = sp[r][i];
                    for c in 0..6 {
                        g[r][c] += s * rw.kcp[b][i][c];
                    }
                }
            }
            for c in 0..6 {
                g[r][c] += rw.xp[b][r][c];
            }
        }
        let y = &mut rw.y[b];
        for r in 0..f {
            y[r] = [0.0; 6];
            for l in 0..f {
                let s = d[r][l];
                for c in 0..6 {
                    y[r][c] += s * g[l][c];
                }
            }
        }
        // H = Āᵀ K + K_pc (the joint loads' and the geometric stiffness's)
        let hm = &mut rw.hm[b];
        *hm = left_at(mb, k);
        if coupled {
            for i in 0..6 {
                for j in 0..6 {
                    hm[i][j] += rw.kpc[b][i][j];
                }
            }
        }
        for i in 0..3 {
            for j in 0..3 {
                hm[3 + i][3 + j] += rw.gpc[b][i][j];
            }
        }
        // K_p += H A − (H S) Y + Āᵀ K_cp, row by row
        let mut hs = [[0.0; 6]; 6];
        for c in 0..f {
            hs[c] = mul_vec(hm, &sq[c]);
        }
        let kt = if coupled {
            Some(left_at(mb, &rw.kcp[b]))
        } else {
            None
        };
        let kp = &mut rw.kd[p];
        for i in 0..6 {
            let mut row = right_a_row(&hm[i], m);
            for c in 0..f {
                let s = hs[c][i];
                for j in 0..6 {
                    row[j] -= s * y[c][j];
                }
            }
            if let Some(t) = &kt {
                for j in 0..6 {
                    row[j] += t[i][j];
                }
            }
            for j in 0..6 {
                kp[i][j] += row[j];
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
        if model.tree_joint[b].is_none() {
            // a free root: no defect (`place::defects`), `S̄ᵀ` permutes the bias
            let e: V6 = std::array::from_fn(|k| rw.bias[b][FREE[k]] + rw.res[b][k]);
            rw.yv[b] = std::array::from_fn(|r| (0..6).map(|l| rw.dinv[b][r][l] * e[l]).sum());
            continue;
        }
        let (m, mb) = (&rw.fq[b], &rw.fp[b]);
        let f = m.f();
        // the joint's defect c moves the child: bias K c and the joint equations' X_c c
        let c = rw.c[b];
        let kc = mul_vec(&rw.kd[b], &c);
        let biased: V6 = std::array::from_fn(|i| rw.bias[b][i] + kc[i]);
        let mut e = [0.0; 6];
        mb.st_mul(&biased, &mut e);
        for k in 0..f {
            e[k] += rw.res[b][k] + (0..6).map(|i| rw.xc[b][k][i] * c[i]).sum::<f64>();
        }
        let mut yv = [0.0; 6];
        for r in 0..f {
            for l in 0..f {
                yv[r] += rw.dinv[b][r][l] * e[l];
            }
        }
        rw.yv[b] = yv;
        if let Some(p) = model.parent[b] {
            let mut t = m.s_mul(&yv);
            for k in 0..6 {
                t[k] -= c[k];
            }
            let ht = mul_vec(&rw.hm[b], &t);
            let ab = mb.at_mul(&rw.bias[b]);
            for k in 0..6 {
                rw.bias[p][k] += ab[k] - ht[k];
            }
        }
    }
    for &b in &model.order {
        if model.tree_joint[b].is_none() {
            let du: V6 = std::array::from_fn(|k| -rw.yv[b][k]);
            for k in 0..6 {
                rw.dx[b][FREE[k]] = du[k];
            }
            rw.res[b] = du;
            continue;
        }
        let m = &rw.fq[b];
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
            x[k] += s[k] + rw.c[b][k];
        }
        rw.dx[b] = x;
        rw.res[b] = du;
    }
}
