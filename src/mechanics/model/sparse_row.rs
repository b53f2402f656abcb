//! A [`DotRow`] compiled to its non-zero nodes, for the Newton residual and Jacobian.
//!
//! Joint rows touch few of the eight nodes `[A φ, A d1, A d2, A d3, B φ, B d1, B d2, B d3]`:
//! a revolute point row has a constant `w` and a `u` over 2–4 nodes, an axis row one node in
//! each factor. [`SparseRow`] keeps, once at model set-up, the node slots where a coefficient is
//! non-zero and evaluates the value, gradient, Hessian blocks and the projections `P̄ᵀ∇g`,
//! `∇g Q` over those only. Every operation repeats the dense formula of [`DotRow`] term by
//! term and only leaves out terms that are exact zeros, so results are bit-identical to the
//! dense evaluation (up to the sign of a zero).
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use super::constraint::{DotRow, LinVec, Nodes, NODES};
use crate::math::Vec3;

/// One factor (`u` or `w`) of a row restricted to its non-zero node slots.
#[derive(Clone, Copy, Debug, Default)]
struct SparseVec {
    /// Node slots `k` (0: φ, 1–3: dₖ) where the A or B coefficient is non-zero, ascending;
    /// the first `n` are used.
    k: [usize; NODES],
    /// Number of slots used.
    n: usize,
    /// A coefficient of each used slot (compact order).
    a: [f64; NODES],
    /// B coefficient of each used slot (compact order).
    b: [f64; NODES],
    /// Constant part, world frame.
    c: Vec3,
}

impl SparseVec {
    /// Compiles `v`; A's coefficients are ignored when the parent is the world (`!has_a`,
    /// its nodes are then zero in the step).
    fn new(v: &LinVec, has_a: bool) -> Self {
        let mut s = Self {
            c: v.c,
            ..Self::default()
        };
        for k in 0..NODES {
            let a = if has_a { v.a[k] } else { 0.0 };
            if a != 0.0 || v.b[k] != 0.0 {
                s.k[s.n] = k;
                s.a[s.n] = a;
                s.b[s.n] = v.b[k];
                s.n += 1;
            }
        }
        s
    }

    /// Value `c + Σₖ (aₖ qᴬₖ + bₖ qᴮₖ)` (same association as [`LinVec::eval`]), world frame.
    #[inline(always)]
    fn eval(&self, qa: &Nodes, qb: &Nodes, has_a: bool) -> Vec3 {
        let mut v = self.c;
        if has_a {
            for i in 0..self.n {
                let k = self.k[i];
                v += qa[k] * self.a[i] + qb[k] * self.b[i];
            }
        } else {
            for i in 0..self.n {
                v += qb[self.k[i]] * self.b[i];
            }
        }
        v
    }
}

/// Which body of a joint a projection is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Side {
    /// The parent A (node indices 0..4).
    A,
    /// The child B (node indices 4..8).
    B,
}

/// A [`DotRow`] `g = u·w − c` restricted to its non-zero nodes.
///
/// The gradient of a row is held *compact*: entry `i` of a `[Vec3; 8]` is `∂g/∂(node idx[i])`
/// (world frame) for the row's union of non-zero nodes, A's first, ascending.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct SparseRow {
    /// First factor.
    u: SparseVec,
    /// Second factor.
    w: SparseVec,
    /// Constant subtracted.
    offset: f64,
    /// The parent is a body (not the world).
    has_a: bool,
    /// Node indices (0..8) where `α` or `β` is non-zero, ascending; the first `n` are used.
    idx: [usize; 2 * NODES],
    /// `α` (coefficients of `u`) at `idx` (compact order).
    al: [f64; 2 * NODES],
    /// `β` (coefficients of `w`) at `idx` (compact order).
    be: [f64; 2 * NODES],
    /// Number of non-zero nodes.
    n: usize,
    /// Number of them on A (`idx[..na]` are below 4).
    na: usize,
    /// Both factors depend on the nodes (non-zero Hessian `αβᵀ + βαᵀ`).
    quad: bool,
    /// Compact gradient `w₀ αₙ + u₀ βₙ` of a linear row (`!quad`: one factor is the constant
    /// part of its [`LinVec`], the other's coefficients are zero), which does not depend on
    /// the configuration.
    gc: [Vec3; 2 * NODES],
}

impl SparseRow {
    /// Compiles `row` for a joint whose parent is a body (`has_a`) or the world.
    #[must_use]
    pub(crate) fn new(row: &DotRow, has_a: bool) -> Self {
        let (al, be) = (row.u.coeffs(), row.w.coeffs());
        let mut s = Self {
            u: SparseVec::new(&row.u, has_a),
            w: SparseVec::new(&row.w, has_a),
            offset: row.offset,
            has_a,
            ..Self::default()
        };
        let first = if has_a { 0 } else { NODES };
        for m in first..2 * NODES {
            if al[m] != 0.0 || be[m] != 0.0 {
                s.idx[s.n] = m;
                s.al[s.n] = al[m];
                s.be[s.n] = be[m];
                s.n += 1;
                if m < NODES {
                    s.na += 1;
                }
            }
        }
        let any = |c: &[f64; 2 * NODES]| c[..s.n].iter().any(|x| *x != 0.0);
        s.quad = any(&s.al) && any(&s.be);
        if !s.quad {
            for i in 0..s.n {
                s.gc[i] = row.w.c * s.al[i] + row.u.c * s.be[i];
            }
        }
        s
    }

