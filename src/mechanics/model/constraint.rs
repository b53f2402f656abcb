//! Quadratic constraint rows over two bodies: the one primitive every joint is built from.
//!
//! A body's coordinates are four vector *nodes* `q = [φ, d1, d2, d3]` (centre of mass and the
//! three directors, world frame, 12 numbers). Every point and axis fixed in a body is linear in
//! its nodes: a material point `X` (body axes, relative to the centre of mass) is `φ + Xᵢ dᵢ`, a
//! body-fixed axis `a` is `aᵢ dᵢ`. A joint acts on a parent `A` (or the world, whose nodes are
//! constants) and a child `B`; every joint constraint of theory.md §3.2 is then a [`DotRow`]
//!
//! ```text
//! g(q) = u(q) · w(q) − c,   u = Σₖ αᴬₖ qᴬₖ + Σₖ αᴮₖ qᴮₖ + u₀,   w = Σₖ βᴬₖ qᴬₖ + Σₖ βᴮₖ qᴮₖ + w₀
//! ```
//!
//! quadratic in q with a constant Hessian `H = (αβᵀ + βαᵀ) ⊗ I₃` over the eight nodes. Hence the
//! midpoint identity `g(q₁) − g(q₀) = ∇g(½(q₀+q₁))·(q₁ − q₀)` holds exactly, which is what makes
//! the energy–momentum scheme conserve energy (theory.md §1.4, §4.3). The same form gives the
//! joint *invariants* (a slide `s = r·a₃`, a planar offset `x = r·a₁`) whose midpoint gradients
//! are exact, momentum-preserving discrete gradients (theory.md §4.2).

use crate::math::Vec3;

/// Number of vector nodes of one body (`φ, d1, d2, d3`).
pub const NODES: usize = 4;

/// A world-frame vector that is linear in the nodes of bodies A and B.
///
/// `v = Σₖ a[k]·qᴬₖ + Σₖ b[k]·qᴮₖ + c`. When A is the world its nodes are constants and are
/// folded into `c` (then `a` is zero).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LinVec {
    /// Coefficients of A's nodes `[φ, d1, d2, d3]`.
    pub a: [f64; NODES],
    /// Coefficients of B's nodes `[φ, d1, d2, d3]`.
    pub b: [f64; NODES],
    /// Constant part, world frame.
    pub c: Vec3,
}

/// The nodes of one body, `[φ, d1, d2, d3]`, world frame.
pub type Nodes = [Vec3; NODES];

/// Reads the four nodes of a body from its 12 coordinates.
#[must_use]
pub fn nodes(q: &[f64]) -> Nodes {
    // one bounds check for the twelve entries
    let q = &q[..12];
    [
        Vec3::new(q[0], q[1], q[2]),
        Vec3::new(q[3], q[4], q[5]),
        Vec3::new(q[6], q[7], q[8]),
        Vec3::new(q[9], q[10], q[11]),
    ]
}

/// Nodes of body `b` of the flat vector `x`.
#[inline]
pub(crate) fn body_nodes(x: &[f64], b: usize) -> Nodes {
    nodes(&x[12 * b..12 * b + 12])
}

/// Writes `v` to `x[at..at + 3]`.
#[inline]
pub(crate) fn write3(x: &mut [f64], at: usize, v: &Vec3) {
    // one bounds check for the three entries
    let s = &mut x[at..at + 3];
    s[0] = v.x;
    s[1] = v.y;
    s[2] = v.z;
}

/// Reads `x[at..at + 3]`.
#[must_use]
#[inline]
pub(crate) fn read3(x: &[f64], at: usize) -> Vec3 {
    let s = &x[at..at + 3];
    Vec3::new(s[0], s[1], s[2])
}

impl LinVec {
    /// A constant vector.
    #[must_use]
    pub fn constant(c: Vec3) -> Self {
        Self {
            c,
            ..Self::default()
        }
    }

