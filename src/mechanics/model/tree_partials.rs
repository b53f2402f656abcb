//! The analytic partial derivatives of the tree dynamics' residual (`tree_dynamics`),
//! `∂res/∂q`, `∂res/∂ν` and `∂res/∂u` at `ν̇₀ = ν̇(q, ν, u)`, in one sweep of spatial quantities
//! (Carpentier & Mansard 2018, world frame; `spatial`), and `ν̇₀` with the mass matrix's
//! articulated-body factors (`articulated`): what the linear model needs (`linear`) without a
//! dual-number pass per direction.
//!
//! Rates `k` in tree order; `j ≺ i`: `j` lies on the path from `i` to the ground (an earlier
//! rate of the same joint included), `B(k)` the body that rate `k` moves, `sub(b)` the bodies
//! of the subtree of `b`. Sums over `b ∈ sub(B(k))` are written `·_k` (composites). Every
//! spatial quantity of body `b` and of its rates is taken about its joint's point `r_b` (the
//! child joint frame's origin, where the rates' twists `S_k = (ω_k, u_k)` act) and shifted
//! along the links (`spatial`), so that products stay of the size of the links, not of their
//! distance from the origin; a pair `(i, j)` meets at `r_B(i)`.
//!
//! ```text
//! kinematics   V_k− = Σ_{j≺k} S_j ν_j,   A_k− = A₀ + Σ_{j≺k} (S_j ν̇_j + V_j− × S_j ν_j),   A₀ = (0, −g)
//!              V_b, A_b the same sums over every rate on the body's path
//!              ∂S_i/∂q_j = S_j × S_i (j ≺ i),   Ṡ_k = V_k− × S_k
//! bodies       f_b = Y_b A_b + V_b ×* Y_b V_b − w_b,   w_b = (n_b + c_b × f_b^e, f_b^e)
//!              (the inputs' body torque n_b and force f_b^e at the centre of mass c_b)
//! composites   Y_k = Σ Y_b,  B_k = Σ (V_b ×* Y_b − Y_b V_b ×),  H_k = Σ Y_b V_b,
//!              F_k = Σ (f_b + w_b),  W_k = Σ w_b,  E_k = Σ (c_b f_bᵉᵀ − (f_b^e·c_b) 1),  f_k^e = Σ f_b^e
//! res_k = S_k·(F_k − W_k) + a_k ν̇_k − gen_k(q_k, ν_k, u)          (gen: `coord_load`)
//! per rate j   W_j = V_j− × S_j,   P_j = A_j− × S_j + V_j− × W_j,   S_j = (ω_j, v_j)
//! i ≼ j        ∂τ_i/∂q_j = S_i·(S_j ×* F_j + Y_j P_j + B_j W_j + W_j ×* H_j − (E_j ω_j + v_j × f_j^e, 0))
//!              ∂τ_i/∂ν_j = S_i·(2 Y_j W_j + B_j S_j + S_j ×* H_j)
//! j ≺ i        ∂τ_i/∂q_j = U_i·P_j + Z_i·W_j + X_i·S_j,   ∂τ_i/∂ν_j = 2 U_i·W_j + Z_i·S_j
//!              U_i = Y_i S_i,  Z_i = B_iᵀ S_i − S_i ×* H_i,
//!              X_i = −S_i ×* W_i − (E_iᵀ ω_i, f_i^e × ω_i)
//! other pairs  0 (neither moves the other)
//! inputs       ∂τ_i/∂u = −S_i·∂W_i/∂u  (body torques and forces),  −∂gen_i/∂u
//! ```
//!
//! The per-coordinate loads `gen` (springs, dampers, stops, clamped inputs, actuators with
//! their gains and clamps) are differentiated by dual numbers on their own coordinate, so
//! their one-sided derivatives at a clamp or a stop are the dual path's. Covered: trees of
//! revolute, prismatic, cylindrical, universal, planar and fixed joints without sticking
//! bristles; spherical joints, free bodies, touching contacts and joint friction take the dual
//! path (`linear`).
//!
//! Cost: O(N) sweeps, O(n·depth) entries, O(n) per mass-matrix solve.

