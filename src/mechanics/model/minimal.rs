//! Minimal coordinates of a tree (`tree_dynamics`) and the step's nodal coordinates: the
//! tangents of the embedding and of the read-off, which put the step's tangent map
//! (`step::tangent`) into the linear model's state `x = (q, ν)`.
//!
//! ```text
//! embedding  φ_b = o_b + R_b c_b,  dᵢ = R_b eᵢ,  φ̇_b = v_b + ω_b × R_b c_b,  ḋᵢ = ω_b × dᵢ
//!            per direction (δq, δν) of x, with Z_b, δV_b of `tree_tangent`:
//!            ξ_b = (δφ_b, δθ_b) = (Z^v + Z^ω × φ_b, Z^ω),
//!            δφ̇_b = δV^v + δV^ω × φ_b + ω_b × δφ_b,   δḋᵢ = δV^ω × dᵢ + ω_b × (Z^ω × dᵢ)
//! read-off q:  δq = M(q)⁻¹ Σ_b J_bᵀ (m_b δφ_b, I_b δθ_b)      (exact for ξ tangent to the tree)
//!          ν = M(q)⁻¹ b,  b = Σ_b J_bᵀ h_b,  h_b = (L_b + φ_b × f_b, f_b) about the origin,
//!            f_b = m_b φ̇_b,  L_b = Σᵢ dᵢ × pᵢ,  pᵢ = Σⱼ Eᵢⱼ ḋⱼ   (the outputs' M-orthogonal
//!            projection of the nodal velocities, `projection.rs`, read as joint rates)
//!          δν = M⁻¹ (δb − δ(M ν)),   b − M ν = (S_kᵀ D_k)_k,   D_k = Σ_{b ∈ sub(k)} (h_b − h′_b)
//!            h′_b = (I_b ω_b + φ_b × f′_b, f′_b),  f′_b = m_b (V^v + ω_b × φ_b): the momentum
//!            of the rates ν;  along (δq, ξ, δv):  (δb − δ(M ν))_k = δS_kᵀ D_k + S_kᵀ δD_k,
//!            δf = m δφ̇,  δL = Σᵢ (δθ × dᵢ) × pᵢ + dᵢ × Σⱼ Eᵢⱼ δḋⱼ,  δφ = Z^v + Z^ω × φ,
//!            δ(h − h′) = (δL + δφ × (f − f′) + φ × (δf − δf′) − δ(I ω), δf − δf′),
//!            δf′ = m (δV^v + δV^ω × φ + ω × δφ),  δ(I ω) = Z^ω × Iω − I (Z^ω × ω) + I δV^ω
//!            (O(N) per column; `readoff_tangent_by_duals` takes a dual pass of the rate load
//!            and of the inverse dynamics at rest instead, the tests' reference)
//! loops      embedding: the tree's columns × ∂(q, ν)/∂(q_I, ν_I) (`loop_linear`); read-off:
//!            δq as above (the perturbations are tangent to the tree), ν by the projection onto
//!            the loops' rates [M Gᵀ; G 0][ν; μ] = [b; 0] in one dual pass; then the rows of I
//! ```
//!
//! `J_b` is body `b`'s twist Jacobian at its centre of mass (`TreeDynamics::generalized`),
//! `I_b` its world inertia about the centre of mass, `E = ½ tr(J) I − J` its Euler tensor,
//! `S_k` rate `k`'s twist about the origin. At the read-off the operating orientations of
//! spherical joints and free bodies are the end state's, so the rotation-vector coordinates are
//! perturbations about the end's orientations.

use super::constraint::read3;
use super::loop_closure::Closure;
use super::scalar::cm;
use super::spatial::{join, split, V6};
use super::tree_dynamics::tree_tangent::{Along, Frames};
use super::tree_dynamics::{c, Real, TreeDynamics};
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};
use num_dual::Dual64;

/// Columns of perturbations in nodal form: per column 6 twist increments and 12 nodal
/// velocities per body (column-major), as `step::tangent::Tangent` holds them.
#[derive(Clone, Debug)]
pub struct NodalColumns {
    /// Number of columns.
    pub cols: usize,
    /// `(δφ, δθ)` per body, per column, m and rad (world).
    pub xi: Vec<f64>,
    /// `δ(φ̇, ḋ₁, ḋ₂, ḋ₃)` per body, per column, m/s and 1/s (world).
    pub dv: Vec<f64>,
}

