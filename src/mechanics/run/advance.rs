//! Advancing a run: one step of the integrator (`step::stage::compose`) taken on a copy of the
//! state and committed only when every stage converged, then, for [`step`], the outputs
//! refreshed (`State::refresh_outputs`: the velocity projection and the read-off).
//!
//! `qₙ, vₙ, … → q_{n+1}, v_{n+1}, …` with the inputs, damping and stiffness held over the step;
//! `t ← t + h`. On error the state is exactly as before the call.

use crate::mechanics::model::determinacy::diagnose;
use crate::mechanics::model::runtime::Model;
use crate::mechanics::step::error::StepError;
use crate::mechanics::step::stage::{compose, Composed, Plan, StepStats};
use crate::mechanics::step::work::Held;

use super::control::{above_floor, Verdict};
use super::events::stop_crossing;
use super::state::State;

/// Advances `state` by `h` seconds with the model's order (inputs held constant) and refreshes
/// its outputs ([`step_state`] followed by [`State::refresh_outputs`]). On error the state is
/// unchanged. Allocates nothing.
///
/// # Errors
/// [`StepError`] when Newton fails, a value is not finite, or `h` is not positive.
pub fn step(model: &Model, state: &mut State, h: f64) -> Result<StepStats, StepError> {
    let stats = step_state(model, state, h)?;
    state.refresh_outputs(model);
    Ok(stats)
}

/// Advances `state` by `h` seconds like [`step`] but leaves the outputs as they were: the
/// integrator step alone. A run of several sub-steps per communication step calls this for each
/// and [`State::refresh_outputs`] once at the end (the outputs' velocity projection and energy
/// cost about a quarter of a step). On error the state is unchanged. Allocates nothing.
///
/// # Errors
/// [`StepError`] when Newton fails, a value is not finite, or `h` is not positive.
pub fn step_state(model: &Model, state: &mut State, h: f64) -> Result<StepStats, StepError> {
    let stats = trial(model, state, h)?;
    commit(state, h, &stats);
    Ok(stats)
}

/// One error-controlled attempt of size `h` (`solver.rtol > 0`, see `control`): the step is
/// taken on the workspace and judged by the local error estimate; an accepted step is
/// committed like [`step_state`] (outputs left as they were), a rejected one leaves the state
/// as it was but for the controller's new proposal (`state.control().proposal(model)`). A step
/// within the tolerance that crosses a joint limit (`events`) is not committed either: the
/// verdict [`Verdict::Land`] names the size that ends on the crossing (when it is above the
/// floor `min_step`).
///
/// # Errors
/// As [`step_state`]; the state is then unchanged.
pub fn controlled_step(model: &Model, state: &mut State, h: f64) -> Result<Verdict, StepError> {
    let stats = trial(model, state, h)?;
    let verdict = state.ctrl.judge(model, &state.q, &state.ws, h);
    if verdict == Verdict::Accept {
        let ws = &state.ws;
        if let Some(theta) = stop_crossing(model, &state.q, &state.angles, &ws.qn, &ws.ang) {
            if above_floor(model, theta * h) {
                return Ok(Verdict::Land(theta * h));
            }
        }
        commit(state, h, &stats);
        // the commit swapped the step's start into the workspace
        state.ctrl.record(&state.ws.qn, h);
    }
    Ok(verdict)
}

/// The step of size `h` from the state into its workspace (`ws.qn`, `ws.vn`, … hold the
/// result); the state itself is untouched.
fn trial(model: &Model, state: &mut State, h: f64) -> Result<StepStats, StepError> {
    if !(h.is_finite() && h > 0.0) {
        return Err(StepError::BadStep(h));
    }
    if state.inputs.iter().any(|x| !x.is_finite()) {
        return Err(StepError::NonFinite("inputs"));
    }
    if state
        .damping
        .iter()
        .chain(state.stiffness.iter())
        .chain(state.gains.iter())
        .any(|x| !x.is_finite())
    {
        return Err(StepError::NonFinite("damping, stiffness or actuator gains"));
    }
    let mut stats = StepStats::default();
    let mut outcome = compose_from(model, state, h, Plan::Configured, &mut stats);
    if let Ok(Composed::FedEnergy(j)) = outcome {
        // a damper fed energy in through the backward stage: the step at order 2 (stage docs)
        let stages = model.settings().stages.max(3) as usize;
        stats.order2 = 1;
        stats.stiff_damper = j;
        outcome = compose_from(model, state, h, Plan::Midpoint(stages), &mut stats);
    }
    match outcome {
        Ok(_) => Ok(stats),
        Err(error @ (StepError::NoConvergence { .. } | StepError::Singular)) => {
            // what is known of a failure where the motion is nearly undetermined (cold path)
            Err(match diagnose(model, &state.q) {
                Some(detail) => StepError::NearlyUndetermined {
                    error: Box::new(error),
                    detail,
                },
                None => error,
            })
        }
        Err(e) => Err(e),
    }
}

/// The step of size `h` composed as `plan` says, from the state into its workspace.
fn compose_from(
    model: &Model,
    state: &mut State,
    h: f64,
    plan: Plan,
    stats: &mut StepStats,
) -> Result<Composed, StepError> {
    let ws = &mut state.ws;
    ws.qn.copy_from_slice(&state.q);
    ws.vn.copy_from_slice(&state.v);
    ws.vlo.copy_from_slice(&state.v_lo);
    ws.lam.copy_from_slice(&state.lam);
    ws.ang.copy_from_slice(&state.angles);
    ws.bristle.copy_from_slice(&state.bristle);
    ws.arm.copy_from_slice(&state.arm);
    ws.fric.copy_from_slice(&state.fric);
    ws.work = state.work;
    ws.hist.copy_from_slice(&state.hist);
    ws.hprev = state.hprev;
    ws.memory = state.memory;
    if let Some(t) = ws.tangent.as_mut() {
        t.rewind();
    }
    let held = Held {
        inputs: &state.inputs,
        damping: &state.damping,
        stiffness: &state.stiffness,
        gains: &state.gains,
    };
    compose(model, ws, &held, h, plan, stats)
}

/// Makes the workspace's step (from [`trial`], with its `stats`) the state.
fn commit(state: &mut State, h: f64, stats: &StepStats) {
    if stats.order2 > 0 {
        state.order2.0 += 1;
        state.order2.1 = state.order2.1.or(stats.stiff_damper);
    }
    let ws = &mut state.ws;
    // commit by swapping buffers of equal length (the workspace's copies are overwritten at
    // the start of the next step)
    std::mem::swap(&mut state.q, &mut ws.qn);
    std::mem::swap(&mut state.v, &mut ws.vn);
    std::mem::swap(&mut state.v_lo, &mut ws.vlo);
    std::mem::swap(&mut state.lam, &mut ws.lam);
    std::mem::swap(&mut state.angles, &mut ws.ang);
    std::mem::swap(&mut state.bristle, &mut ws.bristle);
    std::mem::swap(&mut state.arm, &mut ws.arm);
    std::mem::swap(&mut state.fric, &mut ws.fric);
    state.work = ws.work;
    std::mem::swap(&mut state.hist, &mut ws.hist);
    state.hprev = ws.hprev;
    state.memory = ws.memory;
    if let Some(t) = ws.tangent.as_mut() {
        t.accept();
    }
    state.t += h;
}
