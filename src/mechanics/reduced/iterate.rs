//! The reduced Newton iteration of one stage: chord iterations on the factors of one Jacobian
//! pass, accepted when the estimated distance to the solution is at round-off.
//!
//! The Newton matrix leaves out the constraint forces' geometric stiffness, so every iterate
//! (the first one included) converges linearly at the observed contraction `θ = |δₖ|/|δₖ₋₁|`;
//! the distance of the updated iterate to the solution is about `θ|δₖ|/(1 − θ)`. It must be
//! below the round-off bound of the multiplier form's chord iterates (`chord_accept`), since the
//! conservation laws hold only as far as the equations are solved. A slow contraction
//! refactors once at the current iterate; a stage that still does not contract, or exceeds
//! the iteration budget, returns `NoConvergence` and is redone by the multiplier form.

use super::super::model::Model;
use super::super::work::{Held, Work};
use super::eval::balanced;
use super::{evaluate, factor, prepare, solve, update, RedWork};
use crate::mechanics::StepError;

/// Contraction above which the factors are refreshed.
const REFACTOR: f64 = 0.1;

/// Contraction after a fresh factorisation above which the stage is handed back.
const GIVE_UP: f64 = 0.5;

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
    match out {
        Ok(c) if !balanced(model, ws, held, h) => Err(StepError::NoConvergence {
            iterations: c.iterations,
            residual: f64::NAN,
        }),
        other => other,
    }
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
    let maxit = model.settings().max_iterations.min(MAX_IT);
    let (mut it, mut factorizations) = (0, 0);
    let mut fresh = true;
    let mut since_factor = 0;
    let mut prev = f64::INFINITY;
    let mut best = f64::INFINITY;
    let tol = model.settings().tolerance;
    loop {
        it += 1;
        let res = evaluate(model, ws, rw, held, h, fresh);
        if !res.is_finite() {
            return Err(StepError::NonFinite("state"));
        }
        if fresh {
            factorizations += 1;
            since_factor = 0;
            if !factor(model, rw) {
                return Err(StepError::Singular);
            }
        }
        since_factor += 1;
        solve(model, rw);
        let upd = update(model, rw, ws);
        if !upd.is_finite() {
            return Err(StepError::NonFinite("state"));
        }
        if upd <= chord_accept {
            return Ok(Converged {
                iterations: it,
                factorizations,
                error: upd,
            });
        }
        let theta = upd / prev;
        if it > 1 && theta < 1.0 {
            let err = theta / (1.0 - theta) * upd;
            if theta <= GIVE_UP && err <= chord_accept {
                return Ok(Converged {
                    iterations: it,
                    factorizations,
                    error: err,
                });
            }
        }
        // the round-off floor: after contracting well the updates stop shrinking at a size set
        // by the number of bodies (as in the multiplier form's chord iterations)
        best = best.min(theta);
        if it > 1 && theta >= 0.5 && best <= REFACTOR && upd <= 1e-2 * tol {
            return Ok(Converged {
                iterations: it,
                factorizations,
                error: upd,
            });
        }
        if it >= maxit || (theta > GIVE_UP && since_factor == 1 && it > 1) {
            return Err(StepError::NoConvergence {
                iterations: it,
                residual: res.max(upd),
            });
        }
        fresh = theta > REFACTOR && it > 1;
        if fresh {
            best = f64::INFINITY;
        }
        prev = upd;
    }
}