use super::super::articulated::Articulated;
use super::super::def::JointType;
use super::super::spatial::{
    crf, crm, cross_f, cross_m, inertia, join, shift_f, shift_m, shift_map, split, M6, V6,
};
use super::{Coord, Motion, Parent, TreeDynamics};
use crate::math::{Mat3, Vec3};
use nalgebra::DMatrix;
use num_dual::Dual64;

/// The residual's partial derivatives at an operating point and the mass matrix's factors
/// (module formulas).
pub(crate) struct Partials {
    /// `ν̇₀` (n), rad/s² or m/s².
    pub nud0: Vec<f64>,
    /// `[∂res/∂q  ∂res/∂ν  ∂res/∂u]`, n × (2n + m).
    pub jac: DMatrix<f64>,
    /// The mass matrix's articulated-body factors.
    pub mass: Articulated,
}

/// Per rate: its motion and the tree links; per body its point (module formulas).
struct Rates {
    /// `S_k` about `r_B(k)`.
    s: Vec<V6>,
    prev: Vec<Option<usize>>,
    order: Vec<usize>,
    body: Vec<usize>,
    /// Per body: the last rate on its path to the ground.
    last: Vec<Option<usize>>,
    /// Per body: its joint's point `r_b` (world, m), and `r_b − r_parent` (0 at the ground).
    point: Vec<Vec3>,
    link: Vec<Vec3>,
}

impl TreeDynamics {
    /// Whether [`TreeDynamics::partials`] covers this model (module docs).
    #[must_use]
    pub(crate) fn has_partials(&self) -> bool {
        !self.coords.is_empty()
            && self.sticking.is_empty()
            && self.coords.iter().all(|c| matches!(c, Coord::Joint { .. }))
            && self.parent_of.iter().all(|p| matches!(p, Parent::Joint(_)))
            && self
                .joints
                .iter()
                .flatten()
                .all(|jd| jd.kind != JointType::Spherical)
    }

    /// The rates' motions and links, the bodies' points, at the motion `mo` of `q`.
    fn rates(&self, mo: &Motion<f64>) -> Option<Rates> {
        let (n, nb) = (self.coords.len(), self.mass.len());
        let mut r = Rates {
            s: mo.cols.iter().map(|(w, u, _)| join(w, u)).collect(),
            prev: vec![None; n],
            order: Vec::with_capacity(n),
            body: vec![0; n],
            last: vec![None; nb],
            point: vec![Vec3::zeros(); nb],
            link: vec![Vec3::zeros(); nb],
        };
        for &b in &self.order {
            let Parent::Joint(j) = self.parent_of[b] else {
                return None;
            };
            let jd = self.joints[j].as_ref()?;
            r.point[b] = match jd.kind.dof() {
                0 => mo.o[b] + mo.r[b] * jd.cf_t,
                _ => mo.cols[jd.at].2,
            };
            r.link[b] = jd
                .parent
                .map_or_else(Vec3::zeros, |p| r.point[b] - r.point[p]);
            let mut at = jd.parent.and_then(|p| r.last[p]);
            for k in jd.at..jd.at + jd.kind.dof() {
                r.prev[k] = at;
                r.order.push(k);
                r.body[k] = b;
                at = Some(k);
            }
            r.last[b] = at;
        }
        (r.order.len() == n).then_some(r)
    }

    /// The articulated-body factors of the mass matrix at the motion `mo` of `q`, with the
    /// rotors' armature or (`armature` false) the bodies' share alone; `None` for a tree with
    /// free bodies (not a chain of joint rates) or a mass matrix that is not positive definite.
    pub(crate) fn mass_factors(&self, mo: &Motion<f64>, armature: bool) -> Option<Articulated> {
        if self.coords.is_empty() {
            return None;
        }
        let r = self.rates(mo)?;
        let y: Vec<M6> = (0..self.mass.len())
            .map(|b| {
                let (pg, _) = self.com_of(mo, b);
                inertia(self.mass[b], &(pg - r.point[b]), &self.inertia_world(mo, b))
            })
            .collect();
        self.factors(&r, &y, armature)
    }

