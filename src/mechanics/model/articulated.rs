//! Solves with a tree's joint-space mass matrix by the articulated-body recursion
//! (Featherstone), O(n) per right-hand side instead of the O(n²) of dense triangular factors;
//! for the many columns of a linear model (`linear`, `tree_partials`).
//!
//! Each rate `k` is a one-dof joint with the motion `S_k` (world axes, about its own point
//! `p_k`: `spatial`) on the path of rates `prev(k), prev(prev(k)), …` to the ground (a joint
//! with several rates: massless links between them), `d_k = p_k − p_prev(k)`; `Y_k` the inertia
//! of the bodies the rate carries directly (about `p_k`), `a_k` its rotor inertia (armature, on
//! the diagonal of `M`). Local points keep the products of the size of the links, not of their
//! distance from the origin. Leaves to the ground (`↑`: shifted by `−d_c` to the parent's point):
//!
//! ```text
//! factor   I_k = Y_k + Σ_{children c} ↑(I_c − U_c U_cᵀ / D_c),   U_k = I_k S_k,
//!          D_k = S_kᵀ U_k + a_k > 0          (the pivots of M = Jᵀ Y J + diag(a), M SPD)
//! solve    M x = b:  p_k = Σ_{children c} ↑(p_c + U_c u_c / D_c),   u_k = b_k − S_k·p_k
//!          (leaves first), then  x_k = (u_k − U_k·α_k−) / D_k,  α_k = α_k− + S_k x_k,
//!          α_k− = α_prev(k) shifted by d_k   (ground first, α = 0 there)
//! ```
//!
//! Cost: O(n) to factor (6 × 6 blocks per rate), O(n) per solve.

use super::spatial::{shift_f, shift_map, M6, V6};
use crate::math::Vec3;
use nalgebra::DMatrixViewMut;

/// Columns solved together.
const LANES: usize = 4;

/// The factors of a tree's mass matrix (module formulas), by position in the order ground to
/// leaves.
#[derive(Clone, Debug)]
pub(crate) struct Articulated {
    /// The rate at each position.
    order: Vec<usize>,
    /// The position of the rate before (`n`: the ground).
    up: Vec<usize>,
    /// `d_k`, m.
    d: Vec<Vec3>,
    s: Vec<V6>,
    /// `U_k / D_k`, and the same moved to the point before (`↑`).
    u: Vec<V6>,
    u_up: Vec<V6>,
    /// `1 / D_k`.
    inv: Vec<f64>,
}

impl Articulated {
    /// Factors the mass matrix of rates with motions `s` (world axes, each about its point),
    /// tree links `prev` (the rate before each one on its path to the ground) with the offsets
    /// `d` of their points (m), `order` (ground to leaves), the inertias `own` the rates carry
    /// directly (world axes, about their points) and the rotor inertias `armature` (kg·m² or
    /// kg). `None` when a pivot is not positive and finite (the mass matrix is singular or not
    /// positive definite).
    #[must_use]
    pub(crate) fn new(
        s: &[V6],
        prev: &[Option<usize>],
        d: &[Vec3],
        order: Vec<usize>,
        mut own: Vec<M6>,
        armature: &[f64],
    ) -> Option<Self> {
        let n = s.len();
        let mut at = vec![n; n];
        for (t, &k) in order.iter().enumerate() {
            at[k] = t;
        }
        let mut out = Self {
            up: order
                .iter()
                .map(|&k| prev[k].map_or(n, |p| at[p]))
                .collect(),
            d: order.iter().map(|&k| d[k]).collect(),
            s: order.iter().map(|&k| s[k]).collect(),
            u: vec![V6::zeros(); n],
            u_up: vec![V6::zeros(); n],
            inv: vec![0.0; n],
            order,
        };
        for t in (0..n).rev() {
            let k = out.order[t];
            let uk = own[k] * out.s[t];
            let dk = out.s[t].dot(&uk) + armature[k];
            if !(dk.is_finite() && dk > 0.0) {
                return None;
            }
            if let Some(p) = prev[k] {
                let child = shift_map(&(own[k] - uk * uk.transpose() / dk), &-out.d[t]);
                own[p] += child;
            }
            out.u[t] = uk / dk;
            out.u_up[t] = shift_f(&out.u[t], &-out.d[t]);
            out.inv[t] = 1.0 / dk;
        }
        Some(out)
    }

    /// Overwrites every column `b` of `x` with `M⁻¹ b` (module formulas), `LANES` columns at
    /// a time (the same operations on each: the compiler's vector lanes).
    pub(crate) fn solve_columns(&self, x: &mut DMatrixViewMut<'_, f64>) {
        let (n, cols) = (self.s.len(), x.ncols());
        let zero = [[0.0; LANES]; 6];
        let (mut p, mut acc) = (vec![zero; n + 1], vec![zero; n + 1]);
        let mut v = vec![[0.0; LANES]; n];
        for first in (0..cols).step_by(LANES) {
            let width = LANES.min(cols - first);
            for (t, &k) in self.order.iter().enumerate() {
                for c in 0..width {
                    v[t][c] = x[(k, first + c)];
                }
            }
            p[n] = zero;
            for t in (0..n).rev() {
                let (pt, s, d, uu) = (p[t], &self.s[t], &self.d[t], &self.u_up[t]);
                p[t] = zero;
                let mut vt = v[t];
                for c in 0..LANES {
                    vt[c] -= s[0] * pt[0][c]
                        + s[1] * pt[1][c]
                        + s[2] * pt[2][c]
                        + s[3] * pt[3][c]
                        + s[4] * pt[4][c]
                        + s[5] * pt[5][c];
                }
                v[t] = vt;
                // ↑(p + U v / D): the moment about the point before, n + d × f
                let q = &mut p[self.up[t]];
                for c in 0..LANES {
                    let f = [pt[3][c], pt[4][c], pt[5][c]];
                    q[0][c] += pt[0][c] + d[1] * f[2] - d[2] * f[1] + uu[0] * vt[c];
                    q[1][c] += pt[1][c] + d[2] * f[0] - d[0] * f[2] + uu[1] * vt[c];
                    q[2][c] += pt[2][c] + d[0] * f[1] - d[1] * f[0] + uu[2] * vt[c];
                    q[3][c] += f[0] + uu[3] * vt[c];
                    q[4][c] += f[1] + uu[4] * vt[c];
                    q[5][c] += f[2] + uu[5] * vt[c];
                }
            }
            for t in 0..n {
                let (b, s, d, u) = (acc[self.up[t]], &self.s[t], &self.d[t], &self.u[t]);
                let mut a = b;
                // the parent's acceleration at this point: v + ω × d
                for c in 0..LANES {
                    let w = [b[0][c], b[1][c], b[2][c]];
                    a[3][c] += w[1] * d[2] - w[2] * d[1];
                    a[4][c] += w[2] * d[0] - w[0] * d[2];
                    a[5][c] += w[0] * d[1] - w[1] * d[0];
                }
                let mut xt = [0.0; LANES];
                for c in 0..LANES {
                    xt[c] = v[t][c] * self.inv[t]
                        - (u[0] * a[0][c]
                            + u[1] * a[1][c]
                            + u[2] * a[2][c]
                            + u[3] * a[3][c]
                            + u[4] * a[4][c]
                            + u[5] * a[5][c]);
                }
                for i in 0..6 {
                    for c in 0..LANES {
                        a[i][c] += s[i] * xt[c];
                    }
                }
                acc[t] = a;
                for c in 0..width {
                    x[(self.order[t], first + c)] = xt[c];
                }
            }
        }
    }
}
