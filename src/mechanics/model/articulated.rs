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

use super::spatial::{shift_f, shift_m, shift_map, M6, V6};
use crate::math::Vec3;
use nalgebra::DMatrix;

/// The factors of a tree's mass matrix (module formulas).
#[derive(Clone, Debug)]
pub(crate) struct Articulated {
    /// Rates from the ground to the leaves (every rate after its `prev`).
    order: Vec<usize>,
    prev: Vec<Option<usize>>,
    d: Vec<Vec3>,
    s: Vec<V6>,
    u: Vec<V6>,
    pivot: Vec<f64>,
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
        s: Vec<V6>,
        prev: Vec<Option<usize>>,
        d: Vec<Vec3>,
        order: Vec<usize>,
        mut own: Vec<M6>,
        armature: &[f64],
    ) -> Option<Self> {
        let n = s.len();
        let (mut u, mut pivot) = (vec![V6::zeros(); n], vec![0.0; n]);
        for &k in order.iter().rev() {
            let uk = own[k] * s[k];
            let dk = s[k].dot(&uk) + armature[k];
            if !(dk.is_finite() && dk > 0.0) {
                return None;
            }
            if let Some(p) = prev[k] {
                let child = shift_map(&(own[k] - uk * uk.transpose() / dk), &-d[k]);
                own[p] += child;
            }
            u[k] = uk;
            pivot[k] = dk;
        }
        Some(Self {
            order,
            prev,
            d,
            s,
            u,
            pivot,
        })
    }

    /// Overwrites every column `b` of `x` with `M⁻¹ b` (module formulas).
    pub(crate) fn solve_columns(&self, x: &mut DMatrix<f64>) {
        let n = self.s.len();
        let (mut p, mut acc) = (vec![V6::zeros(); n], vec![V6::zeros(); n]);
        let mut uk = vec![0.0; n];
        for mut col in x.column_iter_mut() {
            p.fill(V6::zeros());
            for &k in self.order.iter().rev() {
                let v = col[k] - self.s[k].dot(&p[k]);
                uk[k] = v;
                if let Some(j) = self.prev[k] {
                    let add = shift_f(&(p[k] + self.u[k] * (v / self.pivot[k])), &-self.d[k]);
                    p[j] += add;
                }
            }
            for &k in &self.order {
                let a = self.prev[k].map_or_else(V6::zeros, |j| shift_m(&acc[j], &self.d[k]));
                let xk = (uk[k] - self.u[k].dot(&a)) / self.pivot[k];
                acc[k] = a + self.s[k] * xk;
                col[k] = xk;
            }
        }
    }
}
