//! Error control of the internal step (`solver.rtol > 0`): the step size is chosen from an
//! estimate of the local error; every step taken is still an energy–momentum step, so
//! `energy − work`, the momenta and the torque balance stay exact whatever the sizes.
//!
//! **Estimate.** The local error of a step of size `h` is set by a derivative of the motion,
//! estimated from divided differences of the coordinates themselves at the ends of the trial
//! step and of the last accepted ones (kept: [`SAMPLES`]), over their unequal spacing, so a
//! change of step size costs nothing:
//!
//! ```text
//! order 2 (midpoint):     e ≈ C₂ h³ |q⁽³⁾|,  q⁽³⁾ ≈ 3! q[tₙ₊₁, tₙ, tₙ₋₁, tₙ₋₂]     C₂ = 1/12
//! order 4 (composition):  e ≈ C₄ h⁵ |q⁽⁵⁾|,  q⁽⁵⁾ ≈ 5! q[tₙ₊₁, …, tₙ₋₄]            C₄ = 6.6e-2 (triple jump), 9.3e-4 (Suzuki)
//! ```
//!
//! (`C` the local error of the scheme on `y' = iωy` per `(ωh)^{p+1}`, for every nodal
//! coordinate: body positions and directors). Differences of positions, not of velocities:
//! the nodal velocity's component normal to the constraints flips sign every step
//! (`vₙ₊₁ = 2(qₙ₊₁ − qₙ)/h − vₙ`), and mean velocities `(qₙ₊₁ − qₙ)/h` taken as point values
//! at the midpoints carry an `h²q⁽³⁾/24` that differs from step to step; both would swamp a
//! high difference and make a shorter step look worse.
//!
//! The error of body
//! `b` is the largest of its directors' (rad) and of its position's over the characteristic
//! length `lc` (1); it is measured per unit time, so that the global error is proportional to
//! the tolerance:
//!
//! ```text
//! E = max_b  e_b / ((atol + rtol·max(1, |φ_b|/lc)) · h / 1 s)
//! ```
//!
//! **Controller.** A step with `E > 1` is rejected (nothing is written) and retried at
//! `h·max(0.2, 0.9 E^{-1/p})`; an accepted one proposes `h·clamp(0.9 E^{-1/p}, 0.2, 5)` for the
//! next, kept unchanged for factors in `[1, 1.5)` so that runs of equal steps keep the
//! predictor's polynomial extrapolation (it needs equal steps). The step stays within
//! `[min_step, max_step]`; a step the estimate wants below the floor is taken at the floor and
//! accepted (counted in [`Control::floor_steps`]). Until enough samples exist (a run's first
//! steps: 2 at order 2, 4 at order 4) steps start at `max_step·tol^{1/p}` and double.
//!
//! **Noise.** The part of a difference that the coordinates' noise (the Newton iterate's
//! error) could explain is not counted. When the noise could make a tenth of the tolerance or
//! more, the estimate cannot tell a good step from a bad one; the noise per unit time falls as
//! `1/h`, so such a step grows by doubling at most until the estimate is informative again.
//!
//! The controller's memory (proposal, samples) is part of the state and of its snapshot, so a
//! restored state continues bit-identically.

use crate::mechanics::model::runtime::Model;
use crate::mechanics::step::newton::Work;

/// Earlier step ends kept besides the current state (order 4 needs four).
pub const SAMPLES: usize = 4;

