//! The Newton start of a stage: the bodies' mean rates over the stage, extrapolated from the
//! history of the previous stages' means.
//!
//! A stage of size `h` moves body `b` by `Δφ = h v̄` and `dᵢ ← cay(h ω̄) dᵢ`. The converged
//! stages' means `mₖ = (Δφ/h, θ/h)` (newest `m₀`) are samples, one step `h` apart, of a smooth
//! function of time, so after [`HISTORY`] stages of the same size the next mean is the
//! polynomial extrapolation of degree `p`:
//!
//! ```text
//! m̂ = Σᵢ₌₁..ₚ₊₁ cₚᵢ mᵢ₋₁,   cₚᵢ = (−1)ⁱ⁺¹ C(p+1, i)
//! (p = 1: 2m₀ − m₁;  p = 2: 3m₀ − 3m₁ + m₂;  p = 3: 4m₀ − 6m₁ + 4m₂ − m₃; …)
//! ```
//!
//! with error `hᵖ⁺¹ m⁽ᵖ⁺¹⁾`: higher degrees win while `h` resolves the motion (`hω ≪ 1`) and
//! lose when it does not (large steps, stiff springs, input jumps). Each body takes the degree
//! (0 ≤ p ≤ [`MAX_DEGREE`]) whose extrapolation of its newest mean from the older ones
//! (`m₀ ≈ Σ cₚᵢ mᵢ`) erred least. With a shorter or unequal history (start, halved stages,
//! the unequal stages of the order-4 composition, a shorter last sub-step) the mean is
//! extrapolated linearly from the nodal rate and the previous mean (first stage: the nodal
//! rate). The predictor sets only the Newton start: the converged stage does not depend on it,
//! a better one saves iterations (chain100 at h = 1e-3: 4.0 iterations per step with the
//! linear start, 2.1 with this one).

use super::assemble::{read3, write3};
use super::kernels::expm1_so3;
use super::model::Model;
use super::work::{Work, HISTORY};
use crate::math::Vec3;

/// Highest extrapolation degree (needs `MAX_DEGREE + 2` stages of history to be judged).
pub const MAX_DEGREE: usize = HISTORY - 2;

/// Extrapolation weights `cₚᵢ` of degree `p` (row `p`, entries `i = 1..=p+1` at `i − 1`).
const WEIGHTS: [[f64; HISTORY - 1]; MAX_DEGREE + 1] = weights();

const fn weights() -> [[f64; HISTORY - 1]; MAX_DEGREE + 1] {
    let mut w = [[0.0; HISTORY - 1]; MAX_DEGREE + 1];
    let mut p = 0;
    while p <= MAX_DEGREE {
        // C(p+1, i) by the multiplicative formula, alternating signs
        let mut c = 1.0;
        let mut i = 1;
        while i <= p + 1 {
            c = c * (p + 2 - i) as f64 / i as f64;
            w[p][i - 1] = if i % 2 == 1 { c } else { -c };
            i += 1;
        }
        p += 1;
    }
    w
}

/// Writes the predictor of a stage of size `h` into `ws.dq`, `ws.q` and the multiplier start
/// `ws.mu = h² λ/2`.
pub(crate) fn predict(model: &Model, ws: &mut Work, h: f64) {
    let nb = model.bodies.len();
    let ratio = if ws.hprev[0] != 0.0 {
        h / ws.hprev[0]
    } else {
        0.0
    };
    let history = ws.hprev.iter().all(|&x| x == h);
    let stride = 6 * nb;
    for b in 0..nb {
        let o = 12 * b;
        let m = |k: usize, i: usize| read3(&ws.hist, k * stride + 6 * b + i);
        let (vbar, wbar) = if history {
            let p = degree(&ws.hist, stride, b, model.lc);
            let mut v = Vec3::zeros();
            let mut w = Vec3::zeros();
            for (i, c) in WEIGHTS[p][..=p].iter().enumerate() {
                v += m(i, 0) * *c;
                w += m(i, 3) * *c;
            }
            (v, w)
        } else {
            let vphi = read3(&ws.vn, o);
            let mut w = Vec3::zeros();
            for i in 0..3 {
                w += read3(&ws.qn, o + 3 + 3 * i).cross(&read3(&ws.vn, o + 3 + 3 * i));
            }
            w *= 0.5;
            (vphi + (vphi - m(0, 0)) * ratio, w + (w - m(0, 3)) * ratio)
        };
        let inc = vbar * h;
        write3(&mut ws.dq, o, &inc);
        write3(&mut ws.q, o, &(read3(&ws.qn, o) + inc));
        // Cayley vector θ = h ω̄ ↔ rotation angle 2 atan(|θ|/2)
        let th = wbar * h;
        let n = th.norm();
        let rv = if n > 0.0 {
            th * (2.0 * (0.5 * n).atan() / n)
        } else {
            th
        };
        let em1 = expm1_so3(&rv);
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
}

/// The degree whose extrapolation of body `b`'s newest mean from its older ones erred least
/// (rates scaled by the characteristic length `lc`: `|Δv̄|/lc` and `|Δω̄|`).
fn degree(hist: &[f64], stride: usize, b: usize, lc: f64) -> usize {
    let m = |k: usize, i: usize| read3(hist, k * stride + 6 * b + i);
    let (v0, w0) = (m(0, 0), m(0, 3));
    let mut best = (f64::INFINITY, 0);
    for (p, row) in WEIGHTS.iter().enumerate() {
        let mut v = v0;
        let mut w = w0;
        for (i, c) in row[..=p].iter().enumerate() {
            v -= m(i + 1, 0) * *c;
            w -= m(i + 1, 3) * *c;
        }
        let err = (v.norm() / lc).max(w.norm());
        // ties (a body at rest) keep the lower degree
        if err < best.0 {
            best = (err, p);
        }
    }
    best.1
}

/// Records the converged stage of size `h` (`ws.dq`, `ws.theta`) as the newest mean of the
/// history.
pub(crate) fn record(ws: &mut Work, nb: usize, h: f64) {
    let stride = 6 * nb;
    ws.hist.copy_within(0..stride * (HISTORY - 1), stride);
    for b in 0..nb {
        let o = 12 * b;
        for k in 0..3 {
            ws.hist[6 * b + k] = ws.dq[o + k] / h;
            ws.hist[6 * b + 3 + k] = ws.theta[3 * b + k] / h;
        }
    }
    ws.hprev.copy_within(0..HISTORY - 1, 1);
    ws.hprev[0] = h;
}

#[cfg(test)]
mod tests {
    use super::weights;

    /// The weights reproduce every polynomial of their degree: extrapolating `t^k` sampled at
    /// `t = 0, −1, −2, …` to `t = 1` gives 1 for `k ≤ p`.
    #[test]
    fn weights_are_exact_for_polynomials() {
        for (p, row) in weights().iter().enumerate() {
            assert_eq!(p, row.iter().filter(|c| **c != 0.0).count() - 1);
            let at = |k: i32| -> f64 {
                row[..=p]
                    .iter()
                    .enumerate()
                    .map(|(i, c)| c * (-(i as f64)).powi(k))
                    .sum()
            };
            for k in 0..=p as i32 {
                let s = at(k);
                assert!((s - 1.0).abs() < 1e-12, "degree {p}, t^{k}: {s}");
            }
            // and not the next power
            let k = p as i32 + 1;
            let s = at(k);
            assert!((s - 1.0).abs() > 0.5, "degree {p} reproduces t^{k}");
        }
    }
}
