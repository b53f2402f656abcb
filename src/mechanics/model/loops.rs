//! Loop-closing joints at the start: position check and velocity projection (interface.md §2:
//! "initial rates that violate a loop's velocity constraints are projected onto them, the least
//! change in kinetic energy").
//!
//! The projection works in twist coordinates `t = (φ̇, ω)` per body (6 numbers, world frame,
//! φ̇ the centre-of-mass velocity), where `q̇ = P(q) t` (`ḋ_i = ω × d_i`) and the kinetic
//! energy is `½ tᵀ M_t t`, `M_t = diag(m I, R J Rᵀ)`. It solves
//! `min ½ Δtᵀ M_t Δt` subject to `G(q0) P(q0) (t0 + Δt) = 0` over the rows of **all** joints
//! (tree rows are already satisfied by `t0`, so they only keep the tree intact), with an SVD
//! pseudo-inverse so that redundant loop rows do no harm.
//!
//! [`project_loop_velocities`] forms that dense problem (O(N³)) and is the reference. The model
//! set-up only asks [`loop_velocities_violated`] (the loop rows' Jacobian alone) and, when the
//! rates violate a loop, solves the same projection on the assembled model with the O(N)
//! bordered tree solve of the outputs' velocity projection (`projection`; redundant rows are
//! dropped there, so the system is regular).

use nalgebra::{DMatrix, DVector};

use super::body::{angular_velocity, rotation, BodyInertia};
use super::constraint::NODES;
use super::def::ModelDef;
use super::error::ModelError;
use super::joint::{body_nodes, JointGeom};
use crate::math::Vec3;

/// Tolerance on a loop-closing joint's position residual at the start, m or 1.
pub const LOOP_TOLERANCE: f64 = 1e-6;

/// The largest row violation of every loop-closing joint at `q` (12 per body):
/// `(joint index, residual)` in model order.
///
/// # Errors
/// [`ModelError::Invalid`] from [`JointGeom::new`].
pub fn loop_residuals(def: &ModelDef, q: &[f64]) -> Result<Vec<(usize, f64)>, ModelError> {
    let mut out = Vec::new();
    for (j, jd) in def
        .joints
        .iter()
        .enumerate()
        .filter(|(_, jd)| jd.loop_closing)
    {
        let g = JointGeom::new(jd, &def.bodies)?;
        out.push((
            j,
            g.residual(&body_nodes(q, g.parent), &body_nodes(q, Some(g.child))),
        ));
    }
    Ok(out)
}

/// Fails with [`ModelError::LoopNotClosed`] for the first loop-closing joint whose residual at
/// `q` exceeds [`LOOP_TOLERANCE`].
///
/// # Errors
/// As described, and [`ModelError::Invalid`] from [`JointGeom::new`].
pub fn check_loops(def: &ModelDef, q: &[f64]) -> Result<(), ModelError> {
    for (j, residual) in loop_residuals(def, q)? {
        if residual > LOOP_TOLERANCE || !residual.is_finite() {
            return Err(ModelError::LoopNotClosed {
                joint: def.joints[j].name.clone(),
                residual,
            });
        }
    }
    Ok(())
}

/// The twist-space gradient of each row of `g` at `q` (12 per body): `∂g/∂φ · φ̇ + ω · Σ d_k ×
/// ∂g/∂d_k` as `[∂g/∂φ, Σ d_k × ∂g/∂d_k]` for the parent (zero for the world) and the child,
/// in row order. Units m/s per (m/s, rad/s).
#[must_use]
pub(crate) fn row_twists(g: &JointGeom, q: &[f64]) -> Vec<([f64; 6], [f64; 6])> {
    let (qa, qb) = (body_nodes(q, g.parent), body_nodes(q, Some(g.child)));
    g.rows
        .iter()
        .map(|row| {
            let mut grad = [Vec3::zeros(); 2 * NODES];
            row.gradient(&qa, &qb, &mut grad);
            let side = |o: usize, nodes: &[Vec3; NODES]| {
                let m: Vec3 = (1..NODES).map(|k| nodes[k].cross(&grad[o + k])).sum();
                let f = grad[o];
                [f.x, f.y, f.z, m.x, m.y, m.z]
            };
            let pa = if g.parent.is_some() {
                side(0, &qa)
            } else {
                [0.0; 6]
            };
            (pa, side(NODES, &qb))
        })
        .collect()
}

/// The velocity Jacobian in twist coordinates, `A = G(q) P(q)` (rows: every row of every joint
/// in `geoms`, in order; columns: `[φ̇, ω]` per body). Row units m/s per (m/s, rad/s).
#[must_use]
pub fn twist_jacobian(geoms: &[JointGeom], q: &[f64], nbody: usize) -> DMatrix<f64> {
    let nrow = geoms.iter().map(|g| g.rows.len()).sum();
    let mut a = DMatrix::zeros(nrow, 6 * nbody);
    let mut i = 0;
    for g in geoms {
        for (pa, ch) in row_twists(g, q) {
            for (body, t) in [(g.parent, pa), (Some(g.child), ch)] {
                let Some(b) = body else { continue };
                for c in 0..6 {
                    a[(i, 6 * b + c)] += t[c];
                }
            }
            i += 1;
        }
    }
    a
}