/// Local error of the EM midpoint step per `h³ |q⁽³⁾|`.
const C2: f64 = 1.0 / 12.0;
/// Local error of the triple jump per `h⁵ |q⁽⁵⁾|`.
const C4_TRIPLE: f64 = 6.6e-2;
/// Local error of Suzuki's five-stage composition per `h⁵ |q⁽⁵⁾|`.
const C4_SUZUKI: f64 = 9.3e-4;
/// The noise of the coordinates as a share of the Newton tolerance (module docs).
const NOISE_SHARE: f64 = 1e-3;
/// The first step of a run as a share of `max_step·tol^{1/p}`: its first steps are taken
/// without an estimate (there are no samples yet), so they start short and double.
const START_SHARE: f64 = 1e-2;
/// A step whose estimate the noise could have made this share of the tolerance or more does
/// not grow the next.
const NOISY: f64 = 0.1;
/// Most a noise-dominated estimate may grow the step.
const NOISY_GROW: f64 = 2.0;
/// Safety factor of the proposed step.
const SAFETY: f64 = 0.9;
/// Most a step may shrink, and grow, from one to the next.
const SHRINK: f64 = 0.2;
const GROW: f64 = 5.0;
/// Growth factors below this keep the proposal unchanged.
const DEAD_BAND: f64 = 1.5;

/// The controller's memory; see the module docs.
#[derive(Clone, Debug, PartialEq)]
pub struct Control {
    /// Proposed next step, s (0: none yet).
    pub(crate) h_next: f64,
    /// Samples held, newest first (0 ..= [`SAMPLES`]).
    pub(crate) count: usize,
    /// Times of the samples relative to the current state's time, newest first, s (< 0).
    pub(crate) tmid: [f64; SAMPLES],
    /// The samples' coordinates, `[sample][12 per body]`, m and 1.
    pub(crate) acc: Vec<f64>,
    /// Steps accepted at the floor `min_step` with an estimate above the tolerance.
    pub(crate) floor_steps: u64,
}

impl Control {
    /// Makes this memory equal to `src`'s (the scratch aside), reusing its allocations.
    pub(crate) fn copy_from(&mut self, src: &Control) {
        self.h_next = src.h_next;
        self.count = src.count;
        self.tmid = src.tmid;
        self.acc.clone_from(&src.acc);
        self.floor_steps = src.floor_steps;
    }

    /// Steps accepted at the floor `solver.min_step` although their error estimate was above
    /// the tolerance, since the start of the run.
    #[must_use]
    pub fn floor_steps(&self) -> u64 {
        self.floor_steps
    }
}

/// The outcome of one controlled attempt.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Verdict {
    /// The estimate is within the tolerance (or the step is at the floor): commit it.
    Accept,
    /// The estimate exceeds the tolerance: discard it and retry at [`Control::proposal`].
    Reject,
    /// The step crosses a joint limit (entering or leaving a stop contact, `run::events`):
    /// discard it and retry with exactly this size, s, which ends where the crossing is.
    Land(f64),
}

impl Control {
    /// An empty memory for `model` (no samples, no proposal); the samples are allocated only
    /// when `solver.rtol > 0`, so a fixed-step run's roll-back copy and snapshot carry none.
    #[must_use]
    pub fn new(model: &Model) -> Self {
        let n = if model.settings().rtol > 0.0 {
            12 * model.bodies.len()
        } else {
            0
        };
        Self {
            h_next: 0.0,
            count: 0,
            tmid: [0.0; SAMPLES],
            acc: vec![0.0; SAMPLES * n],
            floor_steps: 0,
        }
    }

    /// Numbers in [`Control::write_f64`].
    #[must_use]
    pub(crate) fn snapshot_len(&self) -> usize {
        3 + SAMPLES + self.acc.len()
    }

    /// The memory as numbers: `[h_next, count, floor_steps, tmid.., acc..]`.
    pub(crate) fn write_f64(&self, out: &mut Vec<f64>) {
        out.push(self.h_next);
        out.push(self.count as f64);
        out.push(self.floor_steps as f64);
        out.extend_from_slice(&self.tmid);
        out.extend_from_slice(&self.acc);
    }

