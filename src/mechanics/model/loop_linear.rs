//! The constrained dynamics of closed loops in the tree's coordinates and its exact linear
//! model in the independent coordinates `x = (q_I, ν_I)` (`loop_closure`), by forward-mode
//! dual numbers; and the tangents that put the step's tangent map into `x`.
//!
//! ```text
//! dynamics   M(q) ν̇ + res(q, ν, 0, u) = Gᵀ μ,   G ν̇ = −Ġ ν           (μ: the loop's forces)
//!            [M  Gᵀ; G  0] [ν̇; −μ] = [−res(q, ν, 0, u); −Φ̈(q, ν, 0)]
//! state      (q, ν) = complete(q_I, ν_I)  (Newton on q_D, ν_D = −G_D⁻¹ G_I ν_I)
//!            ẋ = (q̇_I, ν̇_I),  q̇ = N(q) ν  (`tree_dynamics`)
//! A, B       one dual pass per direction of (q_I, ν_I, u): complete, then the KKT solve, both
//!            in dual numbers (their derivative parts are the IFT's)
//! C, D       the outputs y(q, ν, ν̇) along the same passes (dependent joints' values included)
//! embedding  ∂(q, ν)/∂(q_I, ν_I) = the derivative parts of complete (2n × 2k), composed with
//!            the tree's embedding tangent (`minimal`)
//! read-off   ν = argmin ½ νᵀMν − bᵀν  s.t.  G ν = 0:  [M  Gᵀ; G  0] [ν; μ] = [b; 0]
//!            (b: the generalized momentum of the nodal velocities, `minimal`; the outputs'
//!            projection onto every active row, loops included, `projection.rs`)
//! ```
//!
//! Cost per direction: the Newton iterations and the KKT solve, each `n` motion passes for `G`,
//! O(n·N + (n + r)³).

use super::linear::{lift, Linear, Quantity};
use super::loop_closure::{solve, Closure};
use super::tree_dynamics::{Real, TreeDynamics};
use nalgebra::{DMatrix, DVector};
use num_dual::Dual64;

/// `[a  gᵀ; g  0]`.
fn kkt<T: Real>(a: &DMatrix<T>, g: &DMatrix<T>) -> DMatrix<T> {
    let (n, r) = (a.nrows(), g.nrows());
    let mut k = DMatrix::zeros(n + r, n + r);
    k.view_mut((0, 0), (n, n)).copy_from(a);
    k.view_mut((0, n), (n, r)).copy_from(&g.transpose());
    k.view_mut((n, 0), (r, n)).copy_from(g);
    k
}

impl Closure {
    /// The tree's accelerations `ν̇` (n) at `(q, ν, u)` on the loops (module formulas).
    ///
    /// # Errors
    /// A message when the constrained system is singular.
    pub fn accelerations<T: Real>(
        &self,
        td: &TreeDynamics,
        q: &[T],
        nu: &[T],
        u: &[T],
    ) -> Result<Vec<T>, String> {
        let n = td.n();
        let z = vec![T::zero(); n];
        let res0 = td.residual(q, nu, &z, u, false);
        let bias = self.phi_ddot(td, q, nu, &z);
        let k = kkt(&td.mass_matrix_of(q), &self.jacobian(td, q));
        let rhs = DVector::from_iterator(
            n + bias.len(),
            res0.iter().chain(&bias).map(|x| T::zero() - *x),
        );
        let s = solve(k, rhs).ok_or("the constrained mass matrix of the loop is singular")?;
        Ok(s.rows(0, n).iter().copied().collect())
    }

    /// The rates `ν` on the loops whose generalized momentum is closest to `b` in the kinetic
    /// metric (module formulas: the read-off).
    ///
    /// # Errors
    /// A message when the constrained system is singular.
    pub fn project_rates<T: Real>(
        &self,
        td: &TreeDynamics,
        q: &[T],
        b: &[T],
    ) -> Result<Vec<T>, String> {
        let n = td.n();
        let k = kkt(&td.bodies_mass_matrix_of(q), &self.jacobian(td, q));
        let rhs = DVector::from_iterator(
            n + self.n_rows(),
            b.iter()
                .copied()
                .chain(std::iter::repeat_n(T::zero(), self.n_rows())),
        );
        let s = solve(k, rhs).ok_or("the constrained mass matrix of the loop is singular")?;
        Ok(s.rows(0, n).iter().copied().collect())
    }