impl NodalColumns {
    /// The columns `self · m` (each new column a combination of the old ones).
    ///
    /// # Panics
    /// When `m` has not `self.cols` rows.
    #[must_use]
    pub fn times(&self, m: &DMatrix<f64>) -> Self {
        assert_eq!(m.nrows(), self.cols, "NodalColumns::times: rows");
        let combine = |v: &[f64]| -> Vec<f64> {
            let len = v.len() / self.cols.max(1);
            let mut out = vec![0.0; len * m.ncols()];
            for new in 0..m.ncols() {
                let dst = &mut out[new * len..(new + 1) * len];
                for old in 0..self.cols {
                    let f = m[(old, new)];
                    if f != 0.0 {
                        for (o, x) in dst.iter_mut().zip(&v[old * len..(old + 1) * len]) {
                            *o += f * x;
                        }
                    }
                }
            }
            out
        };
        Self {
            cols: m.ncols(),
            xi: combine(&self.xi),
            dv: combine(&self.dv),
        }
    }
}

/// Body `b`'s Euler tensor `E = ½ tr(J) I − J` (body axes).
fn euler<T: Real>(j: &Matrix3<T>) -> Matrix3<T> {
    Matrix3::identity() * (j.trace() * c::<T>(0.5)) - j
}

impl TreeDynamics {
    /// The nodal coordinates and velocities (12 and 12 per body, world) at `(q, ν)`.
    pub fn nodal<T: Real>(&self, q: &[T], nu: &[T]) -> (Vec<T>, Vec<T>) {
        let m = self.motion(q, nu, None);
        let nb = self.n_bodies();
        let (mut x, mut v) = (vec![T::zero(); 12 * nb], vec![T::zero(); 12 * nb]);
        for b in 0..nb {
            let (phi, phid) = self.com_of(&m, b);
            for a in 0..3 {
                x[12 * b + a] = phi[a];
                v[12 * b + a] = phid[a];
            }
            for i in 0..3 {
                let d = m.r[b].column(i).into_owned();
                let dd = m.w[b].cross(&d);
                for a in 0..3 {
                    x[12 * b + 3 + 3 * i + a] = d[a];
                    v[12 * b + 3 + 3 * i + a] = dd[a];
                }
            }
        }
        (x, v)
    }

    /// The embedding's tangent at `(q, ν)`: one nodal column per direction of `x = (q, ν)`
    /// (`2n` columns, module formulas).
    #[must_use]
    pub fn embed_tangent(&self, q: &[f64], nu: &[f64]) -> NodalColumns {
        self.embed_tangent_spare(q, nu, 0)
    }

    /// [`TreeDynamics::embed_tangent`] followed by `spare` zero columns (`2n + spare` in all),
    /// which a caller fills (the inputs') without a copy.
    #[must_use]
    pub fn embed_tangent_spare(&self, q: &[f64], nu: &[f64], spare: usize) -> NodalColumns {
        let n = self.n();
        let nb = self.n_bodies();
        let mut out = NodalColumns {
            cols: 2 * n + spare,
            xi: vec![0.0; 6 * nb * (2 * n + spare)],
            dv: vec![0.0; 12 * nb * (2 * n + spare)],
        };
        let fr = self.frames(q, nu);
        let mut al = Along::new(nb, n);
        let (mut dq, mut dnu) = (vec![0.0; n], vec![0.0; n]);
        for col in 0..2 * n {
            let unit = if col < n {
                &mut dq[col]
            } else {
                &mut dnu[col - n]
            };
            *unit = 1.0;
            self.along(&fr, nu, &dq, &dnu, &mut al);
            dq.fill(0.0);
            dnu.fill(0.0);
            let xi = &mut out.xi[col * 6 * nb..(col + 1) * 6 * nb];
            let dv = &mut out.dv[col * 12 * nb..(col + 1) * 12 * nb];
            for b in 0..nb {
                let ((zw, zv), (dw, dvo), (w, _)) =
                    (split(&al.z[b]), split(&al.dv[b]), split(&fr.v[b]));
                let phi = fr.com[b];
                let dphi = zv + zw.cross(&phi);
                let dphid = dvo + dw.cross(&phi) + w.cross(&dphi);
                for a in 0..3 {
                    xi[6 * b + a] = dphi[a];
                    xi[6 * b + 3 + a] = zw[a];
                    dv[12 * b + a] = dphid[a];
                }
                for i in 0..3 {
                    let d = fr.r[b].column(i).into_owned();
                    let dd = dw.cross(&d) + w.cross(&zw.cross(&d));
                    for a in 0..3 {
                        dv[12 * b + 3 + 3 * i + a] = dd[a];
                    }
                }
            }
        }
        out
    }

