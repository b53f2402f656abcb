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
//! unit length), so the test is a small SVD whatever the model's size. Models whose bodies all
//! have mass and inertia skip it.
//!
//! **Determined to round-off only.** The smallest singular value `σ` of `A_s N` is how far the
//! softest motion of the singular bodies is from moving no mass: the admissible motion nearest
//! to it moves bodies with mass by `O(σ)` (in units of the characteristic length per radian), so
//! its kinetic energy is `≈ σ²` of the model's own scale (`m lc²` per unit rate). Below
//! `σ = 1e-9` the motion is not determined at all. Below `σ = 1e-6` — a kinetic energy under
//! 1e-12 of the model's scale, within 1e4 of double precision's round-off — the iteration matrix
//! is singular to round-off, and a step's Newton iteration cannot resolve that motion (a
//! point-mass head whose centre lies on the neck axis only as far as an angle written `1.5708`
//! puts it: `σ ≈ 4e-7`). Both are refused, naming the bodies that carry the motion (those
//! with at least 1 % of the singular vector) and their joints. A run that later meets such a
//! configuration (the singular set of a chain of massless links moves with the joints) gets the
//! same diagnosis in its step failure ([`diagnose`]).

use nalgebra::DMatrix;

use super::body::rotation;
use super::error::ModelError;
use super::joint::JointGeom;
use super::loops::twist_jacobian;
use super::runtime::{Model, ZERO_MOMENT};
use crate::math::{Mat3, Vec3};

/// `σ` at or below this: the motion is not determined (rows of unit length).
const UNDETERMINED: f64 = 1e-9;
/// `σ` below this: determined only to round-off (kinetic energy of the softest motion below
/// 1e-12 of the model's scale); refused at set-up.
const ROUND_OFF: f64 = 1e-6;
/// `σ` below this is named in the message of a failed step.
const DIAGNOSE: f64 = 1e-3;
/// A body carrying at least this part of the softest motion is named.
const NAMED: f64 = 1e-2;

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

/// The softest motion of the singular bodies at a configuration.
struct Softest {
    /// Smallest singular value of `A_s N` (module docs).
    sigma: f64,
    /// The bodies carrying at least [`NAMED`] of it, the largest part first.
    bodies: Vec<usize>,
}

/// The softest motion of the singular bodies at `q` (12 per body); `None` if no body is
/// singular.
fn softest(model: &Model, q: &[f64]) -> Result<Option<Softest>, ModelError> {
    let def = model.def();
    if !model.bodies.iter().any(|b| b.singular) {
        return Ok(None);
    }
    let nb = def.bodies.len();
    let mut dirs = Vec::new();
    for (b, br) in model.bodies.iter().enumerate() {
        if br.singular {
            let rot = rotation(&q[12 * b..12 * b + 12]);
            null_dirs(b, br.mass, &def.bodies[b].inertia, &rot, &mut dirs);
        }
    }
    // only the joints of singular bodies have rows that touch their null directions
    let singular = |b: Option<usize>| b.is_some_and(|b| model.bodies[b].singular);
    let geoms = def
        .joints
        .iter()
        .filter(|j| singular(Some(j.child)) || singular(j.parent))
        .map(|j| JointGeom::new(j, &def.bodies))
        .collect::<Result<Vec<_>, _>>()?;
    let mut a = twist_jacobian(&geoms, q, nb);
    for b in 0..nb {
        for c in 0..3 {
            a.column_mut(6 * b + c).scale_mut(model.lc);
        }
    }
    // A_s N: rows of unit length, a column per null direction; zero rows are dropped; at least
    // as many rows as columns for a full SVD
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
    let (imin, sigma) = svd.singular_values.argmin();
    let Some(vt) = svd.v_t else {
        return Err(ModelError::Invalid("determinacy test: SVD failed".into()));
    };
    let mut weight = vec![0.0; nb];
    for (j, d) in dirs.iter().enumerate() {
        weight[d.body] += vt[(imin, j)] * vt[(imin, j)];
    }
    let mut bodies: Vec<usize> = (0..nb).filter(|&b| weight[b] >= NAMED).collect();
    bodies.sort_by(|&x, &y| weight[y].total_cmp(&weight[x]));
    Ok(Some(Softest { sigma, bodies }))
}

/// `Ok` if the model's motion is determined, beyond round-off, at its initial configuration
/// (module docs); otherwise an error naming the bodies and joints whose motion is not.
///
/// # Errors
/// [`ModelError::Undetermined`] naming the body.
pub(crate) fn check(model: &Model) -> Result<(), ModelError> {
    let Some(soft) = softest(model, &model.q0)? else {
        return Ok(());
    };
    if soft.sigma >= ROUND_OFF {
        return Ok(());
    }
    let body = soft.bodies.first().copied().unwrap_or(0);
    Err(undetermined(model, body, &soft))
}

