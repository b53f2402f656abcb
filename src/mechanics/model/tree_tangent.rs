//! The first-order motion of a tree along a direction `(δq, δν)` of its minimal coordinates,
//! in `f64` spatial vectors about the world origin (`spatial`): what the embedding's and the
//! read-off's tangents (`minimal`) need per column, without a dual-number pass of the
//! kinematics.
//!
//! ```text
//! S_k = (ω_k, u_k − ω_k × p_k)           rate k's twist about the origin (Motion::cols)
//! V_b = (ω_b, v_b − ω_b × o_b)           body b's twist about the origin, at ν
//! Z_b = Z_p + Σ_{k own} S_k δq_k          body b's displacement along δq (Z_ground = 0)
//! δS_k = Z_k⁻ × S_k,   Z_k⁻ = Z_p + Σ_{j ∈ μ(k)} S_j δq_j
//! δV_b = δV_p + Σ_{k own} (δS_k ν_k + S_k δν_k)
//! a point x of body b moves by Z^v + Z^ω × x, an axis d of it by Z^ω × d
//! ```
//!
//! `μ(k)`, the body's own rates whose motion carries rate `k`'s axis: the earlier rates of the
//! same joint (a universal joint's second axis, a planar joint's turn after its slides), every
//! rate of a spherical joint (its rate axes are fixed in the child), a free body's translations
//! for its turns (its turn axes are world axes through its origin). These are the derivatives
//! at the rotation vectors' zero, where the minimal coordinates are evaluated
//! (`tree_dynamics`).
//!
//! Cost: O(n) per direction.

use super::super::spatial::{cross_m, join, V6};
use super::{Coord, JointType, TreeDynamics};
use crate::math::{Mat3, Vec3};

/// The motion of a tree at `(q, ν)` that a direction is taken about (module formulas).
pub(crate) struct Frames {
    /// `S_k` per rate.
    pub s: Vec<V6>,
    /// `V_b` per body.
    pub v: Vec<V6>,
    /// Centre of mass per body (world, m).
    pub com: Vec<Vec3>,
    /// Rotation world ← body per body.
    pub r: Vec<Mat3>,
    /// Inertia about the centre of mass, world axes, per body (kg·m²).
    pub inertia: Vec<Mat3>,
    /// Per body in tree order: the body, its own rates and the body it hangs on.
    links: Vec<(usize, std::ops::Range<usize>, Option<usize>)>,
    /// `μ(k)` per rate.
    carried: Vec<std::ops::Range<usize>>,
    /// The body each rate moves.
    pub body: Vec<usize>,
}

/// A direction's displacements and twist changes (module formulas).
pub(crate) struct Along {
    /// `Z_b` per body.
    pub z: Vec<V6>,
    /// `δV_b` per body.
    pub dv: Vec<V6>,
    /// `δS_k` per rate.
    pub ds: Vec<V6>,
}

impl Along {
    /// Zeros for `nb` bodies and `n` rates.
    pub fn new(nb: usize, n: usize) -> Self {
        Self {
            z: vec![V6::zeros(); nb],
            dv: vec![V6::zeros(); nb],
            ds: vec![V6::zeros(); n],
        }
    }
}

impl TreeDynamics {
    /// The frames of the tree at `(q, ν)` (module formulas).
    pub(crate) fn frames(&self, q: &[f64], nu: &[f64]) -> Frames {
        let m = self.motion(q, nu, None);
        let nb = self.mass.len();
        let mut out = Frames {
            s: m.cols
                .iter()
                .map(|(w, u, p)| join(w, &(u - w.cross(p))))
                .collect(),
            v: Vec::with_capacity(nb),
            com: Vec::with_capacity(nb),
            r: m.r.clone(),
            inertia: Vec::with_capacity(nb),
            links: self
                .order
                .iter()
                .map(|&b| {
                    let (own, parent) = self.own_dofs(b);
                    (b, own, parent)
                })
                .collect(),
            carried: (0..self.coords.len()).map(|k| self.carried_by(k)).collect(),
            body: (0..self.coords.len()).map(|k| self.body_of(k)).collect(),
        };
        for b in 0..nb {
            out.v.push(join(&m.w[b], &(m.v[b] - m.w[b].cross(&m.o[b]))));
            out.com.push(self.com_of(&m, b).0);
            out.inertia.push(self.inertia_world(&m, b));
        }
        out
    }

    /// The rates `μ(k)` whose motion carries rate `k`'s axis (module docs), as a range.
    fn carried_by(&self, k: usize) -> std::ops::Range<usize> {
        match self.coords[k] {
            Coord::Free { i, .. } => k - i..k - i + i.min(3),
            Coord::Joint { joint, k: kk } => {
                let jd = self.joints[joint].as_ref().expect("tree joint");
                if jd.kind == JointType::Spherical {
                    jd.at..jd.at + 3
                } else {
                    jd.at..jd.at + kk
                }
            }
        }
    }

    /// `Z_b`, `δV_b` and `δS_k` along `(δq, δν)` at `fr` and the rates `nu` into `out`
    /// (module formulas).
    pub(crate) fn along(&self, fr: &Frames, nu: &[f64], dq: &[f64], dnu: &[f64], out: &mut Along) {
        for (b, own, parent) in &fr.links {
            let (zp, dvp) = parent.map_or((V6::zeros(), V6::zeros()), |p| (out.z[p], out.dv[p]));
            let (mut z, mut dv) = (zp, dvp);
            for k in own.clone() {
                let mut zm = zp;
                for j in fr.carried[k].clone() {
                    zm += fr.s[j] * dq[j];
                }
                let ds = cross_m(&zm, &fr.s[k]);
                out.ds[k] = ds;
                dv += ds * nu[k] + fr.s[k] * dnu[k];
                z += fr.s[k] * dq[k];
            }
            out.z[*b] = z;
            out.dv[*b] = dv;
        }
    }
}

impl Frames {
    /// Each body's entry of `x` replaced by the sum over its subtree.
    pub(crate) fn subtree_sums(&self, x: &mut [V6]) {
        for (b, _, parent) in self.links.iter().rev() {
            if let Some(p) = *parent {
                let xb = x[*b];
                x[p] += xb;
            }
        }
    }
}
