//! Spatial (Plücker) vectors about a point `O`, world axes, in `f64`: the algebra of
//! the analytic derivatives of the tree dynamics (`tree_partials`) and of the articulated-body
//! solves with its mass matrix (`articulated`).
//!
//! ```text
//! motion  m = (ω, v_O)     (v_O: the velocity of the body point at O)
//! force   f = (n_O, f)     (n_O: the moment about O)
//! ⟨m, f⟩ = ω·n + v·f
//! m₁ × m₂ = (ω₁ × ω₂, ω₁ × v₂ + v₁ × ω₂)
//! m ×* f  = (ω × n + v × f, ω × f)          ⟨m₁ × m₂, f⟩ = −⟨m₂, m₁ ×* f⟩
//! twist ω about the point p with velocity u there:  (ω, u − ω × p)
//! the same vectors about the point a + d instead of a (`shift_*`):
//!   motion (ω, v + ω × d),   force (n − d × f, f),   map Y (motion → force): F Y Fᵀ,
//!   F = [1, −d̂; 0, 1]
//! inertia of mass m, centre of mass c, inertia I_G about it:
//!   Y = [I_G + m ĉ ĉᵀ, m ĉ; m ĉᵀ, m 1],   momentum h = Y V
//! ```

use super::scalar::{hat, Real};
use crate::math::{skew, Mat3, Vec3};
use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};

/// A spatial motion or force vector (module layout: angular part first).
pub(crate) type V6 = Vector6<f64>;

/// A spatial 6 × 6 matrix (an inertia, or a map between spatial vectors).
pub(crate) type M6 = Matrix6<f64>;

/// `(a, b)` as one spatial vector.
#[inline]
pub(crate) fn join(a: &Vec3, b: &Vec3) -> V6 {
    V6::new(a[0], a[1], a[2], b[0], b[1], b[2])
}

/// The angular (first) and linear (second) parts of `x`.
#[inline]
pub(crate) fn split(x: &V6) -> (Vec3, Vec3) {
    (Vec3::new(x[0], x[1], x[2]), Vec3::new(x[3], x[4], x[5]))
}

/// `m₁ × m₂` (motion by motion).
#[inline]
pub(crate) fn cross_m(m1: &V6, m2: &V6) -> V6 {
    let ((w1, v1), (w2, v2)) = (split(m1), split(m2));
    join(&w1.cross(&w2), &(w1.cross(&v2) + v1.cross(&w2)))
}

/// `m ×* f` (motion by force).
#[inline]
pub(crate) fn cross_f(m: &V6, f: &V6) -> V6 {
    let ((w, v), (n, fl)) = (split(m), split(f));
    join(&(w.cross(&n) + v.cross(&fl)), &w.cross(&fl))
}

/// The matrix of `m ×` (`crm(m) x = m × x`).
#[must_use]
pub(crate) fn crm(m: &V6) -> M6 {
    let (w, v) = split(m);
    let (sw, sv) = (skew(&w), skew(&v));
    let mut out = M6::zeros();
    out.fixed_view_mut::<3, 3>(0, 0).copy_from(&sw);
    out.fixed_view_mut::<3, 3>(3, 0).copy_from(&sv);
    out.fixed_view_mut::<3, 3>(3, 3).copy_from(&sw);
    out
}

/// The matrix of `m ×*` (`crf(m) f = m ×* f = −crm(m)ᵀ f`).
#[must_use]
pub(crate) fn crf(m: &V6) -> M6 {
    -crm(m).transpose()
}

/// The spatial inertia about `O` of a body of mass `mass` (kg) with its centre of mass at `c`
/// (world, m) and inertia `ig` about it (world axes, kg·m²), in any scalar of the dynamics
/// (`f64` here, dual numbers in `TreeDynamics::mass_matrix`).
#[must_use]
pub(crate) fn inertia<T: Real>(mass: T, c: &Vector3<T>, ig: &Matrix3<T>) -> Matrix6<T> {
    let ch = hat(c);
    let mut y = Matrix6::<T>::zeros();
    y.fixed_view_mut::<3, 3>(0, 0)
        .copy_from(&(ig + ch * ch.transpose() * mass));
    y.fixed_view_mut::<3, 3>(0, 3).copy_from(&(ch * mass));
    y.fixed_view_mut::<3, 3>(3, 0)
        .copy_from(&(ch.transpose() * mass));
    y.fixed_view_mut::<3, 3>(3, 3)
        .copy_from(&(Matrix3::identity() * mass));
    y
}

/// The motion `m` about `a` as about `a + d`.
#[inline]
pub(crate) fn shift_m(m: &V6, d: &Vec3) -> V6 {
    let (w, v) = split(m);
    join(&w, &(v + w.cross(d)))
}

/// The force `f` about `a` as about `a + d`.
#[inline]
pub(crate) fn shift_f(f: &V6, d: &Vec3) -> V6 {
    let (n, fl) = split(f);
    join(&(n - d.cross(&fl)), &fl)
}

/// The map `y` from motions to forces about `a` (an inertia) as about `a + d`: `F y Fᵀ`, by
/// blocks (`y = [A B; C D]`: `[A − d̂C + (B − d̂D) d̂, B − d̂D; C + D d̂, D]`).
#[must_use]
pub(crate) fn shift_map(y: &M6, d: &Vec3) -> M6 {
    if *d == Vec3::zeros() {
        return *y;
    }
    let h = skew(d);
    let blk = |i: usize, j: usize| -> Mat3 { y.fixed_view::<3, 3>(i, j).into_owned() };
    let (a, b, c, dd) = (blk(0, 0), blk(0, 3), blk(3, 0), blk(3, 3));
    let b2 = b - h * dd;
    let mut out = M6::zeros();
    out.fixed_view_mut::<3, 3>(0, 0)
        .copy_from(&(a - h * c + b2 * h));
    out.fixed_view_mut::<3, 3>(0, 3).copy_from(&b2);
    out.fixed_view_mut::<3, 3>(3, 0).copy_from(&(c + dd * h));
    out.fixed_view_mut::<3, 3>(3, 3).copy_from(&dd);
    out
}
