//! Mass properties of geoms, as MuJoCo's compiler computes them for `inertiafromgeom`: a solid
//! of uniform density (`density`, default 1000 kg/m³, or `mass` given, which sets the density),
//! about its centre in the geom frame (sizes are MuJoCo's half sizes):
//!
//! ```text
//! sphere r            V = 4/3 π r³          I = 2/5 m r² (each axis)
//! ellipsoid a b c     V = 4/3 π a b c       Ixx = m (b² + c²)/5, …
//! box a b c           V = 8 a b c           Ixx = m (b² + c²)/3, …
//! cylinder r, h       V = π r² 2h           Ixx = Iyy = m (3r² + (2h)²)/12,  Izz = m r²/2
//! capsule r, h        a cylinder (mass m_c, length 2h) and two hemispheres (m_s together,
//!                     a sphere's mass): Izz = m_c r²/2 + 2/5 m_s r²,
//!                     Ixx = m_c (3r² + 4h²)/12 + m_s (2r²/5 + h² + 3hr/4)
//! ```
//!
//! (each hemisphere: its centre of mass 3r/8 from its flat face, which sits at ±h; its inertia
//! about the capsule's centre by the parallel-axis theorem). The body's inertial is the sum of
//! its geoms' (`crate::import::inertia::merge`).

use std::f64::consts::PI;

use crate::math::Mat3;

/// The solid shapes of geoms that have a volume (MuJoCo's half sizes, m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Solid {
    /// Radius.
    Sphere(f64),
    /// Radius, half length of the cylindrical part (along z).
    Capsule(f64, f64),
    /// Radius, half length (along z).
    Cylinder(f64, f64),
    /// Half sizes along x, y, z.
    Box([f64; 3]),
    /// Semi-axes along x, y, z.
    Ellipsoid([f64; 3]),
}

impl Solid {
    /// Volume, m³.
    pub fn volume(&self) -> f64 {
        match *self {
            Solid::Sphere(r) => 4.0 / 3.0 * PI * r.powi(3),
            Solid::Capsule(r, h) => 4.0 / 3.0 * PI * r.powi(3) + PI * r * r * 2.0 * h,
            Solid::Cylinder(r, h) => PI * r * r * 2.0 * h,
            Solid::Box([a, b, c]) => 8.0 * a * b * c,
            Solid::Ellipsoid([a, b, c]) => 4.0 / 3.0 * PI * a * b * c,
        }
    }

    /// The inertia about the centre, geom axes, of the solid of mass `m`, kg·m².
    pub fn inertia(&self, m: f64) -> Mat3 {
        let d = |x: f64, y: f64, z: f64| Mat3::from_diagonal(&[x, y, z].into());
        match *self {
            Solid::Sphere(r) => d(0.4 * m * r * r, 0.4 * m * r * r, 0.4 * m * r * r),
            Solid::Ellipsoid([a, b, c]) => d(
                m * (b * b + c * c) / 5.0,
                m * (a * a + c * c) / 5.0,
                m * (a * a + b * b) / 5.0,
            ),
            Solid::Box([a, b, c]) => d(
                m * (b * b + c * c) / 3.0,
                m * (a * a + c * c) / 3.0,
                m * (a * a + b * b) / 3.0,
            ),
            Solid::Cylinder(r, h) => {
                let x = m * (3.0 * r * r + 4.0 * h * h) / 12.0;
                d(x, x, m * r * r / 2.0)
            }
            Solid::Capsule(r, h) => {
                let v = self.volume();
                let (mc, ms) = if v > 0.0 {
                    (
                        m * PI * r * r * 2.0 * h / v,
                        m * 4.0 / 3.0 * PI * r.powi(3) / v,
                    )
                } else {
                    (0.0, 0.0)
                };
                let x = mc * (3.0 * r * r + 4.0 * h * h) / 12.0
                    + ms * (0.4 * r * r + h * h + 0.75 * h * r);
                d(x, x, mc * r * r / 2.0 + 0.4 * ms * r * r)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Solid;
    use std::f64::consts::PI;

    fn close(a: f64, b: f64) {
        assert!((a - b).abs() <= 1e-12 * b.abs().max(1.0), "{a} vs {b}");
    }

    #[test]
    fn capsule_is_a_cylinder_and_a_sphere_split() {
        // the capsule's inertia by integration over its axis: slices of a solid of revolution
        let (r, h, rho) = (0.1, 0.3, 1000.0);
        let c = Solid::Capsule(r, h);
        let m = rho * c.volume();
        let n = 200_000;
        let (lo, hi) = (-h - r, h + r);
        let dz = (hi - lo) / f64::from(n);
        let (mut ixx, mut izz, mut mass) = (0.0, 0.0, 0.0);
        for k in 0..n {
            let z = lo + (f64::from(k) + 0.5) * dz;
            let rho_z = if z.abs() <= h {
                r
            } else {
                (r * r - (z.abs() - h).powi(2)).max(0.0).sqrt()
            };
            let dm = rho * PI * rho_z * rho_z * dz;
            mass += dm;
            izz += dm * rho_z * rho_z / 2.0;
            ixx += dm * (rho_z * rho_z / 4.0 + z * z);
        }
        assert!((mass / m - 1.0).abs() < 1e-6);
        let j = c.inertia(m);
        assert!((j[(2, 2)] - izz).abs() < 1e-6 * izz);
        assert!((j[(0, 0)] - ixx).abs() < 1e-6 * ixx);
        close(j[(0, 0)], j[(1, 1)]);
    }

    #[test]
    fn shapes_against_their_formulas() {
        let m = 2.0;
        let s = Solid::Sphere(0.5).inertia(m);
        close(s[(0, 0)], 0.4 * m * 0.25);
        close(Solid::Sphere(0.5).volume(), 4.0 / 3.0 * PI * 0.125);
        let b = Solid::Box([0.1, 0.2, 0.3]);
        close(b.volume(), 8.0 * 0.006);
        let j = b.inertia(m);
        close(j[(0, 0)], m * (0.04 + 0.09) / 3.0);
        close(j[(1, 1)], m * (0.01 + 0.09) / 3.0);
        close(j[(2, 2)], m * (0.01 + 0.04) / 3.0);
        let c = Solid::Cylinder(0.1, 0.5);
        close(c.volume(), PI * 0.01 * 1.0);
        let j = c.inertia(m);
        close(j[(0, 0)], m * (3.0 * 0.01 + 1.0) / 12.0);
        close(j[(2, 2)], m * 0.01 / 2.0);
        let e = Solid::Ellipsoid([0.1, 0.2, 0.3]);
        close(e.volume(), 4.0 / 3.0 * PI * 0.006);
        let j = e.inertia(m);
        close(j[(0, 0)], m * (0.04 + 0.09) / 5.0);
        close(j[(2, 2)], m * (0.01 + 0.04) / 5.0);
    }
}
