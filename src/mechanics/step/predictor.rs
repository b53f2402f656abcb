//! The Newton start of a stage: the bodies' mean rates over the stage, extrapolated from the
//! history of the previous stages' means.
//!
//! A stage of size `h` moves body `b` by `Δφ = h v̄` and `dᵢ ← cay(h ω̄) dᵢ`. The converged
//! stages' means `mₖ = (Δφ/h, θ/h)` (newest `m₀`) are samples, one step `h` apart, of a smooth
//! function of time. The history keeps their backward differences `∇ᵏm₀` (`∇m₀ = m₀ − m₁`,
//! k = 0 … [`HISTORY`] − 1), so after [`HISTORY`] stages of the same size the next mean is the
//! polynomial extrapolation of degree `p` in Newton's backward form:
//!
//! ```text
//! m̂ = m₀ + ∇m₀ + … + ∇ᵖm₀        (p = 1: 2m₀ − m₁;  p = 2: 3m₀ − 3m₁ + m₂; …)
//! ```
//!
//! with error `hᵖ⁺¹ m⁽ᵖ⁺¹⁾`: higher degrees win while `h` resolves the motion (`hω ≪ 1`) and
//! lose when it does not (large steps, stiff springs, input jumps). The same degree
//! extrapolating `m₀` from the older means errs by exactly `∇ᵖ⁺¹m₀`, so each body takes the
//! degree (0 ≤ p ≤ [`MAX_DEGREE`]) whose next difference is smallest. The order-4 composition's
//! three stages (sizes γ₁h, γ₂h, γ₁h) keep a table each besides the table of every stage, so
//! each stage extrapolates from the same stage of the previous steps, also one step apart.
//! With a shorter or unequal history (start, halved stages, a shorter last sub-step) the mean
//! is extrapolated linearly from the nodal rate and the previous stage's mean (first stage: the
//! nodal rate). The predictor sets only the Newton start: the converged stage does not depend
//! on it, a better one saves iterations (chain100 at h = 1e-3: 4.0 iterations per step with the
//! linear start, 2.0 with this one; at order 4, 10.3 → 6.0 per step of three stages).
//!
//! At steps that do not resolve the motion the nodal rate is a poor start: `v_{n+1} = 2Δq/h −
//! vₙ` carries a component that flips sign every stage and is as large as the motion. A stage
//! that failed from it is retried ([`Start::Means`]) from the last two stages' means alone,
//! each taken at its stage's centre (`−h₀/2` and `−h₀ − h₁/2` from the stage start, sizes
//! signed, newest `h₀`), extrapolated linearly to the new stage's centre `h/2`:
//!
//! ```text
//! m̂ = m₀ + (m₀ − m₁) (h + h₀)/(h₀ + h₁)      (m̂ = m₀ where |h₀ + h₁| < |h₀|: centres too close)
//! ```

use super::work::{Work, HISTORY};
use crate::math::{skew, Mat3, Vec3};
use crate::mechanics::model::constraint::{read3, write3};
use crate::mechanics::model::runtime::Model;

/// Highest extrapolation degree (its error is judged by the difference of the next order).
pub const MAX_DEGREE: usize = HISTORY - 2;

/// Where a stage's Newton iteration starts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Start {
    /// The stage's own difference table where it is full, else the nodal rate and the last
    /// stage's mean (see the module docs).
    Rates,
    /// The last two stages' means only (a retry after a failure from the nodal rate).
    Means,
}