    /// `∂(q, ν)/∂(q_I, ν_I)` at the tree point `(q, ν)` on the loops (2n × 2k).
    ///
    /// # Errors
    /// As [`Closure::complete`].
    pub fn embed_map(
        &self,
        td: &TreeDynamics,
        q: &[f64],
        nu: &[f64],
    ) -> Result<DMatrix<f64>, String> {
        let (n, k) = (td.n(), self.indep.len());
        let (qi, vi) = (self.pick(q), self.pick(nu));
        let mut out = DMatrix::zeros(2 * n, 2 * k);
        for col in 0..2 * k {
            let qd = lift(&qi, (col < k).then_some(col));
            let vd = lift(&vi, (col >= k).then(|| col - k));
            let (qt, vt) = self.complete(td, q, &qd, &vd)?;
            for i in 0..n {
                out[(i, col)] = qt[i].eps;
                out[(n + i, col)] = vt[i].eps;
            }
        }
        Ok(out)
    }

    /// Along the direction `(δq_I, δν_I, δu)` at the tree point `(q, ν)` on the loops with
    /// inputs `u`: `(δẋ, δy) = (A δx + B δu, C δx + D δu)` for the outputs `ys` (one dual pass:
    /// complete, then the KKT solve; module formulas).
    ///
    /// # Errors
    /// A singular constrained system, or a loop that does not close.
    #[allow(clippy::too_many_arguments)]
    pub fn directional(
        &self,
        td: &TreeDynamics,
        q: &[f64],
        nu: &[f64],
        u: &[f64],
        (dqi, dvi, du): (&[f64], &[f64], &[f64]),
        ys: &[Quantity],
    ) -> Result<(Vec<f64>, Vec<f64>), String> {
        let dual = |x: &[f64], d: &[f64]| -> Vec<Dual64> {
            x.iter().zip(d).map(|(&a, &b)| Dual64::new(a, b)).collect()
        };
        let (qi, vi) = (self.pick(q), self.pick(nu));
        let (qd, vd, ud) = (dual(&qi, dqi), dual(&vi, dvi), dual(u, du));
        let (qt, vt) = self.complete(td, q, &qd, &vd)?;
        let nud = self.accelerations(td, &qt, &vt, &ud)?;
        let qdot = td.qdot(&qt, &vt);
        let dx: Vec<f64> = self
            .pick(&qdot)
            .iter()
            .chain(&self.pick(&nud))
            .map(|x: &Dual64| x.eps)
            .collect();
        let dy: Vec<f64> = ys
            .iter()
            .map(|y| td.quantity(&qt, &vt, &nud, *y).eps)
            .collect();
        Ok((dx, dy))
    }

    /// The exact linear model in `x = (q_I, ν_I)` at the tree point `(q, ν)` on the loops with
    /// inputs `u` and outputs `ys` (module formulas): [`Closure::directional`] along each unit
    /// direction.
    ///
    /// # Errors
    /// A singular constrained system, or a loop that does not close.
    pub fn linearize(
        &self,
        td: &TreeDynamics,
        q: &[f64],
        nu: &[f64],
        u: &[f64],
        ys: &[Quantity],
    ) -> Result<Linear, String> {
        let (k, m, p) = (self.indep.len(), td.n_inputs(), ys.len());
        let mut a = DMatrix::zeros(2 * k, 2 * k);
        let mut b = DMatrix::zeros(2 * k, m);
        let mut cm = DMatrix::zeros(p, 2 * k);
        let mut d = DMatrix::zeros(p, m);
        let unit = |len: usize, at: Option<usize>| -> Vec<f64> {
            (0..len)
                .map(|i| f64::from(u8::from(Some(i) == at)))
                .collect()
        };
        for col in 0..2 * k + m {
            let dqi = unit(k, (col < k).then_some(col));
            let dvi = unit(k, (k..2 * k).contains(&col).then(|| col - k));
            let du = unit(m, (col >= 2 * k).then(|| col - 2 * k));
            let (column, ycol) = self.directional(td, q, nu, u, (&dqi, &dvi, &du), ys)?;
            if col < 2 * k {
                a.set_column(col, &DVector::from_vec(column));
                cm.set_column(col, &DVector::from_vec(ycol));
            } else {
                b.set_column(col - 2 * k, &DVector::from_vec(column));
                d.set_column(col - 2 * k, &DVector::from_vec(ycol));
            }
        }
        let nud0 = self.accelerations(td, q, nu, u)?;
        let mut xdot0 = self.pick(&td.qdot(q, nu));
        xdot0.extend(self.pick(&nud0));
        let y0 = ys.iter().map(|y| td.quantity(q, nu, &nud0, *y)).collect();
        Ok(Linear {
            a,
            b,
            c: cm,
            d,
            xdot0,
            y0,
        })
    }
}