    /// The read-off's tangent at the end state: minimal coordinates `q` (operating
    /// orientations set to the end's), nodal coordinates `xq` and velocities `xv` (12 per body),
    /// applied to `cols`; returns `δx = (δq, δν)` of the tree's coordinates (2n × cols). With
    /// `loops`, the rates are those on the loops (module formulas).
    ///
    /// # Errors
    /// A message when the joint-space (or the loop's constrained) mass matrix is singular.
    pub fn readoff_tangent(
        &self,
        q: &[f64],
        xq: &[f64],
        xv: &[f64],
        cols: &NodalColumns,
        loops: Option<&Closure>,
    ) -> Result<DMatrix<f64>, String> {
        self.readoff(q, xq, xv, cols, loops, false)
    }

    /// [`TreeDynamics::readoff_tangent`] with the rates' part by dual-number passes of the
    /// rate load and the inverse dynamics on trees too (slower; the reference of the analytic
    /// path's tests).
    ///
    /// # Errors
    /// As [`TreeDynamics::readoff_tangent`].
    pub fn readoff_tangent_by_duals(
        &self,
        q: &[f64],
        xq: &[f64],
        xv: &[f64],
        cols: &NodalColumns,
        loops: Option<&Closure>,
    ) -> Result<DMatrix<f64>, String> {
        self.readoff(q, xq, xv, cols, loops, true)
    }

    fn readoff(
        &self,
        q: &[f64],
        xq: &[f64],
        xv: &[f64],
        cols: &NodalColumns,
        loops: Option<&Closure>,
        duals: bool,
    ) -> Result<DMatrix<f64>, String> {
        let n = self.n();
        let nb = self.n_bodies();
        let singular = || "the joint-space mass matrix is singular".to_string();
        // the bodies' mass matrix: articulated-body solves, O(n) per column, where the tree is
        // a chain of joint rates; dense factors otherwise
        let m0 = self.motion(q, &vec![0.0; n], None);
        let art = self.mass_factors(&m0, false);
        let lu = art.is_none().then(|| self.bodies_mass_matrix_of(q).lu());
        let solve = |mut x: DMatrix<f64>| -> Result<DMatrix<f64>, String> {
            match (&art, &lu) {
                (Some(a), _) => {
                    a.solve_columns(&mut x.as_view_mut());
                    Ok(x)
                }
                (None, Some(lu)) => lu.solve(&x).ok_or_else(singular),
                (None, None) => Err(singular()),
            }
        };
        let b0 = self.rate_load(q, xq, xv);
        let nu = match loops {
            Some(cl) => DVector::from_vec(cl.project_rates(self, q, &b0)?),
            None => DVector::from_column_slice(solve(DMatrix::from_vec(n, 1, b0))?.as_slice()),
        };
        // δq = M⁻¹ Σ J_bᵀ (m δφ, I δθ), every column by one solve (rate k's twist about the
        // origin S_k against the subtree's wrench, `tree_tangent`)
        let fr = self.frames(q, nu.as_slice());
        let mut wr = vec![V6::zeros(); nb];
        let mut rq = DMatrix::zeros(n, cols.cols);
        for col in 0..cols.cols {
            let xi = &cols.xi[col * 6 * nb..(col + 1) * 6 * nb];
            for (b, w) in wr.iter_mut().enumerate() {
                let (dphi, dth) = (read3(xi, 6 * b), read3(xi, 6 * b + 3));
                let f = dphi * self.body_mass(b);
                *w = join(&(fr.inertia[b] * dth + fr.com[b].cross(&f)), &f);
            }
            fr.subtree_sums(&mut wr);
            for (k, &b) in fr.body.iter().enumerate() {
                rq[(k, col)] = fr.s[k].dot(&wr[b]);
            }
        }
        let dq_all = solve(rq)?;
        let rv = if loops.is_none() && !duals {
            self.rates_tangent(&fr, &nu, xq, xv, cols, &dq_all)
        } else {
            self.rates_tangent_by_duals(q, &nu, xq, xv, cols, &dq_all, loops)?
        };
        // with loops the columns of `rv` are already δν (the projection's own solve)
        let dnu_all = if loops.is_some() { rv } else { solve(rv)? };
        let mut out = DMatrix::zeros(2 * n, cols.cols);
        out.rows_mut(0, n).copy_from(&dq_all);
        out.rows_mut(n, n).copy_from(&dnu_all);
        Ok(out)
    }