    /// Reads [`Control::write_f64`] back.
    ///
    /// # Errors
    /// A wrong length, a count out of range, or a non-finite or out-of-range value.
    pub(crate) fn read_f64(&mut self, data: &[f64]) -> Result<(), String> {
        if data.len() != self.snapshot_len() {
            return Err("step control memory has the wrong length".into());
        }
        let (h, count, floor) = (data[0], data[1], data[2]);
        if !(h.is_finite() && h >= 0.0) {
            return Err(format!("step control: proposed step {h} is not a step"));
        }
        if !(count.fract() == 0.0 && (0.0..=SAMPLES as f64).contains(&count)) {
            return Err(format!(
                "step control: sample count {count} is out of range"
            ));
        }
        if !(floor.fract() == 0.0 && (0.0..9e15).contains(&floor)) {
            return Err(format!("step control: floor count {floor} is out of range"));
        }
        let rest = &data[3..];
        if rest.iter().any(|x| !x.is_finite()) || rest[..SAMPLES].iter().any(|&t| t > 0.0) {
            return Err("step control: a sample is not finite or lies in the future".into());
        }
        self.h_next = h;
        self.count = count as usize;
        self.floor_steps = floor as u64;
        self.tmid.copy_from_slice(&rest[..SAMPLES]);
        self.acc.copy_from_slice(&rest[SAMPLES..]);
        Ok(())
    }

    /// The size the next step should have, s: the controller's proposal, or, before any,
    /// the starting size `max_step·tol^{1/p}`; within `[min_step, max_step]`.
    #[must_use]
    pub fn proposal(&self, model: &Model) -> f64 {
        let s = model.settings();
        let h = if self.h_next > 0.0 {
            self.h_next
        } else {
            let p = f64::from(s.order);
            START_SHARE * s.max_step * (s.rtol + s.atol).min(1.0).powf(1.0 / p)
        };
        clamp_step(model, h)
    }

    /// Judges the trial step of size `h` held in `ws` (from the state's `q`) and sets the next
    /// proposal; on [`Verdict::Accept`] the caller commits the step and calls
    /// [`Control::record`].
    pub(crate) fn judge(&mut self, model: &Model, q: &[f64], ws: &Work, h: f64) -> Verdict {
        let s = model.settings();
        let needed = if s.order == 4 { SAMPLES } else { 2 };
        if self.count < needed {
            // no estimate yet: accept and double (from the start size)
            self.h_next = clamp_step(model, self.h_next.max(2.0 * h));
            return Verdict::Accept;
        }
        let (e, noise) = self.error(model, &ws.qn, q, h, needed);
        let p = f64::from(s.order);
        let mut fac = if e > 0.0 {
            (SAFETY * e.powf(-1.0 / p)).clamp(SHRINK, GROW)
        } else {
            GROW
        };
        if noise > NOISY {
            // the differences are mostly the coordinates' noise, which a longer step makes
            // smaller (per unit time it is ∝ 1/h): grow by doubling at most, until the estimate
            // is informative again (held, a step this short would stay here for good)
            fac = fac.min(NOISY_GROW);
        }
        if e > 1.0 && above_floor(model, h) {
            self.h_next = clamp_step(model, h * fac.min(SAFETY));
            return Verdict::Reject;
        }
        if e > 1.0 {
            self.floor_steps += 1;
        }
        let grown = h * fac;
        self.h_next = clamp_step(
            model,
            if fac < 1.0 {
                grown
            } else if fac >= DEAD_BAND {
                grown.max(self.h_next)
            } else {
                self.h_next.max(h)
            },
        );
        Verdict::Accept
    }

    /// After a step of size `h` failed (Newton did not converge), proposes a quarter of it.
    pub(crate) fn shrink_after_failure(&mut self, model: &Model, h: f64) {
        self.h_next = clamp_step(model, 0.25 * h);
    }

    /// After an accepted step of size `h` from `q_start`: keeps `q_start` as the newest
    /// sample, at `−h` from the new state, the older ones moved back by `h`.
    pub(crate) fn record(&mut self, q_start: &[f64], h: f64) {
        let n = q_start.len();
        self.acc.copy_within(0..(SAMPLES - 1) * n, n);
        self.acc[..n].copy_from_slice(q_start);
        self.tmid.copy_within(0..SAMPLES - 1, 1);
        for t in &mut self.tmid[1..] {
            *t -= h;
        }
        self.tmid[0] = -h;
        self.count = (self.count + 1).min(SAMPLES);
    }

