//! The mutable state: time, coordinates, velocities, inputs, tunable parameters, outputs and the
//! preallocated Newton workspace.

use super::control::Control;
use super::outputs::Outputs;
use crate::mechanics::model::projection::{project_velocities, ProjWork};
use crate::mechanics::model::runtime::Model;
use crate::mechanics::step::newton::Work;
use crate::mechanics::step::work::{history_len, Memory, HISTORY, TABLES};

/// State of one simulation run. `Clone` is a complete snapshot.
#[derive(Clone, Debug)]
pub struct State {
    /// Time, s.
    pub(crate) t: f64,
    /// How far the coordinates and velocities lag behind `t`, s: the span of communication
    /// steps too short to integrate, carried into the next step (see `crate::sim`); 0 after
    /// every integrated step.
    pub(crate) lag: f64,
    /// Coordinates `[φ, d1, d2, d3]` per body (12 per body), world frame, m and 1.
    pub(crate) q: Vec<f64>,
    /// Velocities (12 per body), world frame, m/s and 1/s.
    pub(crate) v: Vec<f64>,
    /// Low part of the velocities (double-double with `v`), 12 per body.
    pub(crate) v_lo: Vec<f64>,
    /// Multiplier memory `λ/2` per active joint row (Newton warm start).
    pub(crate) lam: Vec<f64>,
    /// Unwrapped turn angles (one per rotational joint coordinate), rad.
    pub(crate) angles: Vec<f64>,
    /// Accumulated work of inputs minus damping dissipation, J.
    pub(crate) work: f64,
    /// Contact friction bristles (3 per ground point, then per body–body feature), m.
    pub(crate) bristle: Vec<f64>,
    /// Rotor rates of the joint coordinates with an armature (`JointRt::arm0`), rad/s or m/s:
    /// the rotor's own velocity, carried as the nodal velocities are (`v_{n+1} = 2Δ/h − vₙ`).
    pub(crate) arm: Vec<f64>,
    /// Deflections of the joint friction bristles (`JointRt::fric0`), rad or m.
    pub(crate) fric: Vec<f64>,
    /// Predictor history: difference tables of the stages' mean rates (see `Work::hist`).
    pub(crate) hist: Vec<f64>,
    /// Sizes of the stages of each table, newest first, s (0: none).
    pub(crate) hprev: [[f64; HISTORY]; TABLES],
    /// The solver's memory of the last stages.
    pub(crate) memory: Memory,
    /// The step-size controller's memory (error-controlled runs).
    pub(crate) ctrl: Control,
    pub(crate) inputs: Vec<f64>,
    pub(crate) damping: Vec<f64>,
    pub(crate) stiffness: Vec<f64>,
    /// Gains `[kp, kv]` of each actuator of the model (tunable; 0 where its law has none).
    pub(crate) gains: Vec<f64>,
    pub(crate) outputs: Outputs,
    /// Steps of this run that an order-4 composition redid as order-2 stages (a stiff damper,
    /// `step::stage`), and the joint of the first; a tally for notices, not part of the
    /// snapshot (it does not change what follows).
    pub(crate) order2: (u64, Option<usize>),
    /// Newton workspace (not part of the snapshot).
    pub(crate) ws: Work,
    /// Output-velocity projection workspace (not part of the snapshot).
    pub(crate) pw: ProjWork,
}

impl State {
    /// The initial state of `model` at t = 0 (outputs computed).
    #[must_use]
    pub fn new(model: &Model) -> Self {
        let def = model.def();
        let mut s = Self {
            t: 0.0,
            lag: 0.0,
            q: model.q0.clone(),
            v: model.v0.clone(),
            v_lo: vec![0.0; model.v0.len()],
            lam: vec![0.0; model.nrows],
            angles: model.angles0.clone(),
            work: 0.0,
            hist: vec![0.0; history_len(model)],
            hprev: [[0.0; HISTORY]; TABLES],
            memory: Memory::default(),
            ctrl: Control::new(model),
            inputs: vec![0.0; model.inputs().len()],
            damping: def.joints.iter().map(|j| j.damping).collect(),
            stiffness: def.joints.iter().map(|j| j.stiffness).collect(),
            gains: def.actuators.iter().flat_map(|a| a.law.gains()).collect(),
            outputs: Outputs::for_model(model),
            order2: (0, None),
            bristle: vec![0.0; 3 * model.contact.bristles()],
            arm: vec![0.0; model.narm],
            fric: vec![0.0; model.nfric],
            ws: Work::new(model),
            pw: ProjWork::new(model),
        };
        s.refresh_outputs(model);
        // the rotors start at the joints' rates (the admissible ones the outputs report)
        for (j, jt) in model.joints.iter().enumerate() {
            if jt.armature > 0.0 {
                for k in 0..jt.dofs.len() {
                    s.arm[jt.arm0 + k] = s.outputs.joints[j].qd[k];
                }
            }
        }
        if model.narm > 0 {
            s.refresh_outputs(model);
        }
        s
    }

