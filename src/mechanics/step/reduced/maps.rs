//! Joint maps of the discrete null-space method (theory.md §4.5): the twist of a child body in
//! terms of its parent's twist and the joint's own rates,
//!
//! ```text
//! δθ_c = Z δθ_p + Σ_k n_k u_k                       (rotational rates, rad)
//! δφ_c = δφ_p + δθ_p × e + Σ_k (ρ × n_k) u_k + Σ_l t_l u_l   (translational rates, m)
//! ```
//!
//! i.e. `x_c = A x_p + S u` with `A = [I −ê; 0 Z]`, `S = [ρ̂N T; N 0]` (`x = (δφ, δθ)`, world
//! frame). `Z = I` when the child turns with its parent (every pair except the spherical one,
//! whose child rotation `u` is absolute, world frame, and a free root body, `S = I₆`).
//! `e = ρᴬ + r̃ − Zρᴮ` is the lever from the parent's centre of mass to the child's (`ρᴬ`,
//! `ρᴮ` the joint point from each centre of mass, `r̃ = r` for the pairs whose slide rows are
//! `r·a_k`, else 0 — their point rows are `r·e_k`, world axes).
//!
//! Evaluated at the iterate `q` the map is `Q = ∂q/∂u` of the nodal reparametrization
//! (`reduced::place`); at the midpoint `q̄` it is the discrete null-space matrix `P̄` with
//! `G(q̄) P̄ = 0` exactly for the rows of `joint.rs` (rotational rows `a_i·b_j`:
//! `(ω_B − ω_A)·(ā_i × b̄_j) = 0`; slide rows `r·a_k`: `ṙ·ā_k + r̄·(ω_A × ā_k) = 0`, hence the
//! slide directions `ā₁ × ā₂` and `ā₂ × ā₃`, `ā₃ × ā₁` at the midpoint, whose axes are not
//! orthonormal).
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use crate::math::Vec3;
use crate::mechanics::model::constraint::Nodes;
use crate::mechanics::model::def::JointType;
use crate::mechanics::model::joint::JointGeom;

/// One joint map (see the module docs); `fr + ft ≤ 6` rates, rotational first.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Map {
    /// Number of rotational rates.
    pub fr: usize,
    /// Number of translational rates.
    pub ft: usize,
    /// Rotation axes `n_k` (world frame, unit at the iterate).
    pub n: [Vec3; 3],
    /// Slide directions `t_l` (world frame).
    pub t: [Vec3; 3],
    /// Lever `e` from the parent's centre of mass to the child's (m).
    pub e: Vec3,
    /// Joint point from the child's centre of mass `ρᴮ` (m).
    pub rho: Vec3,
    /// Whether the child turns with its parent (`Z = I`).
    pub z: bool,
}

/// Six-vector `(force or linear part, moment or angular part)`.
pub(crate) type V6 = [f64; 6];

fn split(w: &V6) -> (Vec3, Vec3) {
    (Vec3::new(w[0], w[1], w[2]), Vec3::new(w[3], w[4], w[5]))
}

fn join(a: &Vec3, b: &Vec3) -> V6 {
    [a.x, a.y, a.z, b.x, b.y, b.z]
}

impl Map {
    /// The map of a free root body: `S = I₆` (rotation rates first).
    pub fn free() -> Self {
        Self {
            fr: 3,
            ft: 3,
            n: [Vec3::x(), Vec3::y(), Vec3::z()],
            t: [Vec3::x(), Vec3::y(), Vec3::z()],
            e: Vec3::zeros(),
            rho: Vec3::zeros(),
            z: false,
        }
    }

    /// Number of rates `f = fr + ft`.
    #[inline(always)]
    pub fn f(&self) -> usize {
        self.fr + self.ft
    }

    /// Column `k` of `S`.
    #[inline(always)]
    pub fn s_col(&self, k: usize) -> V6 {
        if k < self.fr {
            join(&self.rho.cross(&self.n[k]), &self.n[k])
        } else {
            join(&self.t[k - self.fr], &Vec3::zeros())
        }
    }