/// Writes the predictor of a stage of size `h` into `ws.dq`, `ws.q` and the multiplier start
/// `ws.mu = h² λ/2`; `table` is the stage's difference table (0 for every stage of an order-2
/// step, 1–3 for the stages of an order-4 step, `None` for halved stages). Returns whether the
/// start used the nodal rate (no full table), after which [`Start::Means`] is a different start.
pub(crate) fn predict(
    model: &Model,
    ws: &mut Work,
    h: f64,
    table: Option<usize>,
    start: Start,
) -> bool {
    let nb = model.bodies.len();
    let stride = 6 * nb;
    let (h0, h1) = (ws.hprev[0][0], ws.hprev[0][1]);
    let ratio = if h0 != 0.0 { h / h0 } else { 0.0 };
    let poly = table.filter(|&t| ws.hprev[t].iter().all(|&x| x == h));
    // the means' linear extrapolation factor (0: the last mean alone)
    let slope = if h1 != 0.0 && (h0 + h1).abs() >= h0.abs() {
        (h + h0) / (h0 + h1)
    } else {
        0.0
    };
    let means = start == Start::Means && h0 != 0.0;
    for b in 0..nb {
        let o = 12 * b;
        let (vbar, wbar) = if means {
            let d = |k: usize, i: usize| read3(&ws.hist, k * stride + 6 * b + i);
            (d(0, 0) + d(1, 0) * slope, d(0, 3) + d(1, 3) * slope)
        } else if let Some(t) = poly {
            let at = t * HISTORY * stride;
            extrapolate(&ws.hist[at..at + HISTORY * stride], stride, b, model.lc)
        } else {
            let vphi = read3(&ws.vn, o);
            let mut w = Vec3::zeros();
            for i in 0..3 {
                w += read3(&ws.qn, o + 3 + 3 * i).cross(&read3(&ws.vn, o + 3 + 3 * i));
            }
            w *= 0.5;
            (
                vphi + (vphi - read3(&ws.hist, 6 * b)) * ratio,
                w + (w - read3(&ws.hist, 6 * b + 3)) * ratio,
            )
        };
        let inc = vbar * h;
        write3(&mut ws.dq, o, &inc);
        write3(&mut ws.q, o, &(read3(&ws.qn, o) + inc));
        // the Cayley rotation of θ = h ω̄: cay(θ) − I = 4/(4 + |θ|²) (θ̂ + θ̂²/2), exact and
        // without a trigonometric call (the rotation by 2 atan(|θ|/2) about θ)
        let th = wbar * h;
        // θ̂² = θθᵀ − |θ|² I
        let n2 = th.norm_squared();
        let em1 =
            (skew(&th) + (th * th.transpose() - Mat3::identity() * n2) * 0.5) * (4.0 / (4.0 + n2));
        for i in 0..3 {
            let dn = read3(&ws.qn, o + 3 + 3 * i);
            let inc = em1 * dn;
            write3(&mut ws.dq, o + 3 + 3 * i, &inc);
            write3(&mut ws.q, o + 3 + 3 * i, &(dn + inc));
        }
    }
    for k in 0..ws.mu.len() {
        ws.mu[k] = ws.lam[k] * h * h;
    }
    poly.is_none() && !means && h0 != 0.0
}

/// Body `b`'s next mean rates `(v̄, ω̄)` from its difference table: the degree whose next
/// difference (rates scaled by the characteristic length `lc`: `|v|/lc` and `|ω|`) is least,
/// the lower one on ties (a body at rest).
fn extrapolate(hist: &[f64], stride: usize, b: usize, lc: f64) -> (Vec3, Vec3) {
    let d = |k: usize, i: usize| read3(hist, k * stride + 6 * b + i);
    let ilc2 = 1.0 / (lc * lc);
    let mut best = (f64::INFINITY, 0);
    for p in 0..=MAX_DEGREE {
        // squared sizes (the same order)
        let err = (d(p + 1, 0).norm_squared() * ilc2).max(d(p + 1, 3).norm_squared());
        if err < best.0 {
            best = (err, p);
        }
    }
    let (mut v, mut w) = (Vec3::zeros(), Vec3::zeros());
    for k in 0..=best.1 {
        v += d(k, 0);
        w += d(k, 3);
    }
    (v, w)
}