    /// A point fixed in body A at `x` (body axes, relative to A's centre of mass).
    #[must_use]
    pub fn point_a(x: &Vec3) -> Self {
        Self {
            a: [1.0, x.x, x.y, x.z],
            ..Self::default()
        }
    }

    /// A point fixed in body B at `x` (body axes, relative to B's centre of mass).
    #[must_use]
    pub fn point_b(x: &Vec3) -> Self {
        Self {
            b: [1.0, x.x, x.y, x.z],
            ..Self::default()
        }
    }

    /// An axis fixed in body A with body-axes components `v`.
    #[must_use]
    pub fn axis_a(v: &Vec3) -> Self {
        Self {
            a: [0.0, v.x, v.y, v.z],
            ..Self::default()
        }
    }

    /// An axis fixed in body B with body-axes components `v`.
    #[must_use]
    pub fn axis_b(v: &Vec3) -> Self {
        Self {
            b: [0.0, v.x, v.y, v.z],
            ..Self::default()
        }
    }

    /// `self − other`.
    #[must_use]
    pub fn sub(&self, other: &Self) -> Self {
        let mut out = *self;
        for k in 0..NODES {
            out.a[k] -= other.a[k];
            out.b[k] -= other.b[k];
        }
        out.c -= other.c;
        out
    }

    /// Value for the nodes of A (ignored when `a` is zero) and B.
    #[must_use]
    #[inline]
    pub fn eval(&self, qa: &Nodes, qb: &Nodes) -> Vec3 {
        // most vectors are fixed in one body (axes, points): the other half is skipped (the
        // same value: its terms are exact zeros)
        let mut v = self.c;
        let zero = [0.0; NODES];
        if self.b == zero {
            for (x, c) in qa.iter().zip(&self.a) {
                v += x * *c;
            }
        } else if self.a == zero {
            for (x, c) in qb.iter().zip(&self.b) {
                v += x * *c;
            }
        } else {
            for k in 0..NODES {
                v += qa[k] * self.a[k] + qb[k] * self.b[k];
            }
        }
        v
    }

    /// Coefficients over the eight nodes `[A φ, A d1, A d2, A d3, B φ, B d1, B d2, B d3]`.
    #[must_use]
    pub fn coeffs(&self) -> [f64; 2 * NODES] {
        let mut out = [0.0; 2 * NODES];
        out[..NODES].copy_from_slice(&self.a);
        out[NODES..].copy_from_slice(&self.b);
        out
    }
}

/// One quadratic constraint (or invariant) row `g = u·w − c`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DotRow {
    /// First factor.
    pub u: LinVec,
    /// Second factor.
    pub w: LinVec,
    /// Constant subtracted, so that `g = 0` on the constraint manifold.
    pub offset: f64,
}

impl DotRow {
    /// The component of `u` along the fixed world direction `e`: `g = u·e` (linear row).
    #[must_use]
    pub fn component(u: LinVec, e: Vec3) -> Self {
        Self {
            u,
            w: LinVec::constant(e),
            offset: 0.0,
        }
    }

    /// `g = u·w − offset`.
    #[must_use]
    pub fn new(u: LinVec, w: LinVec, offset: f64) -> Self {
        Self { u, w, offset }
    }

    /// Value `g(q)`.
    #[must_use]
    #[inline]
    pub fn eval(&self, qa: &Nodes, qb: &Nodes) -> f64 {
        self.u.eval(qa, qb).dot(&self.w.eval(qa, qb)) - self.offset
    }

    /// Gradient: `out[n]` is `∂g/∂(node n)` over the eight nodes `[A…, B…]`, world frame.
    /// Evaluate at the midpoint configuration for the exact discrete derivative.
    pub fn gradient(&self, qa: &Nodes, qb: &Nodes, out: &mut [Vec3; 2 * NODES]) {
        let u = self.u.eval(qa, qb);
        let w = self.w.eval(qa, qb);
        let (al, be) = (self.u.coeffs(), self.w.coeffs());
        for n in 0..2 * NODES {
            out[n] = w * al[n] + u * be[n];
        }
    }

