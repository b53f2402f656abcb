//! Exact linear models of the continuous-time dynamics in minimal coordinates
//! (`tree_dynamics`): by the residual's analytic partial derivatives where they cover the model
//! (`tree_partials`), else by forward-mode dual numbers, one pass per state or input direction.
//!
//! ```text
//! ẋ = f(x, u),  x = (q, ν):   q̇ = N(q) ν,   M(q) ν̇ = −res(q, ν, 0, u)
//! ∂ν̇/∂y = −M⁻¹ ∂res(q, ν, ν̇₀, u)/∂y   (y = q, ν or u; ν̇₀ held: res is affine in ν̇)
//! A = [∂q̇/∂q  ∂q̇/∂ν; ∂ν̇/∂q  ∂ν̇/∂ν],   B = [0; ∂ν̇/∂u]
//! C, D: the outputs y(q, ν, ν̇(x, u)) differentiated along the same directions, ν̇ carried as
//!       the dual number ν̇₀ + ε ∂ν̇/∂(x, u)
//! ```
//!
//! Touching contacts and joint friction add their sticking bristles `σ` to the state
//! (`sticking`): `x = (q, ν, σ)`, `σ̇` their rates, the residual affine in `σ`.
//!
//! Cost, analytic (trees of revolute, prismatic, cylindrical, universal, planar and fixed
//! joints, no bristles): one O(n·depth) sweep for `∂res/∂(q, ν, u)` and one O(n)
//! articulated-body solve per column, O(n·(n·depth + m)) (chains: O(n²)); duals: `2n + m`
//! passes of O(bodies) each, one LU of the `n × n` mass matrix and one solve per direction:
//! O(n·N + n³). Outputs add one dual pass per column either way.

use super::sticking::lift_sigma;
use super::tree_dynamics::tree_partials::Partials;
use super::tree_dynamics::{c, TreeDynamics};
use crate::math::Mat3;
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};
use num_dual::Dual64;

/// An output quantity that can be differentiated (0-based indices, as the variable table's).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    /// Body frame origin component `i`, m.
    BodyR(usize, usize),
    /// Body rotation element `[i, j]`.
    BodyRot(usize, usize, usize),
    /// Body frame origin velocity component `i`, m/s.
    BodyV(usize, usize),
    /// Body angular velocity component `i`, rad/s.
    BodyW(usize, usize),
    /// Site origin component `i`.
    SiteR(usize, usize),
    /// Site rotation element `[i, j]`.
    SiteRot(usize, usize, usize),
    /// Site origin velocity component `i`.
    SiteV(usize, usize),
    /// Site angular velocity component `i`.
    SiteW(usize, usize),
    /// Joint coordinate `k` (spherical: quaternion component `[w, x, y, z]`).
    JointQ(usize, usize),
    /// Joint rate `k` (spherical: relative angular velocity, child frame).
    JointQd(usize, usize),
    /// Joint acceleration `k` (the derivative of `JointQd`).
    JointQdd(usize, usize),
    /// Mechanical energy, J.
    Energy,
    /// Linear momentum component `i`.
    P(usize),
    /// Angular momentum component `i` about the world origin.
    L(usize),
    /// Component `i` of the ground's force on collision shape `shape`'s body through it
    /// (its touching points' normal and friction forces, `sticking`), N, world frame.
    ContactForce(usize, usize),
}

/// A linear model at an operating point (module formulas). Matrices are dense, row-major
/// in the sense of `nalgebra` indexing `(row, column)`.
#[derive(Clone, Debug)]
pub struct Linear {
    /// `∂ẋ/∂x`, 2n × 2n.
    pub a: DMatrix<f64>,
    /// `∂ẋ/∂u`, 2n × m.
    pub b: DMatrix<f64>,
    /// `∂y/∂x`, p × 2n.
    pub c: DMatrix<f64>,
    /// `∂y/∂u`, p × m.
    pub d: DMatrix<f64>,
    /// `ẋ` at the operating point.
    pub xdot0: Vec<f64>,
    /// `y` at the operating point.
    pub y0: Vec<f64>,
}

/// `x` as dual numbers, the derivative part 1 at `seed`.
pub(crate) fn lift(x: &[f64], seed: Option<usize>) -> Vec<Dual64> {
    x.iter()
        .enumerate()
        .map(|(i, &v)| {
            let d = Dual64::from(v);
            if Some(i) == seed {
                d.derivative()
            } else {
                d
            }
        })
        .collect()
}

/// The quaternion `[w, x, y, z]` of `M₀ exp(θ̂)` to first order in `θ` (`q₀ ⊗ (1, θ/2)`).
fn quat_of<T: super::tree_dynamics::Real>(m0: &Mat3, th: &Vector3<T>) -> [T; 4] {
    let q0 = crate::math::matrix_to_quat(m0);
    let (w, v) = (
        c::<T>(q0[0]),
        Vector3::new(c::<T>(q0[1]), c::<T>(q0[2]), c::<T>(q0[3])),
    );
    let (b0, bv) = (T::one(), th * c::<T>(0.5));
    let vw = w * b0 - v.dot(&bv);
    let vv = bv * w + v * b0 + v.cross(&bv);
    [vw, vv[0], vv[1], vv[2]]
}