/// A diagnosis for a step that failed at configuration `q`: if the motion is nearly
/// undetermined there (`σ` below 1e-3), the bodies and joints that carry the softest motion,
/// the estimate of its kinetic energy relative to the model's scale, and a hint.
#[must_use]
pub(crate) fn diagnose(model: &Model, q: &[f64]) -> Option<String> {
    let soft = softest(model, q).ok()??;
    if soft.sigma >= DIAGNOSE || soft.bodies.is_empty() {
        return None;
    }
    Some(format!(
        "the motion is nearly undetermined here: {} {} (kinetic energy of the softest motion \
         ≈ {:.0e} of the model's scale, σ = {:.1e}); give {} mass and inertia, or a smaller \
         max_step if the configuration only passes near this",
        involved(model, &soft.bodies),
        lacks(model, &soft.bodies),
        soft.sigma * soft.sigma,
        soft.sigma,
        quoted(model, &soft.bodies),
    ))
}

/// `'a', 'b'` of the bodies.
fn quoted(model: &Model, bodies: &[usize]) -> String {
    let names: Vec<String> = bodies
        .iter()
        .map(|&b| format!("'{}'", model.def().bodies[b].name))
        .collect();
    names.join(", ")
}

/// "bodies 'a', 'b' on joints 'j', 'k'".
fn involved(model: &Model, bodies: &[usize]) -> String {
    let def = model.def();
    let joints: Vec<String> = def
        .joints
        .iter()
        .filter(|j| bodies.contains(&j.child) || j.parent.is_some_and(|p| bodies.contains(&p)))
        .map(|j| format!("'{}'", j.name))
        .collect();
    let on = match joints.len() {
        0 => String::new(),
        1 => format!(" on joint {}", joints[0]),
        _ => format!(" on joints {}", joints.join(", ")),
    };
    format!(
        "{} {}{on}",
        if bodies.len() == 1 { "body" } else { "bodies" },
        quoted(model, bodies),
    )
}

/// What the bodies lack: "(no mass)", "(no inertia about an axis)" each.
fn lacks(model: &Model, bodies: &[usize]) -> String {
    let what: Vec<String> = bodies
        .iter()
        .map(|&b| {
            format!(
                "'{}' {}",
                model.def().bodies[b].name,
                if model.bodies[b].mass == 0.0 {
                    "has no mass"
                } else {
                    "has no inertia about an axis"
                }
            )
        })
        .collect();
    format!("({})", what.join(", "))
}

/// The error for a body whose motion is not determined (or only to round-off).
fn undetermined(model: &Model, b: usize, soft: &Softest) -> ModelError {
    let def = model.def();
    let what = if model.bodies[b].mass == 0.0 {
        "has no mass"
    } else {
        "has no inertia about an axis"
    };
    let free = model.tree_joint[b].is_none();
    let lonely = def
        .joints
        .iter()
        .all(|j| j.child != b && j.parent != Some(b));
    // a free body has no joint of its own to make fixed: it can be welded to the world
    let (how, fix) = if free && lonely {
        (
            "it is a free body with no joint",
            "give it mass and inertia, weld it to the world or to a body with mass (a fixed \
             joint), or remove the body",
        )
    } else if free {
        (
            "it is a free body (the root of its tree) that its joints let move in a way that \
             moves no body with mass",
            "give it mass and inertia, or weld it to the world (a fixed joint)",
        )
    } else if def.joints.iter().all(|j| j.parent != Some(b)) {
        (
            "it is a leaf whose joint lets it move in a way that moves no body with mass",
            "give it mass and inertia, make that joint fixed, or remove the body",
        )
    } else {
        (
            "its joints let it move in a way that moves no body with mass",
            "give it mass and inertia, make that joint fixed, or remove the body",
        )
    };
    let others = if soft.bodies.len() > 1 || !lonely {
        format!(
            " (the motion is carried by {})",
            involved(model, &soft.bodies)
        )
    } else {
        String::new()
    };
    let why = if soft.sigma <= UNDETERMINED {
        format!("{what} and {how}, so its motion is not determined{others}; {fix}")
    } else {
        format!(
            "{what} and its joints let it move in a way that moves the bodies with mass only \
             by {:.1e} of its own motion{others}: its motion is determined only to round-off \
             (the kinetic energy of that motion is ≈ {:.0e} of the model's scale, below the 1e-12 \
             that double precision resolves), and no step could resolve it. A centre of mass or \
             an axis meant to lie exactly on another (an angle written 1.5708 instead of π/2) \
             does this: write it exactly, give the body inertia, or make that joint fixed",
            soft.sigma,
            soft.sigma * soft.sigma
        )
    };
    ModelError::Undetermined {
        body: def.bodies[b].name.clone(),
        why,
    }
}