/// Pushes body `b`'s newest means `m` (6) into its difference table:
/// `∇ᵏm_new = ∇ᵏ⁻¹m_new − ∇ᵏ⁻¹m₀`.
fn push(hist: &mut [f64], stride: usize, b: usize, m: [f64; 6]) {
    let mut carry = m;
    for k in 0..HISTORY {
        for (i, c) in carry.iter_mut().enumerate() {
            let at = k * stride + 6 * b + i;
            let old = hist[at];
            hist[at] = *c;
            *c -= old;
        }
    }
}

/// Records the converged stage of size `h` (`ws.dq`, `ws.theta`) as the newest mean of table 0
/// and of its own `table` (see [`predict`]).
pub(crate) fn record(ws: &mut Work, nb: usize, h: f64, table: Option<usize>) {
    let stride = 6 * nb;
    let own = table.filter(|&t| t != 0);
    for b in 0..nb {
        let o = 12 * b;
        let mut m = [0.0; 6];
        for k in 0..3 {
            m[k] = ws.dq[o + k] / h;
            m[3 + k] = ws.theta[3 * b + k] / h;
        }
        for t in std::iter::once(0).chain(own) {
            let at = t * HISTORY * stride;
            push(&mut ws.hist[at..at + HISTORY * stride], stride, b, m);
        }
    }
    for t in std::iter::once(0).chain(own) {
        ws.hprev[t].copy_within(0..HISTORY - 1, 1);
        ws.hprev[t][0] = h;
    }
}

/// Forgets a table (its stage was halved: its next entry would not be a step later).
pub(crate) fn invalidate(ws: &mut Work, table: usize) {
    ws.hprev[table] = [0.0; HISTORY];
}

#[cfg(test)]
mod tests {
    use super::{extrapolate, push, HISTORY, MAX_DEGREE};

    /// Polynomials of degree ≤ MAX_DEGREE sampled one step apart are extrapolated exactly (the
    /// selection finds the vanishing difference), a sine at 0.1 rad per step to (0.1)⁵ of its
    /// amplitude, a hundredth of the linear extrapolation's error, and the ties of a body at rest give rest.
    #[test]
    fn difference_table_extrapolates_polynomials_exactly() {
        for deg in 0..=MAX_DEGREE as i32 {
            let f = |t: f64| 1.0 + t.powi(deg) * 0.3;
            let mut hist = vec![0.0; 6 * HISTORY];
            for t in -(HISTORY as i32) + 1..=0 {
                let x = f(f64::from(t));
                push(&mut hist, 6, 0, [x, 2.0 * x, 0.0, -x, 0.0, 0.5 * x]);
            }
            let (v, w) = extrapolate(&hist, 6, 0, 1.0);
            let want = f(1.0);
            assert!(
                (v[0] - want).abs() < 1e-12,
                "degree {deg}: {} vs {want}",
                v[0]
            );
            assert!((v[1] - 2.0 * want).abs() < 1e-12 && (w[0] + want).abs() < 1e-12);
            assert!((w[2] - 0.5 * want).abs() < 1e-12);
        }
        let mut hist = vec![0.0; 6 * HISTORY];
        for t in -(HISTORY as i32) + 1..=0 {
            let x = (0.1 * f64::from(t) + 1.0).sin();
            push(&mut hist, 6, 0, [x, 0.0, 0.0, 0.0, 0.0, 0.0]);
        }
        let (v, _) = extrapolate(&hist, 6, 0, 1.0);
        let linear = 2.0 * 1f64.sin() - 0.9f64.sin();
        let err = (v[0] - 1.1f64.sin()).abs();
        assert!(
            err < 2e-5 && err < 1e-2 * (linear - 1.1f64.sin()).abs(),
            "{err:.2e}"
        );
        let (v, w) = extrapolate(&[0.0; 6 * HISTORY], 6, 0, 1.0);
        assert_eq!((v.norm(), w.norm()), (0.0, 0.0));
    }
}