impl TreeDynamics {
    /// The value of output `y` at `(q, ν, ν̇)`, the bristles at the operating point's values.
    pub fn quantity<T: super::tree_dynamics::Real>(
        &self,
        q: &[T],
        nu: &[T],
        nud: &[T],
        y: Quantity,
    ) -> T {
        self.quantity_with(q, nu, nud, &lift_sigma(self.sticking()), y)
    }

    /// The value of output `y` at `(q, ν, ν̇)` with the bristles at `sigma` (`sticking`).
    pub fn quantity_with<T: super::tree_dynamics::Real>(
        &self,
        q: &[T],
        nu: &[T],
        nud: &[T],
        sigma: &[T],
        y: Quantity,
    ) -> T {
        let m = self.motion(q, nu, None);
        let rot = |r: &Matrix3<T>, i: usize, j: usize| r[(i, j)];
        match y {
            Quantity::BodyR(b, i) => m.o[b][i],
            Quantity::BodyRot(b, i, j) => rot(&m.r[b], i, j),
            Quantity::BodyV(b, i) => m.v[b][i],
            Quantity::BodyW(b, i) => m.w[b][i],
            Quantity::SiteR(s, i) => self.site(&m, s).0[i],
            Quantity::SiteRot(s, i, j) => rot(&self.site(&m, s).1, i, j),
            Quantity::SiteV(s, i) => self.site(&m, s).2[i],
            Quantity::SiteW(s, i) => self.site(&m, s).3[i],
            Quantity::JointQ(j, k) => {
                let at = self.joint_at(j).unwrap_or(0);
                if self.is_spherical(j) {
                    let th = Vector3::new(q[at], q[at + 1], q[at + 2]);
                    quat_of(&self.joint_rot0(j), &th)[k]
                } else {
                    q[at + k]
                }
            }
            Quantity::JointQd(j, k) => nu[self.joint_at(j).unwrap_or(0) + k],
            Quantity::JointQdd(j, k) => nud[self.joint_at(j).unwrap_or(0) + k],
            Quantity::Energy => self.energy(q, nu),
            Quantity::P(i) => self.momentum(q, nu).0[i],
            Quantity::L(i) => self.momentum(q, nu).1[i],
            Quantity::ContactForce(shape, i) => {
                self.sticking()
                    .shape_force(self.body_coms(), &m, sigma, shape)[i]
            }
        }
    }

    /// The directional derivative of the outputs `ys` along `(δq, δν, δu)` at `(q, ν, u)`:
    /// `C δx + D δu` (one forward pass; module formulas).
    ///
    /// # Errors
    /// A message when the joint-space mass matrix is singular.
    #[allow(clippy::too_many_arguments)]
    pub fn directional(
        &self,
        q: &[f64],
        nu: &[f64],
        u: &[f64],
        dq: &[f64],
        dnu: &[f64],
        du: &[f64],
        ys: &[Quantity],
    ) -> Result<Vec<f64>, String> {
        let n = self.n();
        let (nud0, lu) = self.accelerations(q, nu, u)?;
        let dual = |x: &[f64], d: &[f64]| -> Vec<Dual64> {
            x.iter().zip(d).map(|(&a, &b)| Dual64::new(a, b)).collect()
        };
        let (qd, vd, ud) = (dual(q, dq), dual(nu, dnu), dual(u, du));
        let nud_c: Vec<Dual64> = nud0.iter().map(|&x| Dual64::from(x)).collect();
        let res = self.residual(&qd, &vd, &nud_c, &ud, false);
        let r = DVector::from_iterator(n, res.iter().map(|x| -x.eps));
        let dnud = lu
            .solve(&r)
            .ok_or_else(|| "the joint-space mass matrix is singular".to_string())?;
        let nud: Vec<Dual64> = (0..n).map(|i| Dual64::new(nud0[i], dnud[i])).collect();
        Ok(ys
            .iter()
            .map(|y| self.quantity(&qd, &vd, &nud, *y).eps)
            .collect())
    }

    /// The exact linear model at `(q, ν, u)` with outputs `ys` (module formulas); the state
    /// `x = (q, ν, σ)` with the sticking bristles `σ` (`sticking`) last. By the analytic
    /// partial derivatives (`tree_partials`) where they cover the model, else
    /// [`TreeDynamics::linearize_by_duals`].
    ///
    /// # Errors
    /// A message when the joint-space mass matrix is singular.
    pub fn linearize(
        &self,
        q: &[f64],
        nu: &[f64],
        u: &[f64],
        ys: &[Quantity],
    ) -> Result<Linear, String> {
        match self.partials(q, nu, u) {
            Some(p) => Ok(self.linearize_by_partials(p, q, nu, ys)),
            None => self.linearize_by_duals(q, nu, u, ys),
        }
    }

