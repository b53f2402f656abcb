//! The reduced Newton iteration of one stage: a Newton iteration (matrix assembled and
//! factored) followed by chord iterations on its factors, accepted when the estimated distance
//! to the solution is at round-off.
//!
//! The matrix is the exact Jacobian for turning pairs (slides: see `eval`), so the first chord
//! update is about quadratic in the first one, and later ones contract linearly at the observed
//! `θ = |δₖ|/|δₖ₋₁|`; the distance of the updated iterate to the solution is about
//! `θ|δₖ|/(1 − θ)`. It must be below the round-off bound of the multiplier form's chord iterates
//! (`chord_accept`), since the conservation laws hold only as far as the equations are solved.
//! Rules:
//! - a contraction slower than [`REFACTOR`] refreshes the matrix at the current iterate, unless
//!   the updates are at the round-off floor (there a slow ratio is noise);
//! - a first update above [`REFRESH_FIRST`] (a poor predictor: large steps of fast motion)
//!   refreshes the matrix at the second iteration (Newton twice, then chords);
//! - when chord iterations stopped contracting, the next [`EAGER_STAGES`] stages refresh the
//!   matrix at their second iteration too (long chains: the reduced equations are strongly
//!   nonlinear, and chords from the predictor diverge where chords from the first Newton
//!   iterate converge);
//! - a fresh matrix whose first chord update contracts slower than [`GIVE_UP`], or the
//!   iteration budget, returns `NoConvergence`: the stage is redone by the multiplier form.

use super::super::work::{Held, Work, FACTOR_EFFORT};
use super::couple;
use super::eval::evaluate;
use super::place::{defects, prepare, size, update};
use super::tree::{factor, solve};
use super::work::RedWork;
use crate::mechanics::model::runtime::Model;
use crate::mechanics::step::error::StepError;

/// Contraction above which the factors are refreshed.
const REFACTOR: f64 = 0.1;

/// Contraction after a fresh factorisation above which the stage is handed back.
const GIVE_UP: f64 = 0.5;

/// A first update from the predictor above this refreshes the matrix at the second
/// iteration. The chord rate is about proportional to the distance between the iterate the
/// matrix was formed at and the solution (a free body at h = 0.1, Suzuki's stages: first
/// updates 3e-2, then a steady `θ ≈ 5e-3`, 7–8 iterations per stage), so from a poor
/// predictor the matrix formed one update later contracts at about `θ²` and the stage
/// converges in about 4–5 iterations, 2 of them with a fresh matrix. Instruction counts
/// (callgrind, order 4, five stages, against chords on the first matrix only): heavy top
/// h = 0.05 −12 %, free body h = 0.1 −11 %, chain10 h = 0.01 −9 %, UR5 h = 0.05 −16 %,
/// double pendulum h = 0.02 −6 %; within ±1 % where first updates stay small (and chain100
/// at h = 1e-3, order 2, unchanged). 1e-4 gains a few % more on the articulated models but
/// costs a free body at h = 0.05 +8 % (a 6 × 6 factorisation for ≈ 1 chord iteration saved).
const REFRESH_FIRST: f64 = 1e-3;

/// Stages that refresh the matrix at their second iteration after chord iterations of a stage
/// stopped contracting.
const EAGER_STAGES: u32 = 16;

/// A first (Newton) update from the predictor below `ONE_NEWTON · √chord_accept` (at a residual
/// below the tolerance) is accepted without a second residual when the Newton matrix is the
/// exact Jacobian (no slide pair): it leaves an error of about `C |δ|² ≤ C · 1e-4 ·
/// chord_accept`, below `chord_accept` while the quadratic constant `C` of the scaled reduced
/// equations is below 1e4. Measured `C = |δ₂|/|δ₁|²`: heavy top 0.2, double pendulum 1.9,
/// chain10 3, chain100 48, chain1000 250. The double pendulum at h = 1e-3, whose predictor
/// is within 3e-13, then mostly converges in one iteration per step instead of two. The
/// residual condition matters: an update solved from a large residual carries that residual's
/// evaluation round-off (accepted without it under `C ≤ 2·depth`, chain100's first updates,
/// from residuals of 2e-5, made its energy balance over 8000 steps 10× worse).
const ONE_NEWTON: f64 = 1e-2;

/// Iterations after which the stage is handed back.
const MAX_IT: usize = 12;

