//! The law of one ground contact point over a stage (`contact`'s module formulas), in `f64`
//! for the step or in a dual number for its tangent (`contact_tangent`):
//!
//! ```text
//! x = φ + Σ Xᵢ dᵢ,  g = n·x − h₀ − r,  x₀ = −g(q₀),  x₁ = −(g(q₀) + n·Δx)   (penetrations)
//! f = normal(x₀, x₁)                                    (`model::contact_law`)
//! X_c = X − r D̄ᵀ n,  u = P_t (Δφ + ΔD X_c)              (the contact point, its slip)
//! F = friction(s₀, u; c_t = k d p̄, C = μ f)
//! ```

use crate::math::Vec3;
use crate::mechanics::model::contact::GroundPoint;
use crate::mechanics::model::contact_law::{friction, normal, Friction, Normal};
use crate::mechanics::model::scalar::{c, cv, Real};
use nalgebra::{Matrix3, Vector3};

/// `Σᵢ wᵢ dᵢ` over the directors of `q` (a body-axes vector in world axes).
pub(super) fn world<T: Real>(q: &[Vector3<T>; 4], w: &Vector3<T>) -> Vector3<T> {
    q[1] * w.x + q[2] * w.y + q[3] * w.z
}

/// One ground point's step quantities, in `f64` or a dual number (`contact_tangent`).
pub(super) struct GroundStep<T: Real = f64> {
    pub(super) normal: Normal<T>,
    pub(super) friction: Friction<T>,
    /// The contact point, body axes relative to the centre of mass.
    pub(super) xc: Vector3<T>,
    /// Penetrations at the stage's start and end.
    pub(super) x0: T,
    pub(super) x1: T,
}

/// The laws of ground point `p` (bristle `s0`) over a stage of size `h` from the body's nodes
/// `q0` by the increment `dq`, midpoint `qbar` (module formulas).
pub(super) fn ground_law<T: Real>(
    p: &GroundPoint,
    normal_dir: &Vec3,
    height: f64,
    [q0, dq, qbar]: [&[Vector3<T>; 4]; 3],
    s0: Vector3<T>,
    h: f64,
) -> GroundStep<T> {
    let n = cv::<T>(normal_dir);
    let x = cv::<T>(&p.x);
    let g0 = n.dot(&(q0[0] + world(q0, &x))) - c(height) - c(p.radius);
    let dx = dq[0] + world(dq, &x);
    let (x0, x1) = (-g0, -(g0 + n.dot(&dx)));
    let law = p.law;
    let nrm = normal(law.stiffness, law.damping, x0, x1, h);
    // the contact point X − r D̄ᵀn, fixed in the body over the stage
    let dbar = Matrix3::from_columns(&[qbar[1], qbar[2], qbar[3]]);
    let xc = x - dbar.transpose() * n * c::<T>(p.radius);
    let dxc = dq[0] + world(dq, &xc);
    let u = dxc - n * n.dot(&dxc);
    let ct = nrm.mean * c(law.stiffness * law.damping);
    let fr = friction(law.stiffness, ct, nrm.force * c(law.friction), s0, u, h);
    GroundStep {
        normal: nrm,
        friction: fr,
        xc,
        x0,
        x1,
    }
}
