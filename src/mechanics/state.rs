//! The mutable state: time, coordinates, velocities, inputs, tunable parameters, outputs and the
//! preallocated Newton workspace.
//!
//! PLACEHOLDER written at project set-up: the public items are the contract; the mechanics work
//! replaces the bodies.

use super::model::Model;
use super::outputs::Outputs;

/// State of one simulation run. `Clone` is a complete snapshot.
#[derive(Clone, Debug)]
pub struct State {
    t: f64,
    inputs: Vec<f64>,
    damping: Vec<f64>,
    stiffness: Vec<f64>,
    outputs: Outputs,
}

impl State {
    /// The initial state of `model` at t = 0 (outputs computed).
    #[must_use]
    pub fn new(model: &Model) -> Self {
        let def = model.def();
        Self {
            t: 0.0,
            inputs: vec![0.0; model.inputs().len()],
            damping: def.joints.iter().map(|j| j.damping).collect(),
            stiffness: def.joints.iter().map(|j| j.stiffness).collect(),
            outputs: Outputs::default(),
        }
    }

    /// Current time, s.
    #[must_use]
    pub fn time(&self) -> f64 {
        self.t
    }

    /// Sets the current time (e.g. the FMI start time) without changing anything else.
    pub fn set_time(&mut self, t: f64) {
        self.t = t;
    }

    /// Input values in the order of `Model::inputs` (held constant over each step).
    #[must_use]
    pub fn inputs(&self) -> &[f64] {
        &self.inputs
    }

    /// Mutable input values.
    pub fn inputs_mut(&mut self) -> &mut [f64] {
        &mut self.inputs
    }

    /// Damping of joint `j` (tunable).
    #[must_use]
    pub fn damping(&self, j: usize) -> f64 {
        self.damping[j]
    }

    /// Sets the damping of joint `j`.
    pub fn set_damping(&mut self, j: usize, c: f64) {
        self.damping[j] = c;
    }

    /// Stiffness of joint `j` (tunable).
    #[must_use]
    pub fn stiffness(&self, j: usize) -> f64 {
        self.stiffness[j]
    }

    /// Sets the stiffness of joint `j`.
    pub fn set_stiffness(&mut self, j: usize, k: f64) {
        self.stiffness[j] = k;
    }

    /// Outputs at the current time.
    #[must_use]
    pub fn outputs(&self) -> &Outputs {
        &self.outputs
    }

    /// Every number that determines the future of this state (time, q, v, multipliers used as
    /// the Newton start, inputs, tunable parameters, accumulated work, unwrapping memory), flat.
    #[must_use]
    pub fn snapshot(&self) -> Vec<f64> {
        let mut out = vec![self.t];
        out.extend_from_slice(&self.inputs);
        out
    }

    /// Restores a [`State::snapshot`] taken from a state of the same model; recomputes outputs.
    ///
    /// # Errors
    /// A message if the length does not match the model.
    pub fn restore(&mut self, model: &Model, data: &[f64]) -> Result<(), String> {
        if data.len() != 1 + model.inputs().len() {
            return Err(format!(
                "snapshot length {} does not match the model",
                data.len()
            ));
        }
        self.t = data[0];
        self.inputs.copy_from_slice(&data[1..]);
        Ok(())
    }
}
