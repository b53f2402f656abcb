//! One energy–momentum step (order 2) or its triple-jump composition (order 4).
//!
//! PLACEHOLDER written at project set-up; the mechanics work replaces it.

use super::error::StepError;
use super::model::Model;
use super::state::State;

/// Statistics of one step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StepStats {
    /// Newton iterations over all stages.
    pub iterations: usize,
    /// Final scaled residual.
    pub residual: f64,
}

/// Advances `state` by `h` seconds with the model's order; inputs are held constant.
/// On error the state is unchanged. Allocates nothing.
///
/// # Errors
/// [`StepError`] when Newton fails, a value is not finite, or `h` is not positive.
pub fn step(model: &Model, state: &mut State, h: f64) -> Result<StepStats, StepError> {
    let _ = model;
    if !(h.is_finite() && h > 0.0) {
        return Err(StepError::BadStep(h));
    }
    state.set_time(state.time() + h);
    Ok(StepStats::default())
}
