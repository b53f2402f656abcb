//! The scalars the minimal-coordinate dynamics (`tree_dynamics`, `sticking`) is evaluated in:
//! `f64`, or a dual number for exact derivatives (`linear`), and the small products written out
//! for them.
//!
//! ```text
//! mm(a, b) = a b,   mv(a, v) = a v        (3 × 3; nalgebra's generic product is slow for duals)
//! hat(a) v = a × v
//! ```

use crate::math::{Mat3, Vec3};
use nalgebra::{Matrix3, RealField, Vector3};

/// A real scalar the dynamics can be evaluated in: `f64`, or a dual number.
pub trait Real: RealField + Copy {}
impl<T: RealField + Copy> Real for T {}

/// `x` as a `T`.
pub fn c<T: Real>(x: f64) -> T {
    nalgebra::convert(x)
}

pub(crate) fn cv<T: Real>(v: &Vec3) -> Vector3<T> {
    v.map(c)
}

pub(crate) fn cm<T: Real>(m: &Mat3) -> Matrix3<T> {
    m.map(c)
}

pub(crate) fn hat<T: Real>(a: &Vector3<T>) -> Matrix3<T> {
    let z = T::zero();
    Matrix3::new(z, -a[2], a[1], a[2], z, -a[0], -a[1], a[0], z)
}

/// `a b` (3 × 3) written out: nalgebra's generic product, which dual numbers take, is several
/// times slower than these nine dot products.
#[inline]
pub(crate) fn mm<T: Real>(a: &Matrix3<T>, b: &Matrix3<T>) -> Matrix3<T> {
    Matrix3::from_fn(|i, j| a[(i, 0)] * b[(0, j)] + a[(i, 1)] * b[(1, j)] + a[(i, 2)] * b[(2, j)])
}

/// `a v` (3 × 3 by 3) written out (see [`mm`]).
#[inline]
pub(crate) fn mv<T: Real>(a: &Matrix3<T>, v: &Vector3<T>) -> Vector3<T> {
    Vector3::new(
        a[(0, 0)] * v[0] + a[(0, 1)] * v[1] + a[(0, 2)] * v[2],
        a[(1, 0)] * v[0] + a[(1, 1)] * v[1] + a[(1, 2)] * v[2],
        a[(2, 0)] * v[0] + a[(2, 1)] * v[1] + a[(2, 2)] * v[2],
    )
}
