//! One rigid body in director coordinates: mass, Euler tensor, and the maps between the user's
//! body frame (origin, rotation) and the coordinates `q = [φ, d1, d2, d3]` (theory.md §1).
//!
//! `φ` is the centre of mass (world frame, m), `d_i` the columns of the rotation world ← body.
//! Velocities `v = q̇` have the same layout (12 numbers). The mass matrix is
//! `M = diag(m I₃, E ⊗ I₃)` with the Euler tensor `E = ½ tr(J) I − J` (J about the centre of
//! mass, body axes), constant.

use super::def::BodyDef;
use super::error::ModelError;
use crate::math::{Mat3, Vec3};

/// Number of coordinates of one body.
pub const NQ: usize = 12;

/// Inertial data of one body, ready for the integrator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyInertia {
    /// Mass, kg.
    pub mass: f64,
    /// Euler tensor `E = ½ tr(J) I − J`, body axes, kg·m² (symmetric).
    pub euler: Mat3,
    /// Inertia tensor about the centre of mass, body axes, kg·m².
    pub inertia: Mat3,
    /// Centre of mass in the body frame, m.
    pub com: Vec3,
}

/// Director `i` (0-based) of body coordinates `q` (len ≥ 12), world frame.
fn dir(q: &[f64], i: usize) -> Vec3 {
    Vec3::new(q[3 + 3 * i], q[4 + 3 * i], q[5 + 3 * i])
}

/// The rotation `R = [d1 d2 d3]` (world ← body) of body coordinates `q` (len ≥ 12).
#[must_use]
pub fn rotation(q: &[f64]) -> Mat3 {
    Mat3::from_columns(&[dir(q, 0), dir(q, 1), dir(q, 2)])
}

/// Angular velocity `ω = ½ Σ d_i × ḋ_i` (world frame, rad/s) of coordinates `q` and velocities
/// `v` (len ≥ 12 each; exact for orthonormal directors and rigid velocities).
#[must_use]
pub fn angular_velocity(q: &[f64], v: &[f64]) -> Vec3 {
    (0..3).map(|i| dir(q, i).cross(&dir(v, i))).sum::<Vec3>() * 0.5
}

impl BodyInertia {
    /// Inertial data of `def`.
    ///
    /// # Errors
    /// [`ModelError::Invalid`] if the mass is negative or not finite, the inertia is not
    /// symmetric positive semi-definite, or the Euler tensor has a negative eigenvalue
    /// (triangle inequalities of the principal moments violated). A zero mass or a zero or
    /// semi-definite inertia is accepted here; whether the model's motion is then still
    /// determined is a property of the whole model (`Model::new` checks it).
    pub fn new(def: &BodyDef) -> Result<Self, ModelError> {
        let bad = |what: &str| ModelError::Invalid(format!("body '{}': {what}", def.name));
        if !(def.mass.is_finite() && def.mass >= 0.0) {
            return Err(bad("mass must be zero or positive and finite"));
        }
        let j = def.inertia;
        if !j.iter().all(|x| x.is_finite()) || !def.com.iter().all(|x| x.is_finite()) {
            return Err(bad("inertia and com must be finite"));
        }
        let scale = j.trace().abs().max(f64::MIN_POSITIVE);
        if (j - j.transpose()).amax() > 1e-12 * scale {
            return Err(bad("inertia must be symmetric"));
        }
        let j = (j + j.transpose()) * 0.5;
        let euler = Mat3::identity() * (0.5 * j.trace()) - j;
        let ej = j.symmetric_eigenvalues();
        let ee = euler.symmetric_eigenvalues();
        if ej.min() < -1e-12 * scale || ee.min() < -1e-12 * scale {
            return Err(bad("inertia must be positive semi-definite with principal moments satisfying the triangle inequalities"));
        }
        Ok(Self {
            mass: def.mass,
            euler,
            inertia: j,
            com: def.com,
        })
    }

    /// Kinetic energy `T = ½ vᵀ M v`, J, of body velocities `v` (len ≥ 12).
    #[must_use]
    pub fn kinetic_energy(&self, v: &[f64]) -> f64 {
        let mut p = [0.0; NQ];
        self.mass_times(v, &mut p);
        0.5 * (0..NQ).map(|k| v[k] * p[k]).sum::<f64>()
    }

    /// Generalized momenta `p = M v` (len 12): `p_φ = m φ̇` (N·s), `p_i = Σ_j E_ij ḋ_j` (N·m·s).
    pub fn momentum(&self, v: &[f64], out: &mut [f64]) {
        self.mass_times(v, out);
    }

    /// `out = M x` for a 12-vector `x` (layout `[φ, d1, d2, d3]`).
    pub fn mass_times(&self, x: &[f64], out: &mut [f64]) {
        for c in 0..3 {
            out[c] = self.mass * x[c];
        }
        for i in 0..3 {
            let mut s = Vec3::zeros();
            for j in 0..3 {
                s += dir(x, j) * self.euler[(i, j)];
            }
            out[3 + 3 * i..6 + 3 * i].copy_from_slice(s.as_slice());
        }
    }

    /// Angular momentum about the world origin, N·m·s: `L = φ × p_φ + Σ d_i × p_i`.
    #[must_use]
    pub fn angular_momentum(&self, q: &[f64], v: &[f64]) -> Vec3 {
        let mut p = [0.0; NQ];
        self.mass_times(v, &mut p);
        let phi = Vec3::new(q[0], q[1], q[2]);
        let mut l = phi.cross(&Vec3::new(p[0], p[1], p[2]));
        for i in 0..3 {
            l += dir(q, i).cross(&dir(&p, i));
        }
        l
    }

