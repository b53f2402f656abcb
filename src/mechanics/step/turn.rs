//! Joint springs and dampers on a rotational joint coordinate, as an exact, singularity-free
//! discrete gradient.
//!
//! A turn coordinate is the angle `t = atan2(s, c)` of two quadratic invariants of the joint,
//! `s = aᵢ·bⱼ` and `c = aₖ·bₗ` (dot products of parent and child joint axes, [`DotRow`]s;
//! e.g. a revolute joint has `s = a₂·b₁`, `c = a₁·b₁`). Over a step from `(s₀, c₀)` to
//! `(s₁, c₁)` the angle increment is, with no cancellation for small increments,
//!
//! ```text
//! X = c₀ Δs − s₀ Δc  (= c₀ s₁ − s₀ c₁),   Y = c₀ c₁ + s₀ s₁,   Δt = atan2(X, Y) = β X
//! ```
//!
//! (`Δs = Δu·w̄ + ū·Δw` exactly, from the stored increments `q − qₙ`). The generalised force `f`
//! on the coordinate (spring `−k t̄`, damper `−c Δt/h`, with `t̄ = t₀ + Δt/2`, a rotor of
//! inertia `a` in joint space, `−(2a/h²)(Δt − h ω₀)`, and actuators `τ(t̄, Δt/h)` of
//! `model::joint_actuator`) acts on the coordinates as
//!
//! ```text
//! F = f β (c̄ ∇s(q̄) − s̄ ∇c(q̄)),   s̄ = s₀ + Δs/2,  c̄ = c₀ + Δc/2
//! ```
//!
//! Since `∇s(q̄)·Δq = Δs` exactly (s is quadratic) and `c̄ Δs − s̄ Δc = X`, `F·Δq = f Δt`: the
//! spring releases exactly `½k(t₁² − t₀²)` and the damper dissipates exactly `c Δt²/h ≥ 0`.
//! The rotor is the midpoint rule on the joint coordinate with its own rate `ω` (state,
//! `ω₁ = 2Δt/h − ω₀`): its load's work `−(2a/h²)(Δt − hω₀)Δt = −½a(ω₁² − ω₀²)` is exactly the
//! rotor's change of kinetic energy, so `energy − work` stays exact with it.
//! `F` is a combination of midpoint gradients of rigid-motion invariants, so it preserves linear
//! and angular momentum. `β = atan2(X, Y)/X` is smooth (`β → 1/Y` as `X → 0`, by its series), so
//! nothing divides by a small increment: a joint at rest under a stiff spring is as regular as a
//! moving one. (theory.md §4.2: the invariant-based discrete gradient, here of `atan2`.)

use crate::math::{skew, Mat3, Vec3};
use crate::mechanics::model::constraint::DotRow;
use crate::mechanics::model::constraint::LinVec;
use crate::mechanics::model::joint_actuator::JointActuators;
use crate::mechanics::model::joint_friction::JointFriction;
use crate::mechanics::model::stops::Stops;

/// `β = atan2(X, Y)/X` and its partial derivatives `(β, ∂β/∂X, ∂β/∂Y)`; by the series of
/// `atan(z)/z` (`z = X/Y`) when `|X| ≤ 10⁻³ Y`, where the quotient would cancel.
#[must_use]
pub(crate) fn beta(x: f64, y: f64) -> (f64, f64, f64) {
    if y > 0.0 && x.abs() <= 1e-3 * y {
        let z = x / y;
        let z2 = z * z;
        // atan(z)/z = Σ (−z²)ⁿ/(2n+1); the first omitted term is ≤ 1e-30
        let phi = 1.0 + z2 * (-1.0 / 3.0 + z2 * (1.0 / 5.0 + z2 * (-1.0 / 7.0 + z2 / 9.0)));
        let dphi = z * (-2.0 / 3.0 + z2 * (4.0 / 5.0 + z2 * (-6.0 / 7.0 + z2 * 8.0 / 9.0)));
        let b = phi / y;
        (b, dphi / (y * y), -b / y - dphi * x / (y * y * y))
    } else {
        let t = x.atan2(y);
        let r = x * x + y * y;
        let b = t / x;
        ((b), (y / r - b) / x, -1.0 / r)
    }
}