    /// `δb − δ(M ν)` per column of a tree at the end's frames `fr` and rates `nu` (module
    /// formulas; `xq`, `xv` the nodal coordinates and velocities, `dq` the columns' `δq`):
    /// n × cols.
    // per-body loops over several parallel arrays read closer to the formulas by index
    #[allow(clippy::needless_range_loop)]
    fn rates_tangent(
        &self,
        fr: &Frames,
        nu: &DVector<f64>,
        xq: &[f64],
        xv: &[f64],
        cols: &NodalColumns,
        dq: &DMatrix<f64>,
    ) -> DMatrix<f64> {
        let (n, nb) = (self.n(), self.n_bodies());
        let nu = nu.as_slice();
        let node = |x: &[f64], b: usize, k: usize| read3(x, 12 * b + 3 * k);
        // per body: the column-free factors of δL and δ(I ω) (`(δθ × dᵢ) × pᵢ = (dᵢ pᵢᵀ −
        // dᵢ·pᵢ) δθ`, `Σᵢ dᵢ × Σⱼ Eᵢⱼ δḋⱼ = Σⱼ ẽⱼ × δḋⱼ` with `ẽⱼ = Σᵢ Eᵢⱼ dᵢ`,
        // `Z^ω × Iω − I (Z^ω × ω) = (I ω̂ − (Iω)^) Z^ω`), the momenta f, f′ and the difference
        // d = h − h′ of the nodal and the rates' momenta
        let mut lth: Vec<Matrix3<f64>> = Vec::with_capacity(nb);
        let mut et: Vec<[Vector3<f64>; 3]> = Vec::with_capacity(nb);
        let mut izw: Vec<Matrix3<f64>> = Vec::with_capacity(nb);
        let (mut fs, mut f1s) = (Vec::with_capacity(nb), Vec::with_capacity(nb));
        let mut big_d = vec![V6::zeros(); nb];
        for b in 0..nb {
            let e = euler(&self.body_inertia::<f64>(b));
            let d: [Vector3<f64>; 3] = std::array::from_fn(|i| node(xq, b, i + 1));
            let p: [Vector3<f64>; 3] = std::array::from_fn(|i| {
                (0..3).fold(Vector3::zeros(), |acc, j| {
                    acc + node(xv, b, j + 1) * e[(i, j)]
                })
            });
            let l = (0..3).fold(Vector3::zeros(), |acc, i| acc + d[i].cross(&p[i]));
            let (mass, phi) = (self.body_mass(b), fr.com[b]);
            let f = node(xv, b, 0) * mass;
            let (w, vo) = split(&fr.v[b]);
            let iw = fr.inertia[b] * w;
            let f1 = (vo + w.cross(&phi)) * mass;
            big_d[b] = join(&(l + phi.cross(&f) - iw - phi.cross(&f1)), &(f - f1));
            let mut a = Matrix3::zeros();
            let mut dp = 0.0;
            for i in 0..3 {
                a += d[i] * p[i].transpose();
                dp += d[i].dot(&p[i]);
            }
            lth.push(a - Matrix3::identity() * dp);
            et.push(std::array::from_fn(|j| {
                d[0] * e[(0, j)] + d[1] * e[(1, j)] + d[2] * e[(2, j)]
            }));
            izw.push(fr.inertia[b] * w.cross_matrix() - iw.cross_matrix());
            fs.push(f);
            f1s.push(f1);
        }
        fr.subtree_sums(&mut big_d);
        let mut al = Along::new(nb, n);
        let zero = vec![0.0; n];
        let mut dd = vec![V6::zeros(); nb];
        let mut rv = DMatrix::zeros(n, cols.cols);
        for col in 0..cols.cols {
            let xi = &cols.xi[col * 6 * nb..(col + 1) * 6 * nb];
            let dv = &cols.dv[col * 12 * nb..(col + 1) * 12 * nb];
            self.along(fr, nu, dq.column(col).as_slice(), &zero, &mut al);
            for b in 0..nb {
                let (mass, phi) = (self.body_mass(b), fr.com[b]);
                let dth = read3(xi, 6 * b + 3);
                let ((zw, zv), (dw, dvo), (w, _)) =
                    (split(&al.z[b]), split(&al.dv[b]), split(&fr.v[b]));
                let dphi = zv + zw.cross(&phi);
                // the nodal momentum's change
                let df = read3(dv, 12 * b) * mass;
                let mut dl = lth[b] * dth;
                for j in 0..3 {
                    dl += et[b][j].cross(&read3(dv, 12 * b + 3 + 3 * j));
                }
                let dn = dl + dphi.cross(&fs[b]) + phi.cross(&df);
                // the rates' momentum's change
                let df1 = (dvo + dw.cross(&phi) + w.cross(&dphi)) * mass;
                let dn1 = izw[b] * zw + fr.inertia[b] * dw + dphi.cross(&f1s[b]) + phi.cross(&df1);
                dd[b] = join(&(dn - dn1), &(df - df1));
            }
            fr.subtree_sums(&mut dd);
            for (k, &b) in fr.body.iter().enumerate() {
                rv[(k, col)] = al.ds[k].dot(&big_d[b]) + fr.s[k].dot(&dd[b]);
            }
        }
        rv
    }