    /// The error measure `E` of the trial step (module docs) from its end `q1` (at `h`), its
    /// start `q0` (at 0) and the newest `needed` samples.
    /// With it, the largest share of the tolerance that the noise alone could make of the
    /// estimate (`E` counts only what it cannot explain).
    fn error(&self, model: &Model, q1: &[f64], q0: &[f64], h: f64, needed: usize) -> (f64, f64) {
        let s = model.settings();
        let n = q0.len();
        let lc = model.lc;
        let (c, p) = match (s.order, s.stages) {
            (4, 5) => (C4_SUZUKI * 120.0, 4),
            (4, _) => (C4_TRIPLE * 120.0, 4),
            _ => (C2 * 6.0, 2),
        };
        // nodes: the trial's end, its start, then the samples (`needed + 2` in all)
        let mut t = [0.0; SAMPLES + 2];
        t[0] = h;
        t[2..needed + 2].copy_from_slice(&self.tmid[..needed]);
        let m = needed + 1;
        // the most a difference of data each within ±1 of the truth can be off: Σⱼ 1/Πₖ|tⱼ − tₖ|
        let mut gain = 0.0;
        for j in 0..=m {
            let mut prod = 1.0;
            for k in 0..=m {
                if k != j {
                    prod *= (t[j] - t[k]).abs();
                }
            }
            gain += 1.0 / prod;
        }
        // the coordinates' noise: the Newton iterate's error (measured ≈ 1e-13 at the default
        // tolerance 1e-10) or round-off
        let noise = (NOISE_SHARE * s.tolerance).max(64.0 * f64::EPSILON);
        let hp1 = h.powi(p + 1);
        let mut worst: f64 = 0.0;
        let mut noisy: f64 = 0.0;
        for b in 0..n / 12 {
            let phi = (q1[12 * b].powi(2) + q1[12 * b + 1].powi(2) + q1[12 * b + 2].powi(2)).sqrt();
            let tol = s.atol + s.rtol * (phi / lc).max(1.0);
            let mut eb: f64 = 0.0;
            for i in 0..12 {
                let k = 12 * b + i;
                // Newton divided differences of order m over the nodes t[0..=m]
                let mut f = [0.0; SAMPLES + 2];
                f[0] = q1[k];
                f[1] = q0[k];
                for j in 0..needed {
                    f[j + 2] = self.acc[j * n + k];
                }
                for level in 1..=m {
                    for j in 0..=m - level {
                        f[j] = (f[j] - f[j + 1]) / (t[j] - t[j + level]);
                    }
                }
                // only the part of the difference that the noise cannot explain
                let scale = q1[k].abs().max(1.0) * if i < 3 { lc } else { 1.0 };
                let floor = c * hp1 * noise * scale * gain;
                let e = (c * hp1 * f[0].abs() - floor).max(0.0);
                noisy = noisy.max(floor / tol);
                eb = eb.max(if i < 3 { e / lc } else { e });
            }
            worst = worst.max(eb / tol);
        }
        (worst / h, noisy / h)
    }
}

/// The floor of the step, s: `min_step`, never above the ceiling `max_step`.
fn step_floor(model: &Model) -> f64 {
    let s = model.settings();
    s.min_step.min(s.max_step)
}

/// Whether a step of size `h` may still be shortened (it is above the floor).
#[must_use]
pub fn above_floor(model: &Model, h: f64) -> bool {
    h > step_floor(model) * (1.0 + 1e-12)
}

/// `h` within `[floor, max_step]`.
fn clamp_step(model: &Model, h: f64) -> f64 {
    h.min(model.settings().max_step).max(step_floor(model))
}