/// Angle step of one turn coordinate over a stage and the load it carries.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct TurnStep {
    /// Angle increment `Δt = t₁ − t₀`, rad.
    pub dt: f64,
    /// Coefficient of `∇s(q̄)` in the generalised force `F` (N·m per unit of `s`).
    pub fs: f64,
    /// Coefficient of `∇c(q̄)` in `F`.
    pub fc: f64,
    /// `∂(fs, fc)/∂(s₁, c₁)`, row-major `[∂fs/∂s₁, ∂fs/∂c₁, ∂fc/∂s₁, ∂fc/∂c₁]`.
    pub jac: [f64; 4],
}

/// The angle step from `[s₀, c₀]` with increments `[Δs, Δc]`, and the spring (stiffness `k`,
/// N·m/rad, about angle 0), damper (`c_d`, N·m·s/rad), stop (`model::stops`) and rotor
/// (`[a, ω₀]`: armature, kg·m², and the rotor's rate at the stage start, rad/s; the load
/// `−(2a/h²)(Δt − h ω₀)`, module docs) and friction (`model::joint_friction` with its bristle's
/// deflection at the stage start) and actuator (`model::joint_actuator`, with the input vector)
/// load for the start angle `t0` (rad) and stage size `h` (s).
#[must_use]
#[allow(clippy::too_many_arguments)]
pub(crate) fn turn_step(
    [s0, c0]: [f64; 2],
    [ds, dc]: [f64; 2],
    t0: f64,
    k: f64,
    c_d: f64,
    stops: Option<&Stops>,
    [a, w0]: [f64; 2],
    fric: Option<(&JointFriction, f64)>,
    (acts, inputs, gains): (&JointActuators, &[f64], &[f64]),
    h: f64,
) -> TurnStep {
    let x = c0 * ds - s0 * dc;
    let (s1, c1) = (s0 + ds, c0 + dc);
    let y = c0 * c1 + s0 * s1;
    let (b, bx, by) = beta(x, y);
    let dt = b * x;
    if k == 0.0 && c_d == 0.0 && stops.is_none() && a == 0.0 && fric.is_none() && acts.is_empty() {
        return TurnStep {
            dt,
            ..TurnStep::default()
        };
    }
    let (f_stop, df_stop) = stops.map_or((0.0, 0.0), |st| st.force(t0, dt, h));
    let rotor = 2.0 * a / (h * h);
    let (f_fric, df_fric) = fric.map_or((0.0, 0.0), |(fr, s0)| {
        let st = fr.step(s0, dt, h);
        (st.force, st.dforce)
    });
    let (f_act, df_act) = acts.stage(inputs, gains, t0, dt, h);
    let f = -k * (t0 + 0.5 * dt) - c_d * dt / h + f_stop - rotor * (dt - h * w0) + f_fric + f_act;
    let (sb, cb) = (s0 + 0.5 * ds, c0 + 0.5 * dc);
    // ∂X/∂(s₁, c₁) = (c₀, −s₀), ∂Y/∂(s₁, c₁) = (s₀, c₀)
    let r = x * x + y * y;
    let ddt = [(y * c0 - x * s0) / r, (-y * s0 - x * c0) / r];
    let db = [bx * c0 + by * s0, -bx * s0 + by * c0];
    let df = -(0.5 * k + c_d / h + rotor) + df_stop + df_fric + df_act;
    let fb = f * b;
    let mut jac = [0.0; 4];
    for v in 0..2 {
        let dfb = df * ddt[v] * b + f * db[v];
        jac[v] = dfb * cb;
        jac[2 + v] = -dfb * sb;
    }
    jac[1] += 0.5 * fb;
    jac[2] -= 0.5 * fb;
    TurnStep {
        dt,
        fs: fb * cb,
        fc: -fb * sb,
        jac,
    }
}

/// A constant generalised force `f` on a turn coordinate (a coupling's reaction): its step
/// (`fs = f β c̄`, `fc = −f β s̄` and their partials in `(s₁, c₁)`), the unit coefficients
/// `[β c̄, −β s̄]` (`∂(fs, fc)/∂f`) and `∂Δt/∂(s₁, c₁)`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TurnLoad {
    /// The angle step and the load's coefficients.
    pub step: TurnStep,
    /// `[β c̄, −β s̄]`.
    pub unit: [f64; 2],
    /// `[∂Δt/∂s₁, ∂Δt/∂c₁]`.
    pub ddt: [f64; 2],
}