    /// The articulated-body factors of the rates `r` with the bodies' inertias `y` (about
    /// their points) and, if `armature`, the rotors' (module formulas of `articulated`).
    fn factors(&self, r: &Rates, y: &[M6], armature: bool) -> Option<Articulated> {
        let n = self.coords.len();
        let mut own = vec![M6::zeros(); n];
        for (b, last) in r.last.iter().enumerate() {
            if let Some(k) = *last {
                // a body on a fixed joint rides on its parent's last rate
                own[k] += shift_map(&y[b], &(r.point[r.body[k]] - r.point[b]));
            }
        }
        let mut rotor = vec![0.0; n];
        if armature {
            for jd in self.joints.iter().flatten() {
                if jd.armature > 0.0 {
                    rotor[jd.at..jd.at + jd.kind.dof()].fill(jd.armature);
                }
            }
        }
        let mut offset = vec![Vec3::zeros(); n];
        for k in 0..n {
            if let Some(p) = r.prev[k] {
                offset[k] = r.point[r.body[k]] - r.point[r.body[p]];
            }
        }
        Articulated::new(&r.s, &r.prev, &offset, r.order.clone(), own, &rotor)
    }

    /// Velocities and accelerations (gravity in `A₀`) of every body, and of every rate's
    /// frame before it (`V_k−`, `A_k−`), at `(ν, ν̇)` (module formulas; about the bodies'
    /// points).
    fn sweep(&self, r: &Rates, nu: &[f64], nud: &[f64]) -> [Vec<V6>; 4] {
        let (n, nb) = (self.coords.len(), self.mass.len());
        let a0 = join(&Vec3::zeros(), &(-self.gravity));
        let (mut vb, mut ab) = (vec![V6::zeros(); nb], vec![a0; nb]);
        let (mut vm, mut am) = (vec![V6::zeros(); n], vec![a0; n]);
        for &b in &self.order {
            let Parent::Joint(j) = self.parent_of[b] else {
                continue;
            };
            let Some(jd) = self.joints[j].as_ref() else {
                continue;
            };
            let d = &r.link[b];
            let (mut v, mut a) = jd.parent.map_or((V6::zeros(), a0), |p| {
                (shift_m(&vb[p], d), shift_m(&ab[p], d))
            });
            for k in jd.at..jd.at + jd.kind.dof() {
                vm[k] = v;
                am[k] = a;
                a += r.s[k] * nud[k] + cross_m(&v, &r.s[k]) * nu[k];
                v += r.s[k] * nu[k];
            }
            vb[b] = v;
            ab[b] = a;
        }
        [vb, ab, vm, am]
    }