/// The twists `[φ̇, ω]` (6 per body) of the nodal velocities `v` at `q` (12 per body each).
fn twists(q: &[f64], v: &[f64], n: usize) -> DVector<f64> {
    let mut t = DVector::zeros(6 * n);
    for b in 0..n {
        let (qb, vb) = (&q[12 * b..12 * b + 12], &v[12 * b..12 * b + 12]);
        let w = angular_velocity(qb, vb);
        for c in 0..3 {
            t[6 * b + c] = vb[c];
            t[6 * b + 3 + c] = w[c];
        }
    }
    t
}

/// Whether the velocities `v` (12 per body) at `q` violate the velocity constraints of the
/// loop-closing joints by more than 1e-12 relative to the largest twist component (the tree
/// joints' hold by construction of the initial state). Forms only the loop rows' Jacobian.
///
/// # Errors
/// [`ModelError::Invalid`] from [`JointGeom::new`].
pub fn loop_velocities_violated(def: &ModelDef, q: &[f64], v: &[f64]) -> Result<bool, ModelError> {
    let loop_geoms = def
        .joints
        .iter()
        .filter(|j| j.loop_closing)
        .map(|j| JointGeom::new(j, &def.bodies))
        .collect::<Result<Vec<_>, _>>()?;
    if loop_geoms.is_empty() {
        return Ok(false);
    }
    let n = def.bodies.len();
    let t0 = twists(q, v, n);
    let violation = (twist_jacobian(&loop_geoms, q, n) * &t0).amax();
    Ok(violation > 1e-12 * (1.0 + t0.amax()))
}

/// Projects the initial velocities `v` (12 per body) at `q` onto the joints' velocity
/// constraints with the least change in kinetic energy (module docs). Returns `true` when the
/// loop-closing rows were violated (by more than 1e-12 relative to the largest twist component)
/// and `v` was changed, `false` (v untouched) otherwise.
///
/// # Errors
/// [`ModelError::Invalid`] from [`JointGeom::new`] or `BodyInertia::new`.
pub fn project_loop_velocities(
    def: &ModelDef,
    q: &[f64],
    v: &mut [f64],
) -> Result<bool, ModelError> {
    if !loop_velocities_violated(def, q, v)? {
        return Ok(false);
    }
    let n = def.bodies.len();
    let geoms = def
        .joints
        .iter()
        .map(|j| JointGeom::new(j, &def.bodies))
        .collect::<Result<Vec<_>, _>>()?;
    let t0 = twists(q, v, n);
    let a = twist_jacobian(&geoms, q, n);
    let res = &a * &t0;
    // metric M_t^{-1/2} per body, then y = −pinv(A M_t^{-1/2}) A t0, Δt = M_t^{-1/2} y
    // (a massless or inertia-less body's zero moments count as 1e-12 of the model's largest, so
    // that its rates follow its joints; they are determined by them when the model is valid)
    let mut wi = DMatrix::zeros(6 * n, 6 * n);
    let m_floor = 1e-12
        * def
            .bodies
            .iter()
            .map(|b| b.mass)
            .fold(f64::MIN_POSITIVE, f64::max);
    let j_floor = 1e-12
        * def
            .bodies
            .iter()
            .map(|b| b.inertia.amax())
            .fold(f64::MIN_POSITIVE, f64::max);
    for (b, body) in def.bodies.iter().enumerate() {
        let inertia = BodyInertia::new(body)?;
        let r = rotation(&q[12 * b..12 * b + 12]);
        let eig = (r * inertia.inertia * r.transpose()).symmetric_eigen();
        let js = eig.eigenvectors
            * nalgebra::Matrix3::from_diagonal(
                &eig.eigenvalues.map(|x| 1.0 / x.max(j_floor).sqrt()),
            )
            * eig.eigenvectors.transpose();
        for c in 0..3 {
            wi[(6 * b + c, 6 * b + c)] = 1.0 / inertia.mass.max(m_floor).sqrt();
        }
        wi.view_mut((6 * b + 3, 6 * b + 3), (3, 3)).copy_from(&js);
    }
    let svd = (&a * &wi).svd(true, true);
    let eps = 1e-10 * svd.singular_values.max();
    let y = svd
        .solve(&res, eps)
        .map_err(|e| ModelError::Invalid(format!("velocity projection failed: {e}")))?;
    let t = t0 - &wi * y;
    for b in 0..n {
        let qb = &q[12 * b..12 * b + 12];
        let w = Vec3::new(t[6 * b + 3], t[6 * b + 4], t[6 * b + 5]);
        let vb = &mut v[12 * b..12 * b + 12];
        for c in 0..3 {
            vb[c] = t[6 * b + c];
        }
        for k in 0..3 {
            let d = Vec3::new(qb[3 + 3 * k], qb[4 + 3 * k], qb[5 + 3 * k]);
            vb[3 + 3 * k..6 + 3 * k].copy_from_slice(w.cross(&d).as_slice());
        }
    }
    Ok(true)
}