    /// `Sᵀ w` into `out[..f]`: the moment about the joint point along each axis, the force
    /// along each slide.
    #[inline(always)]
    pub fn st_mul(&self, w: &V6, out: &mut [f64; 6]) {
        let (f, m) = split(w);
        let mj = m + f.cross(&self.rho);
        for k in 0..self.fr {
            out[k] = self.n[k].dot(&mj);
        }
        for l in 0..self.ft {
            out[self.fr + l] = self.t[l].dot(&f);
        }
    }

    /// `S u`.
    #[inline(always)]
    pub fn s_mul(&self, u: &[f64; 6]) -> V6 {
        let mut w = Vec3::zeros();
        let mut v = Vec3::zeros();
        for k in 0..self.fr {
            w += self.n[k] * u[k];
        }
        for l in 0..self.ft {
            v += self.t[l] * u[self.fr + l];
        }
        join(&(v + self.rho.cross(&w)), &w)
    }

    /// `A x` (parent twist to the child's, joint rates zero).
    #[inline(always)]
    pub fn a_mul(&self, x: &V6) -> V6 {
        let (v, w) = split(x);
        join(
            &(v + w.cross(&self.e)),
            &if self.z { w } else { Vec3::zeros() },
        )
    }

    /// `Aᵀ w` (child wrench about its centre of mass to the parent's).
    #[inline(always)]
    pub fn at_mul(&self, w: &V6) -> V6 {
        let (f, m) = split(w);
        let mm = self.e.cross(&f) + if self.z { m } else { Vec3::zeros() };
        join(&f, &mm)
    }
}

/// Joint point from the parent's and the child's centre of mass `(ρᴬ, ρᴮ)` at nodes `qa`, `qb`
/// (zero for the world parent, whose joint point is fixed).
pub(crate) fn levers(g: &JointGeom, qa: &Nodes, qb: &Nodes) -> (Vec3, Vec3) {
    let mut ra = Vec3::zeros();
    let mut rb = Vec3::zeros();
    for i in 1..4 {
        ra -= qa[i] * g.r.a[i];
        rb += qb[i] * g.r.b[i];
    }
    (ra, rb)
}

/// The map of joint `g` at nodes `qa` (parent; any nodes for the world) and `qb`: `Q` at the
/// iterate (`mid = false`), `P̄` at the midpoint (`mid = true`).
pub(crate) fn joint_map(g: &JointGeom, qa: &Nodes, qb: &Nodes, mid: bool) -> Map {
    let (ra, rb) = levers(g, qa, qb);
    let a = |k: usize| g.a[k].eval(qa, qb);
    let mut m = Map {
        fr: 0,
        ft: 0,
        n: [Vec3::zeros(); 3],
        t: [Vec3::zeros(); 3],
        e: ra - rb,
        rho: rb,
        z: true,
    };
    let slide_lever = |m: &mut Map| m.e = ra + g.r.eval(qa, qb) - rb;
    match g.kind {
        JointType::Spherical => {
            m.fr = 3;
            m.n = [Vec3::x(), Vec3::y(), Vec3::z()];
            m.e = ra;
            m.z = false;
        }
        JointType::Revolute => {
            m.fr = 1;
            m.n[0] = a(2);
        }
        JointType::Universal => {
            m.fr = 2;
            m.n[0] = a(0);
            m.n[1] = g.b[1].eval(qa, qb);
        }
        JointType::Cylindrical | JointType::Prismatic => {
            if g.kind == JointType::Cylindrical {
                m.fr = 1;
                m.n[0] = a(2);
            }
            m.ft = 1;
            m.t[0] = if mid { a(0).cross(&a(1)) } else { a(2) };
            slide_lever(&mut m);
        }
        JointType::Planar => {
            m.fr = 1;
            m.ft = 2;
            let (a1, a2, a3) = (a(0), a(1), a(2));
            m.n[0] = a3;
            m.t[0] = if mid { a2.cross(&a3) } else { a1 };
            m.t[1] = if mid { a3.cross(&a1) } else { a2 };
            slide_lever(&mut m);
        }
        JointType::Fixed => {}
    }
    m
}