    /// `∂res/∂q`, `∂res/∂ν`, `∂res/∂u` at `(q, ν, u)` and `ν̇₀`, with the mass matrix's factors
    /// (module formulas). `None` when the model is not covered ([`TreeDynamics::has_partials`])
    /// or its mass matrix is not positive definite (then the dual path decides).
    #[allow(clippy::too_many_lines)]
    pub(crate) fn partials(&self, q: &[f64], nu: &[f64], u: &[f64]) -> Option<Partials> {
        if !self.has_partials() {
            return None;
        }
        let (n, nb, m) = (self.coords.len(), self.mass.len(), self.nu);
        let mo = self.motion(q, nu, None);
        let r = self.rates(&mo)?;
        let (mut fe, mut ne) = (vec![Vec3::zeros(); nb], vec![Vec3::zeros(); nb]);
        for &(b, i) in &self.torques {
            ne[b] += Vec3::new(u[i], u[i + 1], u[i + 2]);
        }
        for &(b, i) in &self.forces {
            fe[b] += Vec3::new(u[i], u[i + 1], u[i + 2]);
        }
        // centres of mass about the bodies' points, inertias
        let (mut cg, mut y) = (vec![Vec3::zeros(); nb], vec![M6::zeros(); nb]);
        for b in 0..nb {
            let (pg, _) = self.com_of(&mo, b);
            cg[b] = pg - r.point[b];
            y[b] = inertia(self.mass[b], &cg[b], &self.inertia_world(&mo, b));
        }
        let mass = self.factors(&r, &y, true)?;
        let wext: Vec<V6> = (0..nb)
            .map(|b| join(&(ne[b] + cg[b].cross(&fe[b])), &fe[b]))
            .collect();
        // the subtree totals of the bodies' forces f_b + w_b (inertia and gravity)
        let inertial = |vb: &[V6], ab: &[V6]| -> Vec<V6> {
            let mut f: Vec<V6> = (0..nb)
                .map(|b| y[b] * ab[b] + cross_f(&vb[b], &(y[b] * vb[b])))
                .collect();
            self.to_roots(&r, &mut f, shift_f);
            f
        };
        let mut wc = wext.clone();
        self.to_roots(&r, &mut wc, shift_f);
        let gen = |k: usize| -> f64 {
            let Coord::Joint { joint, k: kk } = self.coords[k] else {
                return 0.0;
            };
            let jd = self.joints[joint].as_ref().expect("tree joint");
            self.coord_load(jd, kk, q[k], nu[k], u)
        };
        // ν̇₀ = −M⁻¹ res(q, ν, 0, u)
        let [vb, ab, _, _] = self.sweep(&r, nu, &vec![0.0; n]);
        let f0 = inertial(&vb, &ab);
        let mut nud0 = DMatrix::from_fn(n, 1, |k, _| {
            let b = r.body[k];
            -(r.s[k].dot(&(f0[b] - wc[b])) - gen(k))
        });
        mass.solve_columns(&mut nud0.as_view_mut());
        let nud0: Vec<f64> = nud0.iter().copied().collect();
        let [vb, ab, vm, am] = self.sweep(&r, nu, &nud0);
        let fc = inertial(&vb, &ab);
        // composites
        let mut yc = y.clone();
        let mut bc: Vec<M6> = (0..nb)
            .map(|b| crf(&vb[b]) * y[b] - y[b] * crm(&vb[b]))
            .collect();
        let mut hc: Vec<V6> = (0..nb).map(|b| y[b] * vb[b]).collect();
        let mut ec: Vec<Mat3> = (0..nb)
            .map(|b| cg[b] * fe[b].transpose() - Mat3::identity() * fe[b].dot(&cg[b]))
            .collect();
        self.to_roots(&r, &mut yc, shift_map);
        self.to_roots(&r, &mut bc, shift_map);
        self.to_roots(&r, &mut hc, shift_f);
        let mut fec = fe.clone();
        for &b in self.order.iter().rev() {
            if let (_, Some(p)) = self.own_dofs(b) {
                let (e, f, d) = (ec[b], fec[b], -r.link[b]);
                ec[p] += e - d * f.transpose() + Mat3::identity() * f.dot(&d);
                fec[p] += f;
            }
        }
        let ww: Vec<V6> = (0..n).map(|k| cross_m(&vm[k], &r.s[k])).collect();
        let pp: Vec<V6> = (0..n)
            .map(|k| cross_m(&am[k], &r.s[k]) + cross_m(&vm[k], &ww[k]))
            .collect();
        let mut jac = DMatrix::zeros(n, 2 * n + m);
        for j in 0..n {
            let (b, sj, w, p) = (r.body[j], r.s[j], ww[j], pp[j]);
            let (wj, vj) = split(&sj);
            let ext = join(&(ec[b] * wj + vj.cross(&fec[b])), &Vec3::zeros());
            let col_q = cross_f(&sj, &fc[b]) + yc[b] * p + bc[b] * w + cross_f(&w, &hc[b]) - ext;
            let col_v = yc[b] * (w * 2.0) + bc[b] * sj + cross_f(&sj, &hc[b]);
            let mut i = Some(j);
            while let Some(k) = i {
                let d = r.point[r.body[k]] - r.point[b];
                jac[(k, j)] = r.s[k].dot(&shift_f(&col_q, &d));
                jac[(k, n + j)] = r.s[k].dot(&shift_f(&col_v, &d));
                i = r.prev[k];
            }
        }
        for i in 0..n {
            let (b, si) = (r.body[i], r.s[i]);
            let (wi, _) = split(&si);
            let ui = yc[b] * si;
            let zi = bc[b].transpose() * si - cross_f(&si, &hc[b]);
            let xi = -cross_f(&si, &wc[b]) - join(&(ec[b].transpose() * wi), &fec[b].cross(&wi));
            let mut j = r.prev[i];
            while let Some(k) = j {
                let d = r.point[b] - r.point[r.body[k]];
                let (sk, w, p) = (
                    shift_m(&r.s[k], &d),
                    shift_m(&ww[k], &d),
                    shift_m(&pp[k], &d),
                );
                jac[(i, k)] = ui.dot(&p) + zi.dot(&w) + xi.dot(&sk);
                jac[(i, n + k)] = 2.0 * ui.dot(&w) + zi.dot(&sk);
                j = r.prev[k];
            }
        }
        let at_u = |(b, i): (usize, usize), w: &dyn Fn(usize) -> V6, jac: &mut DMatrix<f64>| {
            for c in 0..3 {
                let w = w(c);
                let mut k = r.last[b];
                while let Some(kk) = k {
                    let d = r.point[r.body[kk]] - r.point[b];
                    jac[(kk, 2 * n + i + c)] -= r.s[kk].dot(&shift_f(&w, &d));
                    k = r.prev[kk];
                }
            }
        };
        for &t in &self.torques {
            at_u(t, &|c| join(&Vec3::ith(c, 1.0), &Vec3::zeros()), &mut jac);
        }
        for &(b, i) in &self.forces {
            let e = |c: usize| join(&cg[b].cross(&Vec3::ith(c, 1.0)), &Vec3::ith(c, 1.0));
            at_u((b, i), &e, &mut jac);
        }
        self.load_partials(q, nu, u, &mut jac);
        Some(Partials { nud0, jac, mass })
    }
    /// Subtracts the per-coordinate loads' derivatives (`coord_load`, by dual numbers on
    /// each coordinate's own `q_k`, `ν_k` and the inputs it reads) from
    /// `jac = [∂res/∂q  ∂res/∂ν  ∂res/∂u]`.
    fn load_partials(&self, q: &[f64], nu: &[f64], u: &[f64], jac: &mut DMatrix<f64>) {
        let n = self.coords.len();
        let mut ud: Vec<Dual64> = u.iter().map(|&x| Dual64::from(x)).collect();
        for jd in self.joints.iter().flatten() {
            for kk in 0..jd.kind.dof() {
                let k = jd.at + kk;
                let (qk, vk) = (Dual64::from(q[k]), Dual64::from(nu[k]));
                jac[(k, k)] -= self.coord_load(jd, kk, qk.derivative(), vk, &ud).eps;
                jac[(k, n + k)] -= self.coord_load(jd, kk, qk, vk.derivative(), &ud).eps;
                let mut reads: Vec<usize> = jd.input.map(|i| i + kk).into_iter().collect();
                reads.extend(jd.acts.list.iter().map(|a| a.input));
                reads.sort_unstable();
                reads.dedup();
                for l in reads {
                    ud[l] = ud[l].derivative();
                    jac[(k, 2 * n + l)] -= self.coord_load(jd, kk, qk, vk, &ud).eps;
                    ud[l] = Dual64::from(u[l]);
                }
            }
        }
    }

    /// Adds every body's entry of `x` into its parent's, leaves first, moved to the parent's
    /// point by `shift(x, d)`: subtree totals.
    fn to_roots<X: Copy + std::ops::AddAssign>(
        &self,
        r: &Rates,
        x: &mut [X],
        shift: impl Fn(&X, &Vec3) -> X,
    ) {
        for &b in self.order.iter().rev() {
            if let (_, Some(p)) = self.own_dofs(b) {
                let child = shift(&x[b], &-r.link[b]);
                x[p] += child;
            }
        }
    }
}
