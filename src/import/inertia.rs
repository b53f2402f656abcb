//! Inertials of robot-description import: parts placed in a body frame, merged into one.
//!
//! ```text
//! merged:  m = Σ mᵢ,  c = Σ mᵢ cᵢ / m,  J = Σ [J_cᵢ + mᵢ (|cᵢ − c|² I − (cᵢ − c)(cᵢ − c)ᵀ)]
//! ```

use crate::math::{Mat3, Vec3};
use crate::spec::{BodySpec, InertiaSpec};

/// One inertial in a body frame: `(mass, com, inertia about com)`.
pub(crate) type Part = (f64, Vec3, Mat3);

/// `j` with the round-off of the file's numbers removed: entries below `1e-12 · max(|J|, m·1 m²)`
/// of a tensor that is otherwise zero become zero, and principal moments negative by less than
/// that become zero (real files write `ixz="2.4e-35"` for a point mass). Anything larger is
/// left for validation to report.
pub(crate) fn clean(j: Mat3, m: f64) -> Mat3 {
    let tiny = 1e-12 * j.amax().max(m);
    if j.amax() <= tiny {
        return Mat3::zeros();
    }
    let eig = j.symmetric_eigen();
    if eig.eigenvalues.min() >= 0.0 || eig.eigenvalues.min() < -tiny {
        return j;
    }
    let d = Mat3::from_diagonal(&eig.eigenvalues.map(|x| x.max(0.0)));
    eig.eigenvectors * d * eig.eigenvectors.transpose()
}

/// Mass, centre of mass and inertia about it of the merged parts.
pub(crate) fn merge(parts: &[Part]) -> Part {
    match parts {
        [] => (0.0, Vec3::zeros(), Mat3::zeros()),
        [one] => *one,
        _ => {
            let m: f64 = parts.iter().map(|p| p.0).sum();
            let c = if m > 0.0 {
                parts.iter().map(|p| p.1 * p.0).sum::<Vec3>() / m
            } else {
                Vec3::zeros()
            };
            let mut j = Mat3::zeros();
            for (mi, ci, ji) in parts {
                let d = ci - c;
                j += ji + (Mat3::identity() * d.norm_squared() - d * d.transpose()) * *mi;
            }
            (m, c, (j + j.transpose()) * 0.5)
        }
    }
}

/// Gives `body` the merged `parts` (round-off cleaned): its mass, centre of mass and inertia.
pub(crate) fn set_inertial(body: &mut BodySpec, parts: &[Part]) {
    let (m, c, j) = merge(parts);
    let j = clean(j, m);
    body.mass = m;
    body.com = [c.x, c.y, c.z];
    body.inertia = InertiaSpec::Full([
        j[(0, 0)],
        j[(1, 1)],
        j[(2, 2)],
        j[(0, 1)],
        j[(0, 2)],
        j[(1, 2)],
    ]);
}