/// The angle step from `[s₀, c₀]` with increments `[Δs, Δc]` under a constant generalised force
/// `f` (N·m, or scaled residual units): [`turn_step`]'s formulas with `∂f = 0`.
#[must_use]
pub(crate) fn turn_load([s0, c0]: [f64; 2], [ds, dc]: [f64; 2], f: f64) -> TurnLoad {
    let x = c0 * ds - s0 * dc;
    let (s1, c1) = (s0 + ds, c0 + dc);
    let y = c0 * c1 + s0 * s1;
    let (b, bx, by) = beta(x, y);
    let (sb, cb) = (s0 + 0.5 * ds, c0 + 0.5 * dc);
    let r = x * x + y * y;
    let ddt = [(y * c0 - x * s0) / r, (-y * s0 - x * c0) / r];
    let db = [bx * c0 + by * s0, -bx * s0 + by * c0];
    let fb = f * b;
    let mut jac = [0.0; 4];
    for v in 0..2 {
        jac[v] = f * db[v] * cb;
        jac[2 + v] = -f * db[v] * sb;
    }
    jac[1] += 0.5 * fb;
    jac[2] -= 0.5 * fb;
    TurnLoad {
        step: TurnStep {
            dt: b * x,
            fs: fb * cb,
            fc: -fb * sb,
            jac,
        },
        unit: [b * cb, -b * sb],
        ddt,
    }
}

/// `u(q₁)·w(q₁) − u(q₀)·w(q₀) = Δu·w̄ + ū·Δw` of a row from the midpoint `ū, w̄` and the
/// node increments (A: `da`, B: `db`), without the cancellation of subtracting two values.
#[must_use]
pub(crate) fn row_increment(
    row: &DotRow,
    qa_bar: &crate::mechanics::model::constraint::Nodes,
    qb_bar: &crate::mechanics::model::constraint::Nodes,
    da: &crate::mechanics::model::constraint::Nodes,
    db: &crate::mechanics::model::constraint::Nodes,
) -> f64 {
    let lin = |v: &LinVec| {
        let mut out = Vec3::zeros();
        for n in 0..4 {
            out += da[n] * v.a[n] + db[n] * v.b[n];
        }
        out
    };
    lin(&row.u).dot(&row.w.eval(qa_bar, qb_bar)) + row.u.eval(qa_bar, qb_bar).dot(&lin(&row.w))
}