    /// `δb − δ(M ν)` per column by a dual pass of the rate load along `(δq, ξ, δv)` and one
    /// of the inverse dynamics at rest without gravity; with `loops`, `δν` itself by the
    /// projection onto the loops' rates (module formulas).
    #[allow(clippy::too_many_arguments)]
    fn rates_tangent_by_duals(
        &self,
        q: &[f64],
        nu: &DVector<f64>,
        xq: &[f64],
        xv: &[f64],
        cols: &NodalColumns,
        dq: &DMatrix<f64>,
        loops: Option<&Closure>,
    ) -> Result<DMatrix<f64>, String> {
        let (n, nb) = (self.n(), self.n_bodies());
        let nu_c: Vec<Dual64> = nu.iter().map(|&x| Dual64::from(x)).collect();
        let zero = vec![Dual64::from(0.0); n];
        let no_input = vec![Dual64::from(0.0); self.n_inputs()];
        let mut rv = DMatrix::zeros(n, cols.cols);
        for col in 0..cols.cols {
            let xi = &cols.xi[col * 6 * nb..(col + 1) * 6 * nb];
            let dv = &cols.dv[col * 12 * nb..(col + 1) * 12 * nb];
            let qd: Vec<Dual64> = (0..n).map(|i| Dual64::new(q[i], dq[(i, col)])).collect();
            let mut xqd: Vec<Dual64> = xq.iter().map(|&x| Dual64::from(x)).collect();
            for b in 0..nb {
                let dth = read3(xi, 6 * b + 3);
                for i in 0..3 {
                    let o = 12 * b + 3 + 3 * i;
                    let dd = dth.cross(&read3(xq, o));
                    for a in 0..3 {
                        xqd[o + a].eps = dd[a];
                    }
                }
                for a in 0..3 {
                    xqd[12 * b + a].eps = xi[6 * b + a];
                }
            }
            let xvd: Vec<Dual64> = xv
                .iter()
                .zip(dv)
                .map(|(&x, &d)| Dual64::new(x, d))
                .collect();
            let db = self.rate_load(&qd, &xqd, &xvd);
            if let Some(cl) = loops {
                let nud = cl.project_rates(self, &qd, &db)?;
                for i in 0..n {
                    rv[(i, col)] = nud[i].eps;
                }
                continue;
            }
            let dmnu = self.residual(&qd, &zero, &nu_c, &no_input, true);
            for i in 0..n {
                rv[(i, col)] = db[i].eps - dmnu[i].eps;
            }
        }
        Ok(rv)
    }

    /// `b = Σ_b J_bᵀ (m φ̇, Σᵢ dᵢ × Σⱼ Eᵢⱼ ḋⱼ)` at minimal `q` and nodal `xq`, `xv` (module
    /// formulas): the generalized momentum of the nodal velocities.
    fn rate_load<T: Real>(&self, q: &[T], xq: &[T], xv: &[T]) -> Vec<T> {
        let n = self.n();
        let nb = self.n_bodies();
        let m = self.motion(q, &vec![T::zero(); n], None);
        let (mut f, mut nn) = (vec![Vector3::zeros(); nb], vec![Vector3::zeros(); nb]);
        let node = |x: &[T], b: usize, k: usize| {
            let o = 12 * b + 3 * k;
            Vector3::new(x[o], x[o + 1], x[o + 2])
        };
        for b in 0..nb {
            // the Euler tensor is a constant of the body: formed in f64, lifted
            let e = cm::<T>(&euler(&self.body_inertia::<f64>(b)));
            let mut l = Vector3::zeros();
            for i in 0..3 {
                let mut p = Vector3::zeros();
                for j in 0..3 {
                    p += node(xv, b, j + 1) * e[(i, j)];
                }
                l += node(xq, b, i + 1).cross(&p);
            }
            let (phi, _) = self.com_of(&m, b);
            f[b] = node(xv, b, 0) * c::<T>(self.body_mass(b));
            nn[b] = l + phi.cross(&f[b]);
        }
        self.generalized(&m, f, nn)
    }
}