/// Outcome of a converged stage: iterations, factorisations, estimated error.
pub(crate) struct Converged {
    /// Iterations (residual evaluations and solves).
    pub iterations: usize,
    /// Jacobian passes with a factorisation among them.
    pub factorizations: usize,
    /// Estimated scaled distance of the accepted iterate to the solution.
    pub error: f64,
}

/// Runs the reduced iteration of a stage of size `h` from the predictor in `ws.dq`, `ws.q`;
/// on success `ws.q`, `ws.dq` hold the converged iterate.
///
/// # Errors
/// `NoConvergence` (slow contraction or budget), `Singular`, `NonFinite`.
pub(crate) fn newton(
    model: &Model,
    ws: &mut Work,
    held: &Held,
    h: f64,
    chord_accept: f64,
) -> Result<Converged, StepError> {
    let mut rw = std::mem::take(&mut ws.red);
    let out = run(model, ws, &mut rw, held, h, chord_accept);
    ws.red = rw;
    out
}

/// The estimated error if the iterate updated by `upd` (at iteration `it`, from the residual
/// `res`, contracting at `theta`, at best at `best` so far) is accepted.
fn accepted(
    model: &Model,
    it: usize,
    res: f64,
    upd: f64,
    theta: f64,
    best: f64,
    chord_accept: f64,
) -> Option<f64> {
    let tol = model.settings().tolerance;
    // the first Newton update with the exact Jacobian leaves an error of about C·|δ|²
    if it == 1 && model.exact_reduced && res <= tol && upd <= ONE_NEWTON * chord_accept.sqrt() {
        return Some(upd * upd);
    }
    if upd <= chord_accept {
        return Some(upd);
    }
    if it > 1 && theta < 1.0 {
        let err = theta / (1.0 - theta) * upd;
        if theta <= GIVE_UP && err <= chord_accept {
            return Some(err);
        }
    }
    // the round-off floor: after contracting well the updates stop shrinking at a size set by
    // the number of bodies (as in the multiplier form's chord iterations)
    (it > 1 && theta >= 0.5 && best <= REFACTOR && upd <= 1e-2 * tol).then_some(upd)
}

fn run(
    model: &Model,
    ws: &mut Work,
    rw: &mut RedWork,
    held: &Held,
    h: f64,
    chord_accept: f64,
) -> Result<Converged, StepError> {
    prepare(model, rw, ws);
    // after chord iterations stopped contracting, the next stages refresh the matrix at the
    // second iteration too (Newton twice, then chords from a closer iterate)
    let eager = ws.memory.eager > 0;
    ws.memory.eager = ws.memory.eager.saturating_sub(1);
    let maxit = model.settings().max_iterations.min(MAX_IT);
    let (mut it, mut factorizations) = (0, 0);
    let mut fresh = true;
    let mut since_factor = 0;
    let mut prev = f64::INFINITY;
    let mut best = f64::INFINITY;
    let tol = model.settings().tolerance;
    loop {
        it += 1;
        let mut res = evaluate(model, ws, rw, held, h, fresh);
        if !res.is_finite() {
            return Err(StepError::NonFinite("state"));
        }
        ws.effort += 1 + if fresh { FACTOR_EFFORT } else { 0 };
        if fresh {
            factorizations += 1;
            since_factor = 0;
            if !factor(model, rw) || !couple::factor(model, rw) {
                return Err(StepError::Singular);
            }
        }
        since_factor += 1;
        defects(model, rw);
        couple::keep(rw);
        solve(model, rw);
        couple::correct(model, ws, rw);
        res = res.max(couple::residual(model, rw));
        let upd = size(model, rw);
        if !upd.is_finite() {
            return Err(StepError::NonFinite("state"));
        }
        let theta = upd / prev;
        if it > 1 {
            best = best.min(theta);
        }
        let accept = accepted(model, it, res, upd, theta, best, chord_accept);
        if accept.is_none() && (it >= maxit || (theta > GIVE_UP && since_factor == 2)) {
            return Err(StepError::NoConvergence {
                iterations: it,
                residual: res.max(upd),
            });
        }
        update(model, rw, ws);
        if let Some(error) = accept {
            return Ok(Converged {
                iterations: it,
                factorizations,
                error,
            });
        }
        if theta > REFACTOR && since_factor >= 2 && it > 2 && upd > 1e-2 * tol {
            ws.memory.eager = EAGER_STAGES;
        }
        // at the round-off floor a slow ratio is noise, not a stale matrix
        let floor = upd <= 1e-2 * tol;
        fresh =
            (theta > REFACTOR && it > 1 && !floor) || (it == 1 && (eager || upd > REFRESH_FIRST));
        prev = upd;
    }
}