    /// Coordinates of the body whose frame has world origin `origin` (m) and rotation `rot`
    /// (world ← body): `φ = origin + R·com`, `d_i = R e_i`.
    #[must_use]
    pub fn coords_from_frame(&self, origin: &Vec3, rot: &Mat3) -> [f64; NQ] {
        let mut q = [0.0; NQ];
        q[..3].copy_from_slice((origin + rot * self.com).as_slice());
        q[3..].copy_from_slice(rot.as_slice());
        q
    }

    /// Body frame of coordinates `q`: world origin `φ − R·com` (m) and `R = [d1 d2 d3]`.
    #[must_use]
    pub fn frame_from_coords(&self, q: &[f64]) -> (Vec3, Mat3) {
        let rot = rotation(q);
        (Vec3::new(q[0], q[1], q[2]) - rot * self.com, rot)
    }

    /// Velocities (len 12) of a rigid motion with body-origin velocity `v_origin` (world, m/s)
    /// and angular velocity `w` (world, rad/s) at coordinates `q`:
    /// `φ̇ = v_origin + w × (R com)`, `ḋ_i = w × d_i`.
    #[must_use]
    pub fn velocity_from_twist(&self, q: &[f64], v_origin: &Vec3, w: &Vec3) -> [f64; NQ] {
        let rot = rotation(q);
        let mut v = [0.0; NQ];
        v[..3].copy_from_slice((v_origin + w.cross(&(rot * self.com))).as_slice());
        for i in 0..3 {
            v[3 + 3 * i..6 + 3 * i].copy_from_slice(w.cross(&dir(q, i)).as_slice());
        }
        v
    }

    /// Velocity of the body frame origin, world frame, m/s: `φ̇ − ω × (R com)`.
    #[must_use]
    pub fn origin_velocity(&self, q: &[f64], v: &[f64]) -> Vec3 {
        let w = angular_velocity(q, v);
        Vec3::new(v[0], v[1], v[2]) - w.cross(&(rotation(q) * self.com))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::exp_so3;

    fn sample() -> BodyInertia {
        let j = Mat3::new(0.4, 0.05, -0.02, 0.05, 0.3, 0.01, -0.02, 0.01, 0.25);
        let def = BodyDef {
            name: "b".into(),
            mass: 2.5,
            com: Vec3::new(0.1, -0.2, 0.3),
            inertia: j,
        };
        BodyInertia::new(&def).unwrap()
    }

    /// E = ½tr(J)I − J ⇔ J = tr(E)I − E; box principal values E_i = m a_i²/12 (theory §1.2).
    #[test]
    fn euler_tensor_identities() {
        let b = sample();
        let back = Mat3::identity() * b.euler.trace() - b.euler;
        assert!((back - b.inertia).amax() < 1e-15);
        let (m, a, bb, c) = (3.0, 1.0, 0.6, 0.3);
        let j = Mat3::from_diagonal(&Vec3::new(bb * bb + c * c, a * a + c * c, a * a + bb * bb))
            * (m / 12.0);
        let def = BodyDef {
            name: "box".into(),
            mass: m,
            com: Vec3::zeros(),
            inertia: j,
        };
        let e = BodyInertia::new(&def).unwrap().euler;
        let want = Mat3::from_diagonal(&Vec3::new(a * a, bb * bb, c * c)) * (m / 12.0);
        assert!((e - want).amax() < 1e-15);
    }

    /// T = ½ m|φ̇|² + ½ ω·J_s ω and L = J_s ω + φ × m φ̇ on rigid motions (theory §1.3, §1.6).
    #[test]
    fn energy_and_momentum_of_rigid_motion() {
        let b = sample();
        let rot = exp_so3(&Vec3::new(0.3, -1.1, 0.7));
        let origin = Vec3::new(1.0, 2.0, -0.5);
        let q = b.coords_from_frame(&origin, &rot);
        let (vo, w) = (Vec3::new(0.3, -0.2, 0.9), Vec3::new(1.5, -0.4, 2.0));
        let v = b.velocity_from_twist(&q, &vo, &w);
        let phid = Vec3::new(v[0], v[1], v[2]);
        let js = rot * b.inertia * rot.transpose();
        let t = 0.5 * b.mass * phid.norm_squared() + 0.5 * w.dot(&(js * w));
        assert!((b.kinetic_energy(&v) - t).abs() < 1e-13 * t);
        let phi = Vec3::new(q[0], q[1], q[2]);
        let l = js * w + phi.cross(&phid) * b.mass;
        assert!((b.angular_momentum(&q, &v) - l).norm() < 1e-13 * l.norm());
        assert!((angular_velocity(&q, &v) - w).norm() < 1e-14);
        assert!((b.origin_velocity(&q, &v) - vo).norm() < 1e-14);
        let (o2, r2) = b.frame_from_coords(&q);
        assert!((o2 - origin).norm() < 1e-15 && (r2 - rot).amax() < 1e-16);
        // centre-of-mass velocity against a finite difference of the placement
        let eps = 1e-6;
        let qp = b.coords_from_frame(&(origin + vo * eps), &(exp_so3(&(w * eps)) * rot));
        let qm = b.coords_from_frame(&(origin - vo * eps), &(exp_so3(&(-w * eps)) * rot));
        for k in 0..NQ {
            assert!(((qp[k] - qm[k]) / (2.0 * eps) - v[k]).abs() < 1e-8);
        }
    }

    #[test]
    fn rejects_bad_inertia() {
        let def = BodyDef {
            name: "x".into(),
            mass: 1.0,
            com: Vec3::zeros(),
            inertia: Mat3::from_diagonal(&Vec3::new(1.0, 0.1, 0.1)),
        };
        assert!(BodyInertia::new(&def).is_err());
    }
}