    /// The constant Hessian as an 8×8 node matrix `S` with `H = S ⊗ I₃`:
    /// `S[n][m] = αₙβₘ + βₙαₘ`.
    #[must_use]
    pub fn hessian(&self) -> [[f64; 2 * NODES]; 2 * NODES] {
        let (al, be) = (self.u.coeffs(), self.w.coeffs());
        let mut s = [[0.0; 2 * NODES]; 2 * NODES];
        for n in 0..2 * NODES {
            for m in 0..2 * NODES {
                s[n][m] = al[n] * be[m] + be[n] * al[m];
            }
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> (Nodes, Nodes, Nodes, Nodes) {
        let v = |x: f64, y: f64, z: f64| Vec3::new(x, y, z);
        let qa0 = [
            v(0.1, 0.2, 0.3),
            v(0.9, 0.1, 0.0),
            v(-0.1, 1.0, 0.2),
            v(0.0, -0.2, 1.1),
        ];
        let qb0 = [
            v(1.0, -0.5, 0.3),
            v(0.2, 0.9, 0.1),
            v(1.0, 0.0, 0.3),
            v(0.3, 0.1, -0.8),
        ];
        let qa1 = [
            v(0.3, 0.1, 0.2),
            v(0.7, 0.4, 0.1),
            v(-0.3, 0.9, 0.0),
            v(0.1, -0.1, 1.0),
        ];
        let qb1 = [
            v(0.8, -0.3, 0.6),
            v(0.4, 0.7, 0.2),
            v(0.9, -0.2, 0.5),
            v(0.2, 0.3, -0.9),
        ];
        (qa0, qb0, qa1, qb1)
    }

    fn row() -> DotRow {
        let r = LinVec::point_b(&Vec3::new(0.2, -0.1, 0.4))
            .sub(&LinVec::point_a(&Vec3::new(-0.3, 0.5, 0.1)));
        let a3 = LinVec::axis_a(&Vec3::new(0.1, 0.2, 0.97));
        DotRow::new(r, a3, 0.25)
    }

    /// g(q₁) − g(q₀) = ∇g(q̄)·Δq exactly for every DotRow (theory.md §1.4).
    #[test]
    fn midpoint_identity_is_exact() {
        let (qa0, qb0, qa1, qb1) = sample();
        let g = row();
        let mid = |x: &Nodes, y: &Nodes| -> Nodes { std::array::from_fn(|k| (x[k] + y[k]) * 0.5) };
        let (qam, qbm) = (mid(&qa0, &qa1), mid(&qb0, &qb1));
        let mut grad = [Vec3::zeros(); 8];
        g.gradient(&qam, &qbm, &mut grad);
        let mut lin = 0.0;
        for k in 0..NODES {
            lin += grad[k].dot(&(qa1[k] - qa0[k])) + grad[k + NODES].dot(&(qb1[k] - qb0[k]));
        }
        let diff = g.eval(&qa1, &qb1) - g.eval(&qa0, &qb0);
        assert!((diff - lin).abs() < 1e-15, "{diff} vs {lin}");
    }

    /// The Hessian is the derivative of the gradient (finite differences).
    #[test]
    fn hessian_matches_gradient_differences() {
        let (qa, qb, _, _) = sample();
        let g = row();
        let s = g.hessian();
        let mut g0 = [Vec3::zeros(); 8];
        g.gradient(&qa, &qb, &mut g0);
        for m in 0..8 {
            for c in 0..3 {
                let (mut qa1, mut qb1) = (qa, qb);
                if m < NODES {
                    qa1[m][c] += 1e-6;
                } else {
                    qb1[m - NODES][c] += 1e-6;
                }
                let mut g1 = [Vec3::zeros(); 8];
                g.gradient(&qa1, &qb1, &mut g1);
                for n in 0..8 {
                    let fd = (g1[n] - g0[n]) / 1e-6;
                    let mut exact = Vec3::zeros();
                    exact[c] = s[n][m];
                    assert!((fd - exact).norm() < 1e-8);
                }
            }
        }
    }
}
