//! Small linear-algebra vocabulary shared by the whole crate (nalgebra aliases and helpers).

use nalgebra::{Matrix3, Vector3};

/// A 3-vector of `f64` (world or body frame, as the caller states).
pub type Vec3 = Vector3<f64>;
/// A 3×3 matrix of `f64`.
pub type Mat3 = Matrix3<f64>;

/// Skew-symmetric matrix `â` with `â b = a × b`.
#[must_use]
pub fn skew(a: &Vec3) -> Mat3 {
    Mat3::new(0.0, -a.z, a.y, a.z, 0.0, -a.x, -a.y, a.x, 0.0)
}

/// Rotation matrix from fixed-axis roll, pitch, yaw (URDF `rpy`): `R = Rz(yaw) · Ry(pitch) · Rx(roll)`.
#[must_use]
pub fn rpy_to_matrix(rpy: &Vec3) -> Mat3 {
    let (sr, cr) = rpy.x.sin_cos();
    let (sp, cp) = rpy.y.sin_cos();
    let (sy, cy) = rpy.z.sin_cos();
    Mat3::new(
        cy * cp,
        cy * sp * sr - sy * cr,
        cy * sp * cr + sy * sr,
        sy * cp,
        sy * sp * sr + cy * cr,
        sy * sp * cr - cy * sr,
        -sp,
        cp * sr,
        cp * cr,
    )
}

/// Fixed-axis roll, pitch, yaw of a rotation matrix (the inverse of [`rpy_to_matrix`]; pitch in
/// `[−π/2, π/2]`; at pitch ±π/2, where only roll ∓ yaw is defined, roll is 0).
#[must_use]
pub fn matrix_to_rpy(r: &Mat3) -> Vec3 {
    let cp = r[(0, 0)].hypot(r[(1, 0)]);
    let pitch = (-r[(2, 0)]).atan2(cp);
    if cp < 1e-12 {
        return Vec3::new(0.0, pitch, (-r[(0, 1)]).atan2(r[(1, 1)]));
    }
    Vec3::new(
        r[(2, 1)].atan2(r[(2, 2)]),
        pitch,
        r[(1, 0)].atan2(r[(0, 0)]),
    )
}

/// Rotation matrix of a unit quaternion `[w, x, y, z]` (normalised here).
#[must_use]
pub fn quat_to_matrix(q: &[f64; 4]) -> Mat3 {
    let n = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]).sqrt();
    let (w, x, y, z) = (q[0] / n, q[1] / n, q[2] / n, q[3] / n);
    Mat3::new(
        1.0 - 2.0 * (y * y + z * z),
        2.0 * (x * y - w * z),
        2.0 * (x * z + w * y),
        2.0 * (x * y + w * z),
        1.0 - 2.0 * (x * x + z * z),
        2.0 * (y * z - w * x),
        2.0 * (x * z - w * y),
        2.0 * (y * z + w * x),
        1.0 - 2.0 * (x * x + y * y),
    )
}

/// Unit quaternion `[w, x, y, z]` (w ≥ 0) of a rotation matrix, by Shepperd's method.
#[must_use]
pub fn matrix_to_quat(r: &Mat3) -> [f64; 4] {
    let tr = r[(0, 0)] + r[(1, 1)] + r[(2, 2)];
    let q = if tr >= r[(0, 0)] && tr >= r[(1, 1)] && tr >= r[(2, 2)] {
        let w = 0.5 * (1.0 + tr).max(0.0).sqrt();
        let s = 0.25 / w;
        [
            w,
            (r[(2, 1)] - r[(1, 2)]) * s,
            (r[(0, 2)] - r[(2, 0)]) * s,
            (r[(1, 0)] - r[(0, 1)]) * s,
        ]
    } else if r[(0, 0)] >= r[(1, 1)] && r[(0, 0)] >= r[(2, 2)] {
        let x = 0.5 * (1.0 + 2.0 * r[(0, 0)] - tr).max(0.0).sqrt();
        let s = 0.25 / x;
        [
            (r[(2, 1)] - r[(1, 2)]) * s,
            x,
            (r[(0, 1)] + r[(1, 0)]) * s,
            (r[(0, 2)] + r[(2, 0)]) * s,
        ]
    } else if r[(1, 1)] >= r[(2, 2)] {
        let y = 0.5 * (1.0 + 2.0 * r[(1, 1)] - tr).max(0.0).sqrt();
        let s = 0.25 / y;
        [
            (r[(0, 2)] - r[(2, 0)]) * s,
            (r[(0, 1)] + r[(1, 0)]) * s,
            y,
            (r[(1, 2)] + r[(2, 1)]) * s,
        ]
    } else {
        let z = 0.5 * (1.0 + 2.0 * r[(2, 2)] - tr).max(0.0).sqrt();
        let s = 0.25 / z;
        [
            (r[(1, 0)] - r[(0, 1)]) * s,
            (r[(0, 2)] + r[(2, 0)]) * s,
            (r[(1, 2)] + r[(2, 1)]) * s,
            z,
        ]
    };
    if q[0] < 0.0 {
        [-q[0], -q[1], -q[2], -q[3]]
    } else {
        q
    }
}

/// Rotation by the rotation vector `theta` (Rodrigues): `exp(θ̂)`.
#[must_use]
pub fn exp_so3(theta: &Vec3) -> Mat3 {
    let a2 = theta.norm_squared();
    let k = skew(theta);
    let (s, c) = if a2 < 1e-12 {
        (1.0 - a2 / 6.0, 0.5 - a2 / 24.0)
    } else {
        let a = a2.sqrt();
        (a.sin() / a, (1.0 - a.cos()) / a2)
    };
    Mat3::identity() + k * s + k * k * c
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quaternion_round_trip() {
        let r = exp_so3(&Vec3::new(0.3, -2.5, 0.7));
        let q = matrix_to_quat(&r);
        assert!((quat_to_matrix(&q) - r).norm() < 1e-14);
        assert!((r.transpose() * r - Mat3::identity()).norm() < 1e-14);
    }

    #[test]
    fn rpy_matches_axis_composition() {
        let rpy = Vec3::new(0.1, -0.4, 1.2);
        let r = exp_so3(&(Vec3::z() * rpy.z))
            * exp_so3(&(Vec3::y() * rpy.y))
            * exp_so3(&(Vec3::x() * rpy.x));
        assert!((rpy_to_matrix(&rpy) - r).norm() < 1e-14);
    }
}
