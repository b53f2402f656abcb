//! Momenta between bodies in contact, exact at any Newton tolerance.
//!
//! The Jacobian of a stage leaves out the coupling of two bodies through a contact feature
//! (`step::contact`), so where bodies press on each other Newton converges linearly and stops
//! at the tolerance; the accepted iterate then carries a residual `r` whose sums are momentum
//! errors. With `a = Δq − h vₙ` per node (`v_{n+1} = vₙ + 2a/h`) and `F_b = m_b g + f_b` the
//! external forces (gravity and body-force inputs):
//!
//! ```text
//! D_p = Σ_b m_b a_φ,b − (h²/2) Σ_b F_b                       = (h/2)(p_{n+1} − pₙ − h ΣF)
//! D_L = Σ_b (φ̄_b × m_b a_φ,b + Σ_ij E_ij d̄ᵢ × a_dⱼ)
//!       − (h²/2) Σ_b φ̄_b × F_b                               = (h/2)(L_{n+1} − Lₙ − h Σ φ̄×F)
//! ```
//!
//! (`L` of the nodes: `Σ φ × m φ̇ + Σ_ij E_ij dᵢ × ḋⱼ`; the midpoint's `Δq = (h/2)(vₙ + v_{n+1})`
//! makes `L_{n+1} − Lₙ = (2/h) Σ q̄ × M a` exactly, since `E` is symmetric.) Every internal force
//! (contact features, joints, their loads) cancels from both sums at any iterate. Where the
//! momenta are balances of the model — no ground, no joint to the world, contact between
//! bodies — the end of the stage is moved rigidly as a whole until both defects vanish:
//!
//! ```text
//! φ_{n+1} += δ,  δ = −D_p / M                                 (exact in one pass)
//! q_{n+1} ← c + exp(δθ)(q_{n+1} − c),  δθ = −I_c⁻¹ D_L         (c the end's centre of mass,
//!                                                              I_c the inertia about it)
//! ```
//!
//! A rigid motion of the whole leaves every joint row and every contact invariant at the end
//! unchanged, so the correction moves the iterate by no more than its distance to the solution
//! (the tolerance); the rotation's `δθ` contracts by about `|a|/size` per pass.

use super::work::{Held, Work};
use crate::math::{Mat3, Vec3};
use crate::mechanics::model::constraint::{body_nodes, read3, write3};
use crate::mechanics::model::kernels::expm1_so3;
use crate::mechanics::model::runtime::Model;

/// Most passes of the correction (the translation is exact in the first; the rotation
/// contracts by about `|a|/size` per pass: six reach round-off from a loose tolerance of 1e-6).
const PASSES: usize = 8;

/// A turn below this ends the passes (rad): below the round-off of a director.
const TURN_FLOOR: f64 = 1e-18;

/// Whether the model's momenta are balances that contact between bodies can spoil: it has
/// body–body features, no ground and no joint to the world.
#[must_use]
pub(crate) fn applies(model: &Model) -> bool {
    !model.contact.features.is_empty()
        && model.contact.ground.is_none()
        && model.joints.iter().all(|j| j.parent.is_some())
}

/// The defects `(D_p, D_L)` of the iterate in `ws` (module formulas), with `ws.acc` and
/// `ws.qbar` refreshed.
fn defects(model: &Model, ws: &mut Work, held: &Held, h: f64) -> (Vec3, Vec3) {
    let hh = 0.5 * h * h;
    let g = model.def().gravity;
    ws.set_midpoint();
    let (mut dp, mut dl) = (Vec3::zeros(), Vec3::zeros());
    for (b, br) in model.bodies.iter().enumerate() {
        ws.set_acc(b);
        let a = body_nodes(&ws.acc, b);
        let qb = body_nodes(&ws.qbar, b);
        let lin = a[0] * br.mass - g * (hh * br.mass);
        dp += lin;
        dl += qb[0].cross(&lin);
        for i in 0..3 {
            for j in 0..3 {
                dl += qb[i + 1].cross(&a[j + 1]) * br.e[(i, j)];
            }
        }
    }
    for &(b, at) in &model.body_forces {
        let f = Vec3::new(held.inputs[at], held.inputs[at + 1], held.inputs[at + 2]) * hh;
        dp -= f;
        dl -= read3(&ws.qbar, 12 * b).cross(&f);
    }
    (dp, dl)
}

/// Moves the stage's end `ws.q` (and `ws.dq`) rigidly as a whole so that the defects vanish
/// (module docs); a no-op unless [`applies`].
pub(crate) fn balance(model: &Model, ws: &mut Work, held: &Held, h: f64) {
    if !applies(model) {
        return;
    }
    let total: f64 = model.bodies.iter().map(|b| b.mass).sum();
    if total <= 0.0 {
        return;
    }
    for _ in 0..PASSES {
        let (dp, _) = defects(model, ws, held, h);
        let shift = -dp / total;
        for b in 0..model.bodies.len() {
            let at = 12 * b;
            let q = read3(&ws.q, at) + shift;
            write3(&mut ws.q, at, &q);
            let d = read3(&ws.dq, at) + shift;
            write3(&mut ws.dq, at, &d);
        }
        let (_, dl) = defects(model, ws, held, h);
        // the end's centre of mass and inertia about it
        let mut c = Vec3::zeros();
        for (b, br) in model.bodies.iter().enumerate() {
            c += read3(&ws.q, 12 * b) * br.mass;
        }
        c /= total;
        let mut inertia = Mat3::zeros();
        for (b, br) in model.bodies.iter().enumerate() {
            let q = body_nodes(&ws.q, b);
            let x = q[0] - c;
            inertia += (Mat3::identity() * x.norm_squared() - x * x.transpose()) * br.mass;
            // J = tr(E) I − E in body axes, R J Rᵀ in the world
            let r = Mat3::from_columns(&[q[1], q[2], q[3]]);
            let j = Mat3::identity() * br.e.trace() - br.e;
            inertia += r * j * r.transpose();
        }
        let Some(inv) = inertia.try_inverse() else {
            return;
        };
        let turn = -(inv * dl);
        if !turn.iter().all(|x| x.is_finite()) {
            return;
        }
        if turn.norm() <= TURN_FLOOR {
            return;
        }
        let k = expm1_so3(&turn);
        for b in 0..model.bodies.len() {
            for node in 0..4 {
                let at = 12 * b + 3 * node;
                let x = read3(&ws.q, at);
                let dx = if node == 0 { k * (x - c) } else { k * x };
                write3(&mut ws.q, at, &(x + dx));
                let d = read3(&ws.dq, at) + dx;
                write3(&mut ws.dq, at, &d);
            }
        }
    }
}