    /// Whether [`TreeDynamics::linearize`] takes the analytic partial derivatives
    /// (`tree_partials`: trees without spherical joints, free bodies, touching contacts or
    /// joint friction) rather than the dual-number passes.
    #[must_use]
    pub fn has_analytic_linearization(&self) -> bool {
        self.has_partials()
    }

    /// The linear model from the residual's partial derivatives `p` (module formulas: one
    /// articulated-body solve per column; the outputs `ys` by one dual pass per column).
    fn linearize_by_partials(&self, p: Partials, q: &[f64], nu: &[f64], ys: &[Quantity]) -> Linear {
        let (n, m, pn) = (self.n(), self.n_inputs(), ys.len());
        let mut x = p.jac;
        x.neg_mut();
        p.mass.solve_columns(&mut x.as_view_mut());
        let mut a = DMatrix::zeros(2 * n, 2 * n);
        a.view_mut((0, n), (n, n)).fill_with_identity();
        a.view_mut((n, 0), (n, 2 * n))
            .copy_from(&x.columns(0, 2 * n));
        let mut b = DMatrix::zeros(2 * n, m);
        b.view_mut((n, 0), (n, m)).copy_from(&x.columns(2 * n, m));
        let mut cm = DMatrix::zeros(pn, 2 * n);
        let mut d = DMatrix::zeros(pn, m);
        if pn > 0 {
            for col in 0..2 * n + m {
                let qd = lift(q, (col < n).then_some(col));
                let vd = lift(nu, (n..2 * n).contains(&col).then(|| col - n));
                let nud: Vec<Dual64> = (0..n)
                    .map(|i| Dual64::new(p.nud0[i], x[(i, col)]))
                    .collect();
                for (k, y) in ys.iter().enumerate() {
                    let v = self.quantity_with(&qd, &vd, &nud, &[], *y).eps;
                    if col < 2 * n {
                        cm[(k, col)] = v;
                    } else {
                        d[(k, col - 2 * n)] = v;
                    }
                }
            }
        }
        let mut xdot0 = nu.to_vec();
        xdot0.extend_from_slice(&p.nud0);
        let y0 = ys
            .iter()
            .map(|y| self.quantity(q, nu, &p.nud0, *y))
            .collect();
        Linear {
            a,
            b,
            c: cm,
            d,
            xdot0,
            y0,
        }
    }

    /// [`TreeDynamics::linearize`] by one forward dual-number pass per state and input
    /// direction (module formulas): every model, and the reference of the analytic path.
    ///
    /// # Errors
    /// A message when the joint-space mass matrix is singular.
    pub fn linearize_by_duals(
        &self,
        q: &[f64],
        nu: &[f64],
        u: &[f64],
        ys: &[Quantity],
    ) -> Result<Linear, String> {
        let (n, m, p) = (self.n(), self.n_inputs(), ys.len());
        let sigma = self.sticking().sigma0().to_vec();
        let nx = 2 * n + sigma.len();
        let (nud0, lu) = self.accelerations(q, nu, u)?;
        let nud_d: Vec<Dual64> = nud0.iter().map(|&x| Dual64::from(x)).collect();
        let mut a = DMatrix::zeros(nx, nx);
        let mut b = DMatrix::zeros(nx, m);
        let mut cm = DMatrix::zeros(p, nx);
        let mut d = DMatrix::zeros(p, m);
        for col in 0..nx + m {
            let qd = lift(q, (col < n).then_some(col));
            let vd = lift(nu, (n..2 * n).contains(&col).then(|| col - n));
            let sd = lift(&sigma, (2 * n..nx).contains(&col).then(|| col - 2 * n));
            let ud = lift(u, (col >= nx).then(|| col - nx));
            let res = self.residual_with(&qd, &vd, &nud_d, &ud, &sd, false);
            let r = DVector::from_iterator(n, res.iter().map(|x| -x.eps));
            let dnud = lu
                .solve(&r)
                .ok_or_else(|| "the joint-space mass matrix is singular".to_string())?;
            let qdot = self.qdot(&qd, &vd);
            let sdot = self.bristle_rates(&qd, &vd);
            let nud_col: Vec<Dual64> = (0..n).map(|i| Dual64::new(nud0[i], dnud[i])).collect();
            let mut put = |row: usize, val: f64| {
                if col < nx {
                    a[(row, col)] = val;
                } else {
                    b[(row, col - nx)] = val;
                }
            };
            for i in 0..n {
                put(i, qdot[i].eps);
                put(n + i, dnud[i]);
            }
            for (i, s) in sdot.iter().enumerate() {
                put(2 * n + i, s.eps);
            }
            for (k, y) in ys.iter().enumerate() {
                let v = self.quantity_with(&qd, &vd, &nud_col, &sd, *y).eps;
                if col < nx {
                    cm[(k, col)] = v;
                } else {
                    d[(k, col - nx)] = v;
                }
            }
        }
        let mut xdot0 = self.qdot(q, nu);
        xdot0.extend_from_slice(&nud0);
        xdot0.extend(self.bristle_rates(q, nu));
        let y0 = ys.iter().map(|y| self.quantity(q, nu, &nud0, *y)).collect();
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