/// `∂θ/∂ε` (3 × 3, world frame) of a body's rotation increment `θ = ½ Σᵢ d̄ⁱ × (dᵢ − dᵢₙ)`
/// for the Newton update `dᵢ ← exp(ε̂) dᵢ` at `ε = 0`, from the start nodes `n` and the
/// iterate `q`: with `M = ΔD D̄⁻¹` and `P = D D̄⁻¹`, `dM = (I − ½M) ε̂ P` and
/// `dθ = ½ axial(dM − dMᵀ)`. Equals `I` at `q = n`. Used by the spherical joint's damper
/// `−(c/h)(θᴮ − θᴬ)`, whose Jacobian is `(c/h) ∂θ/∂ε`.
#[must_use]
pub(crate) fn theta_jac(
    n: &crate::mechanics::model::constraint::Nodes,
    q: &crate::mechanics::model::constraint::Nodes,
) -> Mat3 {
    let dbar = [
        (n[1] + q[1]) * 0.5,
        (n[2] + q[2]) * 0.5,
        (n[3] + q[3]) * 0.5,
    ];
    let rec = crate::mechanics::model::kernels::reciprocal(&dbar);
    // D̄⁻¹ has the reciprocal vectors as rows
    let inv = Mat3::from_rows(&[rec[0].transpose(), rec[1].transpose(), rec[2].transpose()]);
    let d = Mat3::from_columns(&[q[1], q[2], q[3]]);
    let dd = Mat3::from_columns(&[q[1] - n[1], q[2] - n[2], q[3] - n[3]]);
    let m = dd * inv;
    let p = d * inv;
    let left = Mat3::identity() - m * 0.5;
    let mut out = Mat3::zeros();
    for k in 0..3 {
        let dm = left * skew(&Vec3::ith(k, 1.0)) * p;
        let a = dm - dm.transpose();
        out.set_column(k, &(Vec3::new(a[(2, 1)], a[(0, 2)], a[(1, 0)]) * 0.5));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn beta_is_smooth_across_its_two_branches() {
        for &y in &[1.0, 0.7, 1.3] {
            for &x in &[1e-12, 1e-6, 0.999e-3, 1.001e-3, 0.05, -0.3, 2.0] {
                let x = x * y;
                let (b, bx, by) = beta(x, y);
                let exact = x.atan2(y) / x;
                assert!((b - exact).abs() <= 1e-15 * exact.abs(), "{x} {y}");
                // derivatives against central differences
                let e = 1e-6 * (1.0 + x.abs());
                let fx = (beta(x + e, y).0 - beta(x - e, y).0) / (2.0 * e);
                let fy = (beta(x, y + e).0 - beta(x, y - e).0) / (2.0 * e);
                assert!(
                    (bx - fx).abs() <= 1e-7 * (1.0 + fx.abs()),
                    "bx {x} {y}: {bx} {fx}"
                );
                assert!(
                    (by - fy).abs() <= 1e-7 * (1.0 + fy.abs()),
                    "by {x} {y}: {by} {fy}"
                );
            }
        }
        // X = 0 exactly: β = 1/Y
        assert_eq!(beta(0.0, 2.0).0, 0.5);
    }

    #[test]
    fn the_force_does_exactly_the_spring_and_damper_work() {
        let (k, c, h) = (270.0, 38.0, 0.02);
        // a rotor of 0.3 kg·m² turning at 0.7 rad/s
        let (ar, w0) = (0.3, 0.7);
        for &(t0, dt_true) in &[(0.4_f64, 0.03_f64), (-2.9, -0.5), (1.0, 1e-11), (3.0, 0.3)] {
            let (s0, c0) = (t0.sin(), t0.cos());
            let t1: f64 = t0 + dt_true;
            let (ds, dc) = (t1.sin() - s0, t1.cos() - c0);
            let fr = JointFriction {
                limit: 0.4,
                mirrored: false,
            };
            let fric = Some((&fr, 3e-5));
            let st = turn_step(
                [s0, c0],
                [ds, dc],
                t0,
                k,
                c,
                None,
                [ar, w0],
                fric,
                (&JointActuators::default(), &[], &[]),
                h,
            );
            assert!((st.dt - dt_true).abs() <= 1e-15 * (1.0 + t0.abs()) + 1e-12 * dt_true.abs());
            // F·Δq = fs Δs + fc Δc = −½k(t₁² − t₀²) − c Δt²/h − ½a(ω₁² − ω₀²)
            let w = st.fs * ds + st.fc * dc;
            let tt = t0 + st.dt;
            let w1 = 2.0 * st.dt / h - w0;
            let fs = fr.step(3e-5, st.dt, h);
            let expected = -0.5 * k * (tt * tt - t0 * t0)
                - c * st.dt * st.dt / h
                - 0.5 * ar * (w1 * w1 - w0 * w0)
                - (fr.energy(fs.s1) - fr.energy(3e-5))
                - fs.loss;
            assert!(
                (w - expected).abs() <= 1e-12 * (1.0 + expected.abs()),
                "{w} {expected}"
            );
            // partials against central differences in (s₁, c₁)
            let e = 1e-7;
            for v in 0..2 {
                let (a, b) = if v == 0 { (e, 0.0) } else { (0.0, e) };
                let p = turn_step(
                    [s0, c0],
                    [ds + a, dc + b],
                    t0,
                    k,
                    c,
                    None,
                    [ar, w0],
                    fric,
                    (&JointActuators::default(), &[], &[]),
                    h,
                );
                let m = turn_step(
                    [s0, c0],
                    [ds - a, dc - b],
                    t0,
                    k,
                    c,
                    None,
                    [ar, w0],
                    fric,
                    (&JointActuators::default(), &[], &[]),
                    h,
                );
                let fs = (p.fs - m.fs) / (2.0 * e);
                let fc = (p.fc - m.fc) / (2.0 * e);
                assert!(
                    (st.jac[v] - fs).abs() <= 1e-5 * (1.0 + fs.abs()),
                    "{v} {fs}"
                );
                assert!(
                    (st.jac[2 + v] - fc).abs() <= 1e-5 * (1.0 + fc.abs()),
                    "{v} {fc}"
                );
            }
        }
    }
}
