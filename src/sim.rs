//! One simulation run shared by `triad simulate` and the FMU: communication steps made of equal
//! internal sub-steps, with roll-back on failure. Both front ends call this, so their results are
//! identical by construction.

use crate::mechanics::{step_state, Model, ModelDef, ModelError, SolverSettings, State, StepError};

/// Why a communication step stopped short.
#[derive(Debug, Clone, PartialEq)]
pub struct AdvanceError {
    /// The sub-step failure.
    pub error: StepError,
    /// Time of the last good state, to which the run was rolled back, s.
    pub last_good_time: f64,
}

/// A running simulation: the model and its state.
#[derive(Clone, Debug)]
pub struct Simulation {
    model: Model,
    state: State,
    /// State at the start of the current communication step (roll-back target).
    saved: State,
    /// Whether a clamped actuator input has been reported ([`Simulation::clamp_notice`]).
    clamp_noticed: bool,
}

impl Simulation {
    /// Builds the model and its initial state at `start_time`.
    ///
    /// # Errors
    /// [`ModelError`] from [`Model::new`].
    pub fn new(
        def: &ModelDef,
        settings: SolverSettings,
        start_time: f64,
    ) -> Result<Self, ModelError> {
        let model = Model::new(def, settings)?;
        let mut state = State::new(&model);
        state.set_time(start_time);
        let saved = state.clone();
        Ok(Self {
            model,
            state,
            saved,
            clamp_noticed: false,
        })
    }

    /// The first time an actuator input exceeds its joint's effort limit (the step applies it
    /// clamped to ±effort), a message naming the joint; `None` before and ever after: a clamp is
    /// reported once per run. Call it after setting the inputs of a communication step.
    pub fn clamp_notice(&mut self) -> Option<String> {
        if self.clamp_noticed {
            return None;
        }
        let msg = self.model.clamped_input(self.state.inputs())?;
        self.clamp_noticed = true;
        Some(msg)
    }

    /// The model.
    #[must_use]
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The current state.
    #[must_use]
    pub fn state(&self) -> &State {
        &self.state
    }

    /// Recomputes the outputs from the current state (after a tunable parameter changed
    /// between communication steps).
    pub fn refresh_outputs(&mut self) {
        self.state.refresh_outputs(&self.model);
    }

    /// The current state, mutable (inputs, tunable parameters, restoring snapshots).
    pub fn state_mut(&mut self) -> &mut State {
        &mut self.state
    }

    /// Current time, s.
    #[must_use]
    pub fn time(&self) -> f64 {
        self.state.time()
    }

    /// Number of equal sub-steps used for a communication step `h`: `ceil(h / max_step)`
    /// (at least 1), with a relative slack of 1e-9 so that `h = k·max_step` takes exactly k.
    #[must_use]
    pub fn substeps(&self, h: f64) -> usize {
        let ratio = h / self.model.settings().max_step;
        let n = (ratio * (1.0 - 1e-9)).ceil();
        if n.is_finite() && n >= 1.0 {
            n as usize
        } else {
            1
        }
    }

    /// Advances by the communication step `h` in `substeps(h)` equal sub-steps, landing on
    /// `t + h` exactly (the last sub-step ends at the float `t + h`). Inputs are held constant.
    ///
    /// # Errors
    /// On a failed sub-step the state is rolled back to the start of this communication step and
    /// the error says why.
    pub fn advance(&mut self, h: f64) -> Result<(), AdvanceError> {
        self.advance_state(h)?;
        // outputs once per communication step, after the last sub-step
        self.state.refresh_outputs(&self.model);
        Ok(())
    }

    /// [`Simulation::advance`] without the refresh of the outputs (velocity projection, energy,
    /// momenta, joint coordinates: about a third of a chain's step): the outputs keep the values
    /// of the last refresh until [`Simulation::refresh_outputs`] or an [`Simulation::advance`].
    /// For drivers that step several times between reading outputs.
    ///
    /// # Errors
    /// As [`Simulation::advance`].
    pub fn advance_state(&mut self, h: f64) -> Result<(), AdvanceError> {
        let t0 = self.state.time();
        if !(h.is_finite() && h > 0.0) {
            return Err(AdvanceError {
                error: StepError::BadStep(h),
                last_good_time: t0,
            });
        }
        let n = self.substeps(h);
        // `step` leaves the state untouched when it fails, so only a communication step of
        // several sub-steps needs its own roll-back copy
        if n > 1 {
            self.saved.clone_from(&self.state);
        }
        let dt = h / n as f64;
        let t_end = t0 + h;
        for k in 0..n {
            if let Err(error) = step_state(&self.model, &mut self.state, dt) {
                if k > 0 {
                    self.state.clone_from(&self.saved);
                }
                return Err(AdvanceError {
                    error,
                    last_good_time: t0,
                });
            }
        }
        self.state.set_time(t_end);
        Ok(())
    }
}
