//! Whether the motion of a model with massless or inertia-less bodies is still determined.
//!
//! In twist coordinates `t = (φ̇, ω)` per body (world frame) the admissible velocities at `q₀`
//! are `A t = 0` (`A = G P`, every joint row, `loops::twist_jacobian`) and the kinetic energy is
//! `½ tᵀ M t`, `M = diag(m_b I, R_b J_b R_bᵀ)`. The motion is determined when `M` is regular on
//! the admissible velocities:
//!
//! ```text
//! tᵀ M t = 0  ⇔  M t = 0  ⇔  t_b = 0 on every body with a regular M_b,  t_b = N_b y_b on the others
//! undetermined  ⇔  A_s N y = 0 for some y ≠ 0
//! ```
//!
//! (`M` is positive semi-definite; `N_b` an orthonormal basis of `null(M_b)`: the translations of
//! a massless body, the principal axes with a zero moment). `A_s N` has a column per null
//! direction of the singular bodies only (translations scaled by the characteristic length
//! `lc`, so that lengths and angles weigh alike) and the rows of their joints (each scaled to
//! unit length), so the test is a small SVD whatever the model's size: undetermined when the
//! smallest singular value is below `1e-9`. The body with the largest part of the null vector
//! is the one named. Models whose bodies all have mass and inertia skip the test.

use nalgebra::DMatrix;

use super::body::rotation;
use super::error::ModelError;
use super::joint::JointGeom;
use super::loops::twist_jacobian;
use super::runtime::{Model, ZERO_MOMENT};
use crate::math::{Mat3, Vec3};

/// Singular values below this (rows of unit length) count as zero.
const TOL: f64 = 1e-9;

/// One null direction of a singular body's mass matrix (world frame, unit).
struct NullDir {
    body: usize,
    /// Translation of the centre of mass (true) or rotation about `dir` (false).
    linear: bool,
    dir: Vec3,
}

/// The null directions of body `b` (mass `m`, inertia `j` about the centre of mass, body axes)
/// at rotation `rot` (world ← body).
fn null_dirs(b: usize, m: f64, j: &Mat3, rot: &Mat3, out: &mut Vec<NullDir>) {
    if m == 0.0 {
        for dir in [Vec3::x(), Vec3::y(), Vec3::z()] {
            out.push(NullDir {
                body: b,
                linear: true,
                dir,
            });
        }
    }
    let eig = j.symmetric_eigen();
    let big = eig.eigenvalues.amax();
    for k in 0..3 {
        if eig.eigenvalues[k] <= ZERO_MOMENT * big {
            out.push(NullDir {
                body: b,
                linear: false,
                dir: rot * eig.eigenvectors.column(k).into_owned(),
            });
        }
    }
}

/// `Ok` if the model's motion is determined at its initial configuration (module docs);
/// otherwise an error naming the body whose motion is not, and why.
///
/// # Errors
/// [`ModelError::Undetermined`] naming the body.
pub(crate) fn check(model: &Model) -> Result<(), ModelError> {
    let def = model.def();
    if !model.bodies.iter().any(|b| b.singular) {
        return Ok(());
    }
    let nb = def.bodies.len();
    let mut dirs = Vec::new();
    for (b, br) in model.bodies.iter().enumerate() {
        if br.singular {
            let rot = rotation(&model.q0[12 * b..12 * b + 12]);
            null_dirs(b, br.mass, &def.bodies[b].inertia, &rot, &mut dirs);
        }
    }
    let geoms = def
        .joints
        .iter()
        .map(|j| JointGeom::new(j, &def.bodies))
        .collect::<Result<Vec<_>, _>>()?;
    let mut a = twist_jacobian(&geoms, &model.q0, nb);
    for b in 0..nb {
        for c in 0..3 {
            a.column_mut(6 * b + c).scale_mut(model.lc);
        }
    }
    // A_s N: rows of unit length, a column per null direction; zero rows (joints away from
    // the singular bodies) are dropped; at least as many rows as columns for a full SVD
    let k = dirs.len();
    let mut rows: Vec<Vec<f64>> = Vec::new();
    for i in 0..a.nrows() {
        let norm = a.row(i).norm();
        if norm == 0.0 {
            continue;
        }
        let row: Vec<f64> = dirs
            .iter()
            .map(|d| {
                let at = 6 * d.body + if d.linear { 0 } else { 3 };
                (0..3).map(|c| a[(i, at + c)] * d.dir[c]).sum::<f64>() / norm
            })
            .collect();
        if row.iter().any(|&x| x != 0.0) {
            rows.push(row);
        }
    }
    let nr = rows.len().max(k);
    let an = DMatrix::from_fn(nr, k, |i, j| rows.get(i).map_or(0.0, |r| r[j]));
    let svd = an.svd(false, true);
    let (imin, smin) = svd.singular_values.argmin();
    if smin > TOL {
        return Ok(());
    }
    let Some(vt) = svd.v_t else {
        return Err(ModelError::Invalid("determinacy test: SVD failed".into()));
    };
    // the body carrying the largest part of the null vector
    let mut weight = vec![0.0; nb];
    for (j, d) in dirs.iter().enumerate() {
        weight[d.body] += vt[(imin, j)] * vt[(imin, j)];
    }
    let body = (0..nb)
        .max_by(|&x, &y| weight[x].total_cmp(&weight[y]))
        .unwrap_or(0);
    Err(undetermined(model, body))
}

/// The error for a body whose motion is not determined.
fn undetermined(model: &Model, b: usize) -> ModelError {
    let def = model.def();
    let name = &def.bodies[b].name;
    let what = if model.bodies[b].mass == 0.0 {
        "has no mass"
    } else {
        "has no inertia about an axis"
    };
    let free = model.tree_joint[b].is_none();
    let how = if free
        && def
            .joints
            .iter()
            .all(|j| j.child != b && j.parent != Some(b))
    {
        "it is a free body with no joint"
    } else if def.joints.iter().all(|j| j.parent != Some(b)) {
        "it is a leaf whose joint lets it move in a way that moves no body with mass"
    } else {
        "its joints let it move in a way that moves no body with mass"
    };
    ModelError::Undetermined {
        body: name.clone(),
        why: format!(
            "{what} and {how}, so its motion is not determined; give it mass and inertia, \
             make that joint fixed, or remove the body"
        ),
    }
}