    /// Recomputes the outputs from the current state: first the M-orthogonal projection of the
    /// nodal velocities onto the admissible ones (one linear solve, `projection.rs`), then every
    /// output. Allocates nothing. [`crate::mechanics::step`] calls it after every step;
    /// [`crate::mechanics::step_state`] leaves it to the caller.
    pub fn refresh_outputs(&mut self, model: &Model) {
        // a singular projection (impossible for a regular model) falls back to the nodal
        // velocities inside `project_velocities`
        let _ = project_velocities(model, &self.q, &self.v, &mut self.pw);
        super::outputs::update(
            model,
            &self.q,
            &self.v,
            &self.pw.vp,
            &self.angles,
            &self.stiffness,
            &self.bristle,
            &self.arm,
            &self.fric,
            self.work,
            &mut self.outputs,
        );
    }

    /// The step-size controller's memory (used when `solver.rtol > 0`).
    #[must_use]
    pub fn control(&self) -> &Control {
        &self.ctrl
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

    /// How far the coordinates and velocities lag behind [`State::time`], s (0 unless the last
    /// communication steps were too short to integrate; they are carried into the next step).
    #[must_use]
    pub fn lag(&self) -> f64 {
        self.lag
    }

    /// Sets the lag (see [`State::lag`]), s.
    pub fn set_lag(&mut self, lag: f64) {
        self.lag = lag;
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

    /// The contact friction bristles' deflections (3 per ground point, world frame, then per
    /// body–body feature), m.
    #[must_use]
    pub fn contact_bristles(&self) -> &[f64] {
        &self.bristle
    }

    /// The contact friction bristles' deflections, mutable (a state perturbed along its
    /// bristle states, restoring snapshots); as [`State::contact_bristles`].
    pub fn contact_bristles_mut(&mut self) -> &mut [f64] {
        &mut self.bristle
    }

    /// The joint friction bristles' deflections (one per coordinate with friction), rad or m.
    #[must_use]
    pub fn joint_bristles(&self) -> &[f64] {
        &self.fric
    }

    /// The joint friction bristles' deflections, mutable; as [`State::joint_bristles`].
    pub fn joint_bristles_mut(&mut self) -> &mut [f64] {
        &mut self.fric
    }

    /// Damping of joint `j` (tunable), N·m·s/rad or N·s/m.
    #[must_use]
    pub fn damping(&self, j: usize) -> f64 {
        self.damping[j]
    }

    /// Sets the damping of joint `j`.
    pub fn set_damping(&mut self, j: usize, c: f64) {
        self.damping[j] = c;
    }

    /// Stiffness of joint `j` (tunable), N·m/rad or N/m.
    #[must_use]
    pub fn stiffness(&self, j: usize) -> f64 {
        self.stiffness[j]
    }

    /// Sets the stiffness of joint `j` (outputs, including the spring energy, are recomputed at
    /// the next step or restore).
    pub fn set_stiffness(&mut self, j: usize, k: f64) {
        self.stiffness[j] = k;
    }

    /// Gains `[kp, kv]` of actuator `a` (index in `ModelDef::actuators`; tunable), N·m/rad or
    /// N/m and N·m·s/rad or N·s/m per unit of gear (0 where its law has none).
    #[must_use]
    pub fn gains(&self, a: usize) -> [f64; 2] {
        [self.gains[2 * a], self.gains[2 * a + 1]]
    }

    /// Sets gain `k` (0: kp, 1: kv) of actuator `a`; the next step uses it (a gain the law has
    /// no use for has no effect).
    pub fn set_gain(&mut self, a: usize, k: usize, value: f64) {
        self.gains[2 * a + k] = value;
    }

    /// Outputs at the current time.
    #[must_use]
    pub fn outputs(&self) -> &Outputs {
        &self.outputs
    }

    /// Coordinates `[φ, d1, d2, d3]` of every body (12 per body), world frame.
    #[must_use]
    pub fn coordinates(&self) -> &[f64] {
        &self.q
    }

    /// Velocities (12 per body), world frame.
    #[must_use]
    pub fn velocities(&self) -> &[f64] {
        &self.v
    }

    /// Makes this state equal to `src` in everything that determines its future (the snapshot's
    /// contents), leaving out the scratch workspaces and the outputs (a function of the rest:
    /// [`State::refresh_outputs`] recomputes them): the cheap copy a roll-back needs. Reuses this
    /// state's allocations, allocates nothing.
    pub fn copy_values_from(&mut self, src: &State) {
        self.t = src.t;
        self.lag = src.lag;
        self.q.clone_from(&src.q);
        self.v.clone_from(&src.v);
        self.v_lo.clone_from(&src.v_lo);
        self.lam.clone_from(&src.lam);
        self.angles.clone_from(&src.angles);
        self.work = src.work;
        self.bristle.clone_from(&src.bristle);
        self.arm.clone_from(&src.arm);
        self.fric.clone_from(&src.fric);
        self.hist.clone_from(&src.hist);
        self.hprev = src.hprev;
        self.memory = src.memory;
        self.ctrl.copy_from(&src.ctrl);
        self.inputs.clone_from(&src.inputs);
        self.damping.clone_from(&src.damping);
        self.stiffness.clone_from(&src.stiffness);
        self.gains.clone_from(&src.gains);
    }

    /// Newton work done by this state's steps so far, in iterations (one per residual
    /// evaluation and solve, two more per factorisation); a measure to bound the work of a
    /// communication step by, not part of the state's values or snapshot.
    #[must_use]
    pub fn effort(&self) -> u64 {
        self.ws.effort
    }

    /// How many steps of this run an order-4 composition redid as order-2 stages because a
    /// joint's damping was too stiff for the step (its backward stage would have fed energy
    /// in), and the model's index of the joint of the first such step.
    #[must_use]
    pub fn order2_steps(&self) -> (u64, Option<usize>) {
        self.order2
    }

    /// Test-only: forgets the predictor's history and the iteration's memory, as after
    /// [`State::new`]; the next steps converge to the same solution (to the solver's
    /// tolerance) from a poorer start. Never use outside tests.
    #[doc(hidden)]
    pub fn forget_history(&mut self) {
        self.hist.fill(0.0);
        self.hprev = [[0.0; HISTORY]; TABLES];
        self.memory = Memory::default();
    }

    /// Every number that determines the future of this state (time, q, v, multipliers used as
    /// the Newton start, inputs, tunable parameters, accumulated work, unwrapping memory), flat:
    /// `[t, lag, q.., v.., v_lo.., λ/2.., angles.., work, hist.., h_prev.., memory (3), inputs.., damping.., stiffness.., actuator gains.., bristles.., rotor rates.., joint friction bristles.., step control..]`.
    #[must_use]
    pub fn snapshot(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.snapshot_len());
        out.push(self.t);
        out.push(self.lag);
        out.extend_from_slice(&self.q);
        out.extend_from_slice(&self.v);
        out.extend_from_slice(&self.v_lo);
        out.extend_from_slice(&self.lam);
        out.extend_from_slice(&self.angles);
        out.push(self.work);
        out.extend_from_slice(&self.hist);
        out.extend_from_slice(self.hprev.as_flattened());
        out.extend_from_slice(&self.memory.to_f64());
        out.extend_from_slice(&self.inputs);
        out.extend_from_slice(&self.damping);
        out.extend_from_slice(&self.stiffness);
        out.extend_from_slice(&self.gains);
        out.extend_from_slice(&self.bristle);
        out.extend_from_slice(&self.arm);
        out.extend_from_slice(&self.fric);
        self.ctrl.write_f64(&mut out);
        out
    }

    fn snapshot_len(&self) -> usize {
        3 + Memory::LEN
            + HISTORY * TABLES
            + self.q.len()
            + self.hist.len()
            + 2 * self.v.len()
            + self.lam.len()
            + self.angles.len()
            + self.inputs.len()
            + self.damping.len()
            + self.stiffness.len()
            + self.gains.len()
            + self.bristle.len()
            + self.arm.len()
            + self.fric.len()
            + self.ctrl.snapshot_len()
    }

    /// Restores a [`State::snapshot`] taken from a state of the same model; recomputes outputs.
    ///
    /// # Errors
    /// A message if the length does not match the model or the step-control memory is
    /// invalid (the state is then partly overwritten: restore into a scratch state).
    pub fn restore(&mut self, model: &Model, data: &[f64]) -> Result<(), String> {
        if data.len() != self.snapshot_len() {
            return Err(format!(
                "snapshot length {} does not match the model ({})",
                data.len(),
                self.snapshot_len()
            ));
        }
        let mut at = 0;
        let mut take = |dst: &mut [f64]| {
            dst.copy_from_slice(&data[at..at + dst.len()]);
            at += dst.len();
        };
        let mut t = [0.0; 2];
        take(&mut t);
        take(&mut self.q);
        take(&mut self.v);
        take(&mut self.v_lo);
        take(&mut self.lam);
        take(&mut self.angles);
        let mut w = [0.0];
        take(&mut w);
        take(&mut self.hist);
        let mut hp = [[0.0; HISTORY]; TABLES];
        take(hp.as_flattened_mut());
        let mut memory = [0.0; Memory::LEN];
        take(&mut memory);
        take(&mut self.inputs);
        take(&mut self.damping);
        take(&mut self.stiffness);
        take(&mut self.gains);
        take(&mut self.bristle);
        take(&mut self.arm);
        take(&mut self.fric);
        self.ctrl.read_f64(&data[at..])?;
        self.t = t[0];
        self.lag = t[1];
        self.work = w[0];
        self.hprev = hp;
        self.memory = Memory::from_f64(memory);
        self.refresh_outputs(model);
        Ok(())
    }
}