    /// The factors `(u, w)` at the nodes `qa`, `qb` (world frame).
    #[inline(always)]
    pub(crate) fn uw(&self, qa: &Nodes, qb: &Nodes) -> (Vec3, Vec3) {
        (
            self.u.eval(qa, qb, self.has_a),
            self.w.eval(qa, qb, self.has_a),
        )
    }

    /// Value `g = u·w − c` from the factors.
    #[inline]
    pub(crate) fn value(&self, u: &Vec3, w: &Vec3) -> f64 {
        u.dot(w) - self.offset
    }

    /// Compact gradient `w αₙ + u βₙ` from the factors `u`, `w` at the evaluation point,
    /// written to `buf` (entries `n..` untouched); a linear row returns its constant gradient.
    #[inline(always)]
    pub(crate) fn grad<'a>(
        &'a self,
        u: &Vec3,
        w: &Vec3,
        buf: &'a mut [Vec3; 2 * NODES],
    ) -> &'a [Vec3; 2 * NODES] {
        if !self.quad {
            return &self.gc;
        }
        for i in 0..self.n {
            buf[i] = w * self.al[i] + u * self.be[i];
        }
        buf
    }

    /// Compact gradient at the nodes `qa`, `qb` into `buf` (see [`SparseRow::grad`]); a
    /// linear row evaluates nothing.
    #[inline(always)]
    pub(crate) fn grad_at<'a>(
        &'a self,
        qa: &Nodes,
        qb: &Nodes,
        buf: &'a mut [Vec3; 2 * NODES],
    ) -> &'a [Vec3; 2 * NODES] {
        if !self.quad {
            return &self.gc;
        }
        let (u, w) = self.uw(qa, qb);
        self.grad(&u, &w, buf)
    }

    /// `fa`, `fb` (node forces of A and B) `+= coef · g`.
    #[inline(always)]
    pub(crate) fn add_forces(
        &self,
        g: &[Vec3; 2 * NODES],
        coef: f64,
        fa: &mut [Vec3; NODES],
        fb: &mut [Vec3; NODES],
    ) {
        for i in 0..self.na {
            fa[self.idx[i]] += g[i] * coef;
        }
        for i in self.na..self.n {
            fb[self.idx[i] - NODES] += g[i] * coef;
        }
    }

    /// Adds `hc · S` (`S = αβᵀ + βαᵀ`, see [`DotRow::hessian`]) to the 4 × 4 node couplings:
    /// the A–A block into `cb[a]`, B–B into `cb[b]` and A–B (A rows) into `cab`. Nothing for
    /// a linear row.
    #[inline(always)]
    pub(crate) fn add_hessian(
        &self,
        hc: f64,
        cb: &mut [[f64; 16]],
        a: Option<usize>,
        b: usize,
        cab: &mut [f64; 16],
    ) {
        if self.quad {
            self.add_hessian_quad(hc, cb, a, b, cab);
        }
    }

    /// [`SparseRow::add_hessian`] of a quadratic row.
    fn add_hessian_quad(
        &self,
        hc: f64,
        cb: &mut [[f64; 16]],
        a: Option<usize>,
        b: usize,
        cab: &mut [f64; 16],
    ) {
        for i in 0..self.n {
            let (an, bn) = (self.al[i] * hc, self.be[i] * hc);
            if an == 0.0 && bn == 0.0 {
                continue;
            }
            let ni = self.idx[i];
            for j in 0..self.n {
                let v = an * self.be[j] + bn * self.al[j];
                let mj = self.idx[j];
                match (ni < NODES, mj < NODES, a) {
                    (true, true, Some(a)) => cb[a][4 * ni + mj] += v,
                    (true, false, Some(_)) => cab[4 * ni + mj - NODES] += v,
                    (false, false, _) => cb[b][4 * (ni - NODES) + mj - NODES] += v,
                    _ => {}
                }
            }
        }
    }

    /// `[f_φ ; Σᵢ dᵢ × f_{dᵢ}]` of the compact gradient `g` on one side (`P̄ᵀ∇g` with the
    /// midpoint directors, `∇g Q` with the iterate's); `None` when the row does not touch
    /// that body (the result would be zero).
    #[inline(always)]
    pub(crate) fn project(
        &self,
        g: &[Vec3; 2 * NODES],
        side: Side,
        d: &[Vec3; 3],
    ) -> Option<[f64; 6]> {
        let (lo, hi, off) = match side {
            Side::A => (0, self.na, 0),
            Side::B => (self.na, self.n, NODES),
        };
        if lo == hi {
            return None;
        }
        let mut f0 = Vec3::zeros();
        let mut m = Vec3::zeros();
        for i in lo..hi {
            let l = self.idx[i] - off;
            if l == 0 {
                f0 = g[i];
            } else {
                m += d[l - 1].cross(&g[i]);
            }
        }
        Some([f0.x, f0.y, f0.z, m.x, m.y, m.z])
    }

    /// The compact gradient spread over all eight nodes (zeros elsewhere).
    #[inline]
    pub(crate) fn expand(&self, g: &[Vec3; 2 * NODES]) -> [Vec3; 2 * NODES] {
        let mut out = [Vec3::zeros(); 2 * NODES];
        for i in 0..self.n {
            out[self.idx[i]] = g[i];
        }
        out
    }
}

#[cfg(test)]
#[path = "sparse_row_tests.rs"]
mod tests;
