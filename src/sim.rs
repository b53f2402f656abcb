//! One simulation run shared by `triad simulate` and the FMU: communication steps made of
//! internal sub-steps, with roll-back on failure. Both front ends call this, so their results are
//! identical by construction.
//!
//! The sub-steps of a communication step are equal: `ceil(H / max_step)` of them with fixed
//! steps (`solver.rtol = 0`; one whose Newton iteration fails, an impact too hard for it, is
//! retaken as two halves, each likewise, down to 1/16, [`SPLITS`]), or, with error control, `ceil(r / h)` for the span `r` still to
//! go and the controller's proposal `h` (recomputed after every step, see
//! `mechanics::run::control`), so the last one ends exactly on the communication point and a
//! steady proposal gives equal steps. A step that would cross a joint limit (enter or leave a
//! stop contact) is retried to end on the crossing (`mechanics::run::events`), and the steps
//! after it again share the span left equally. Rejected attempts count towards `max_substeps`.
//!
//! Three guards keep every accepted step meaningful:
//! - a communication step shorter than [`MIN_STEP_RATIO`]` × max_step` is not integrated (the
//!   velocities of so short a step are dominated by the round-off of the positions, ~ε|q|/h):
//!   the time advances and the span is carried as the state's lag into the next step, whose
//!   sub-steps then cover it; the bodies lag the clock by less than that span, and every step
//!   taken is still an energy–momentum step, so the invariants stay exact;
//! - a communication step needing more than `max_substeps` sub-steps takes that many and stops,
//!   reporting the time reached ([`Failure::WorkBound`]);
//! - a communication step whose Newton work exceeds [`WORK_PER_SUBSTEP`]` × max_substeps`
//!   body-iterations (Newton iterations × the model's size, [`Simulation::work_size`];
//!   a factorisation counts as three iterations) stops after the sub-step that crossed it, at
//!   the time reached ([`Failure::EffortBound`]): sub-steps in violent states (huge torques,
//!   bodies spinning at 1000 rad/s) cost tens to hundreds of Newton iterations each, and the
//!   sub-step count alone let one call run for 90 s. One body-iteration costs 0.3–0.7 µs on a
//!   2-core x86 machine (loops and contacts are counted in the size), so the default bound
//!   (100 000 sub-steps: 4e6 body-iterations) is about 1–2 s of CPU; ordinary calls of 100 000
//!   sub-steps of the shipped models need 1–4 iterations a sub-step, within it;
//! - a step whose outputs are not all finite is rolled back ([`Failure::NonFinite`]).

use crate::mechanics::{
    above_floor, begin_step_map, controlled_step, finish_step_map, first_event, penetration,
    step_state, Event, Independent, Model, ModelDef, ModelError, Operating, SolverSettings, State,
    StepError, StepMap, Verdict,
};
use thiserror::Error;

/// How many times a fixed sub-step whose Newton iteration fails is halved before the
/// communication step fails (module docs): down to 1/16 of `max_step`.
pub const SPLITS: u32 = 4;

/// A fixed sub-step of size `dt` ([`step_state`]); where Newton fails (no convergence, a
/// singular matrix; not a nearly undetermined motion, which is reported as it is) it is
/// retaken as two halves, each likewise, `depth` times. Each step taken
/// is an energy–momentum step. On error the state may have moved by earlier halves (the caller
/// rolls back).
fn step_split(model: &Model, state: &mut State, dt: f64, depth: u32) -> Result<(), StepError> {
    match step_state(model, state, dt) {
        Ok(_) => Ok(()),
        // (not where the motion is nearly undetermined: that failure names its cause)
        Err(StepError::NoConvergence { .. } | StepError::Singular) if depth > 0 => {
            step_split(model, state, 0.5 * dt, depth - 1)?;
            step_split(model, state, 0.5 * dt, depth - 1)
        }
        Err(e) => Err(e),
    }
}

/// The width of the time bracket an early return's event search ends at, s (module docs of
/// [`Simulation::advance_early`]).
pub const EVENT_TIME_TOL: f64 = 1e-13;

/// Events within this fraction of a step's start are not early returns (the step starts on
/// them: a return landed past its event, within [`EVENT_TIME_TOL`]); every later crossing is,
/// however close to the start.
const EVENT_START: f64 = 1e-9;

/// Steps an early return's event search takes at most (the bracket shrinks superlinearly:
/// 10–20 are typical).
const EVENT_ITERATIONS: usize = 60;

/// A communication step shorter than this fraction of `max_step` is carried into the next one
/// instead of being integrated on its own (1 ns at the default `max_step` of 1 ms).
pub const MIN_STEP_RATIO: f64 = 1e-6;

/// Newton body-iterations (iterations × [`Simulation::work_size`]) one communication step may
/// take per sub-step allowed (`solver.max_substeps`): module docs.
pub const WORK_PER_SUBSTEP: f64 = 40.0;

/// Why a communication step stopped short.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum Failure {
    /// A sub-step failed (the state is rolled back to the start of the communication step).
    #[error(transparent)]
    Step(#[from] StepError),
    /// The step needed more sub-steps than `solver.max_substeps`; it took that many.
    #[error("the step needs {needed} sub-steps of at most max_step, more than solver.max_substeps = {bound}; it stopped after {bound}")]
    WorkBound {
        /// Sub-steps the whole communication step needs.
        needed: f64,
        /// `solver.max_substeps`.
        bound: u32,
    },
    /// The step's Newton work exceeded its bound; it stopped after the sub-step that crossed it.
    #[error("the step's Newton work reached {work:.3e} body-iterations, more than its bound of {bound:.3e} ({WORK_PER_SUBSTEP} × solver.max_substeps); it stopped after {steps} sub-steps")]
    EffortBound {
        /// Newton iterations done (a factorisation counts three) × the model's size.
        work: f64,
        /// The bound, body-iterations.
        bound: f64,
        /// Sub-steps taken (attempts, with error control).
        steps: u64,
    },
    /// An output became NaN or infinite (the state is rolled back).
    #[error("non-finite output ({0})")]
    NonFinite(String),
}

impl Failure {
    /// Whether the step stopped at the time reached with good state (a work bound), rather
    /// than being rolled back.
    #[must_use]
    pub fn stopped_short(&self) -> bool {
        matches!(
            self,
            Failure::WorkBound { .. } | Failure::EffortBound { .. }
        )
    }
}

/// Why a communication step stopped short, and where the run stands.
#[derive(Debug, Clone, PartialEq)]
pub struct AdvanceError {
    /// What went wrong.
    pub error: Failure,
    /// Time of the last good state, at which the run now stands, s: the start of the
    /// communication step after a roll-back, the progress made after [`Failure::WorkBound`].
    pub last_good_time: f64,
}

/// Joint accelerations at one state ([`Simulation::accelerations`]).
#[derive(Clone, Debug)]
pub struct Accelerations {
    at: Vec<Option<usize>>,
    nud: Vec<f64>,
}

impl Accelerations {
    /// Acceleration `k` of joint `joint` (rad/s² or m/s²).
    #[must_use]
    pub fn get(&self, joint: usize, k: usize) -> Option<f64> {
        self.nud.get(self.at.get(joint).copied()?? + k).copied()
    }
}

/// A running simulation: the model and its state.
#[derive(Clone, Debug)]
pub struct Simulation {
    model: Model,
    state: State,
    /// State at the start of the current communication step (roll-back target).
    saved: State,
    /// State at the start of the current sub-step (early return: the retake of a sub-step
    /// that crossed an event).
    sub: State,
    /// Whether a clamped actuator input has been reported ([`Simulation::clamp_notice`]).
    clamp_noticed: bool,
    /// Whether an order-4 step redone at order 2 has been reported
    /// ([`Simulation::order2_notice`]).
    order2_noticed: bool,
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
            sub: saved.clone(),
            saved,
            clamp_noticed: false,
            order2_noticed: false,
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

    /// The first time an order-4 step was redone as order-2 stages because a joint's damping
    /// is too stiff for the step (its backward stage would have fed energy in), a message
    /// naming the joint; `None` before and ever after. Call it after a communication step.
    pub fn order2_notice(&mut self) -> Option<String> {
        let (count, joint) = self.state.order2_steps();
        if self.order2_noticed || count == 0 {
            return None;
        }
        self.order2_noticed = true;
        let what = joint
            .and_then(|j| self.model.def().joints.get(j))
            .map_or("the contacts' damping and friction".to_string(), |j| {
                format!("the damping of joint '{}'", j.name)
            });
        Some(format!(
            "order 4: a step before t = {} was taken as order-2 stages: {what} is too stiff for \
             the step (the composition's backward stage would feed energy in); such steps stay \
             dissipative and the energy account exact, at order 2. A smaller solver.max_step \
             keeps order 4",
            self.state.time()
        ))
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

    /// The operating point of the current state in minimal coordinates (trees without contact;
    /// `mechanics::Operating`).
    ///
    /// # Errors
    /// Why the model has none (a loop, contact).
    pub fn operating(&self) -> Result<Operating, String> {
        Operating::of(&self.model, &self.state).map_err(|e| e.to_string())
    }

    /// The exact discrete-time linear model of the communication step `h` from the current
    /// state (`δx(t+h) = Ad δx(t) + Bd δu`, `x` the minimal coordinates of
    /// [`Simulation::operating`], `u` every input of the model): the step's tangent map
    /// (`mechanics::step::tangent`) carried through every sub-step and stage that
    /// [`Simulation::advance`] takes, between the embedding's and the read-off's tangents
    /// (`mechanics::model::minimal`). The step sizes are those the run takes (with error
    /// control: held at the accepted ones). The simulation advances by `h`.
    ///
    /// # Errors
    /// A loop or contact (no minimal coordinates), a failed step, or a singular mass matrix.
    pub fn step_map(&mut self, h: f64) -> Result<StepMap, String> {
        self.step_map_in(h, &Independent::Auto)
    }

    /// [`Simulation::step_map`] with closed loops in the independent coordinates `pick`.
    ///
    /// # Errors
    /// As [`Simulation::step_map`], and a pick that is not independent here.
    pub fn step_map_in(&mut self, h: f64, pick: &Independent) -> Result<StepMap, String> {
        let end = begin_step_map(&self.model, &mut self.state, pick)?;
        let advanced = self.advance(h);
        let map = finish_step_map(&self.model, &mut self.state, &end);
        advanced.map_err(|e| e.error.to_string())?;
        map
    }

    /// The joint accelerations at the current state and inputs (the outputs `joint.J.qdd`).
    ///
    /// # Errors
    /// Why there are none: a loop, contact, or a singular joint-space mass matrix.
    pub fn accelerations(&self) -> Result<Accelerations, String> {
        let op = self.operating()?;
        let nud = op.accelerations()?;
        let at = (0..self.model.def().joints.len())
            .map(|j| op.dynamics.joint_at(j))
            .collect();
        Ok(Accelerations { at, nud })
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

    /// Number of equal sub-steps for an integrated span `h`: `ceil(h / max_step)` (at least 1),
    /// with a relative slack of 1e-9 so that `h = k·max_step` takes exactly k; as a float, so
    /// that a span of 1e300 s is counted, not wrapped.
    #[must_use]
    pub fn substeps(&self, h: f64) -> f64 {
        let ratio = h / self.model.settings().max_step;
        let n = (ratio * (1.0 - 1e-9)).ceil();
        if n >= 1.0 {
            n
        } else {
            1.0
        }
    }

    /// The model's size for the work bound: its bodies, 1.5 units per constraint row of a
    /// loop-closing joint (the bordered solve) and a quarter per contact point and feature;
    /// what one Newton iteration costs is about proportional to it.
    #[must_use]
    pub fn work_size(&self) -> f64 {
        let m = &self.model;
        let loops: usize = m
            .joints
            .iter()
            .enumerate()
            .filter(|(j, jt)| m.tree_joint[jt.child] != Some(*j))
            .map(|(_, jt)| jt.rows.len())
            .sum();
        (m.def().bodies.len().max(1) as f64)
            + 1.5 * loops as f64
            + 0.25 * m.contact.bristles() as f64
    }

    /// The Newton body-iterations one communication step may take (module docs).
    #[must_use]
    pub fn work_bound(&self) -> f64 {
        WORK_PER_SUBSTEP * f64::from(self.model.settings().max_substeps.max(1))
    }

    /// The Newton work since `start` (an effort count) of a model of size `size`
    /// ([`Simulation::work_size`], computed once per communication step), body-iterations.
    fn work_since(&self, start: u64, size: f64) -> f64 {
        (self.state.effort() - start) as f64 * size
    }

    /// Advances by the communication step `h`, landing on `t + h` exactly (the last sub-step
    /// ends at the float `t + h`). Inputs are held constant. The span integrated is `h` plus the
    /// lag carried from earlier steps too short to integrate (module docs), in `substeps` equal
    /// sub-steps; a span shorter than [`MIN_STEP_RATIO`]` × max_step` is carried on instead.
    ///
    /// # Errors
    /// On a failed sub-step or a non-finite output the state is rolled back to the start of this
    /// communication step; past `max_substeps` sub-steps the run stops where it got to. The
    /// error says which and when.
    pub fn advance(&mut self, h: f64) -> Result<(), AdvanceError> {
        self.advance_refreshed(h, false).map(drop)
    }

    /// The communication step ([`Simulation::advance_state_with`]), then the outputs once,
    /// after the last sub-step, rolled back when one is not finite.
    fn advance_refreshed(&mut self, h: f64, early: bool) -> Result<Option<f64>, AdvanceError> {
        let result = self.advance_state_with(h, early);
        let moved = match &result {
            Ok((moved, _)) => *moved,
            Err(e) => e.error.stopped_short(),
        };
        if moved {
            self.state.refresh_outputs(&self.model);
            if let Some(what) = self.state.outputs().first_non_finite() {
                self.state.copy_values_from(&self.saved);
                self.state.refresh_outputs(&self.model);
                return Err(AdvanceError {
                    error: Failure::NonFinite(what),
                    last_good_time: self.state.time(),
                });
            }
        }
        result.map(|(_, at)| at)
    }

    /// [`Simulation::advance`] without the refresh of the outputs (velocity projection, energy,
    /// momenta, joint coordinates: about a third of a chain's step): the outputs keep the values
    /// of the last refresh until [`Simulation::refresh_outputs`] or an [`Simulation::advance`].
    /// For drivers that step several times between reading outputs. Whether the bodies moved
    /// (false: the step was carried on as lag).
    ///
    /// # Errors
    /// As [`Simulation::advance`], less the check of the outputs.
    pub fn advance_state(&mut self, h: f64) -> Result<bool, AdvanceError> {
        self.advance_state_with(h, false).map(|(moved, _)| moved)
    }

    /// [`Simulation::advance`] that returns early, at the time a joint reaches or leaves a
    /// stop or a contact touches or leaves (`mechanics::first_event`; FMI 3's early return):
    /// `Some(t)` is that time, `None` a step that landed on `t + h` without an event. A sub-step
    /// (with error control: an accepted step) that crosses an event is retaken to end on it,
    /// the size found to [`EVENT_TIME_TOL`] (`land_on_event`), just past the crossing; an event
    /// within `EVENT_START` (1e-9) of a sub-step's fraction from its start is not reported (the
    /// one returned at before).
    ///
    /// # Errors
    /// As [`Simulation::advance`].
    pub fn advance_early(&mut self, h: f64) -> Result<Option<f64>, AdvanceError> {
        self.advance_refreshed(h, true)
    }

    /// The earliest event crossed from `self.sub` to the state at a fraction in
    /// `(EVENT_START, hi)` of that step (`mechanics::first_event`).
    fn event_since_sub(&self, hi: f64) -> Option<(f64, Event)> {
        first_event(
            &self.model,
            &self.sub.q,
            &self.sub.angles,
            &self.state.q,
            &self.state.angles,
            EVENT_START,
            hi,
        )
    }

    /// After a sub-step of size `h` from `self.sub`: if it crossed an event, the sub-step
    /// retaken to end on it, and its size; `None` without an event.
    ///
    /// The size `τ` is the root of the event's signed penetration `x(τ)` at the end of a step
    /// of size `τ` from `self.sub`, bracketed between the start (`x₀`) and `h` and found by
    /// the Illinois variant of regula falsi (superlinear; each evaluation one step) to a
    /// bracket of [`EVENT_TIME_TOL`] s or `x(τ) = 0`; the step ends on the bracket's side past
    /// the crossing. An earlier crossing of another limit or contact found on the way takes
    /// over the search.
    fn land_on_event(&mut self, h: f64) -> Result<Option<f64>, StepError> {
        let Some((_, mut ev)) = self.event_since_sub(1.0 + 1e-12) else {
            return Ok(None);
        };
        let pen = |sim: &Self, ev: Event, of_sub: bool| {
            let s = if of_sub { &sim.sub } else { &sim.state };
            penetration(&sim.model, ev, &s.q, &s.angles)
        };
        let (mut a, mut fa) = (0.0, pen(self, ev, true));
        let (mut b, mut fb) = (h, pen(self, ev, false));
        // which end the last retained update kept twice (Illinois)
        let mut side = 0i8;
        let mut at = h;
        for _ in 0..EVENT_ITERATIONS {
            if b - a <= EVENT_TIME_TOL || fb == 0.0 {
                break;
            }
            let mut tau = (a * fb - b * fa) / (fb - fa);
            if !(tau > a && tau < b) {
                tau = 0.5 * (a + b);
            }
            self.state.copy_values_from(&self.sub);
            step_state(&self.model, &mut self.state, tau)?;
            at = tau;
            // another event crossed earlier within the retake takes over
            if let Some((theta, other)) = self.event_since_sub(1.0) {
                if other != ev && theta < 1.0 {
                    ev = other;
                    (a, fa) = (0.0, pen(self, ev, true));
                    (b, fb) = (tau, pen(self, ev, false));
                    side = 0;
                    continue;
                }
            }
            let ft = pen(self, ev, false);
            if (ft > 0.0) == (fb > 0.0) {
                (b, fb) = (tau, ft);
                if side == 1 {
                    fa *= 0.5;
                }
                side = 1;
            } else {
                (a, fa) = (tau, ft);
                if side == -1 {
                    fb *= 0.5;
                }
                side = -1;
            }
        }
        if at != b {
            self.state.copy_values_from(&self.sub);
            step_state(&self.model, &mut self.state, b)?;
        }
        Ok(Some(b))
    }

    fn advance_state_with(
        &mut self,
        h: f64,
        early: bool,
    ) -> Result<(bool, Option<f64>), AdvanceError> {
        let t0 = self.state.time();
        if !(h.is_finite() && h > 0.0) {
            return Err(AdvanceError {
                error: StepError::BadStep(h).into(),
                last_good_time: t0,
            });
        }
        let t_end = t0 + h;
        let span = self.state.lag() + h;
        let settings = self.model.settings();
        if span < MIN_STEP_RATIO * settings.max_step {
            self.state.set_lag(span);
            self.state.set_time(t_end);
            return Ok((false, None));
        }
        if settings.rtol > 0.0 {
            return self.advance_controlled(t0, t_end, span, early);
        }
        let needed = self.substeps(span);
        let bound = settings.max_substeps.max(1);
        let n = needed.min(f64::from(bound)) as usize;
        // the roll-back copy (a failed `step` leaves the state untouched, but earlier sub-steps
        // and the lag must be undone too)
        self.saved.copy_values_from(&self.state);
        let dt = span / needed;
        let (start, budget, size) = (self.state.effort(), self.work_bound(), self.work_size());
        for k in 0..n {
            if early {
                self.sub.copy_values_from(&self.state);
            }
            let stepped = step_split(&self.model, &mut self.state, dt, SPLITS).and_then(|()| {
                if early {
                    self.land_on_event(dt)
                } else {
                    Ok(None)
                }
            });
            match stepped {
                Err(error) => {
                    self.state.copy_values_from(&self.saved);
                    return Err(AdvanceError {
                        error: error.into(),
                        last_good_time: t0,
                    });
                }
                Ok(Some(landed)) => {
                    let reached = (t0 - self.saved.lag()) + dt * k as f64 + landed;
                    self.state.set_lag(0.0);
                    self.state.set_time(reached);
                    return Ok((true, Some(reached)));
                }
                Ok(None) => {}
            }
            let work = self.work_since(start, size);
            if work > budget && k + 1 < n {
                self.state.set_lag(0.0);
                let reached = (t0 - self.saved.lag()) + dt * (k + 1) as f64;
                self.state.set_time(reached);
                return Err(AdvanceError {
                    error: Failure::EffortBound {
                        work,
                        bound: budget,
                        steps: k as u64 + 1,
                    },
                    last_good_time: reached,
                });
            }
        }
        self.state.set_lag(0.0);
        if needed > f64::from(bound) {
            // stopped short: the clock is where the bodies are
            let reached = (t0 - self.saved.lag()) + dt * n as f64;
            self.state.set_time(reached);
            return Err(AdvanceError {
                error: Failure::WorkBound { needed, bound },
                last_good_time: reached,
            });
        }
        self.state.set_time(t_end);
        Ok((true, None))
    }

    /// The error-controlled communication step (module docs): `span` (the step and the lag)
    /// from the bodies' time to `t_end`; with `early`, it returns at the end of an accepted
    /// step that reached an event (the controller lands its steps on them).
    fn advance_controlled(
        &mut self,
        t0: f64,
        t_end: f64,
        span: f64,
        early: bool,
    ) -> Result<(bool, Option<f64>), AdvanceError> {
        let bound = self.model.settings().max_substeps.max(1);
        self.saved.copy_values_from(&self.state);
        let mut remaining = span;
        let mut attempts: u32 = 0;
        let mut done = 0.0;
        // a step that must end on a joint-stop crossing (`Verdict::Land`)
        let mut landing: Option<f64> = None;
        let (start, budget, size) = (self.state.effort(), self.work_bound(), self.work_size());
        while remaining > 0.0 {
            let work = self.work_since(start, size);
            if work > budget {
                let reached = (t0 - self.saved.lag()) + done;
                self.state.set_lag(0.0);
                self.state.set_time(reached);
                return Err(AdvanceError {
                    error: Failure::EffortBound {
                        work,
                        bound: budget,
                        steps: u64::from(attempts),
                    },
                    last_good_time: reached,
                });
            }
            if attempts >= bound {
                let reached = (t0 - self.saved.lag()) + done;
                self.state.set_lag(0.0);
                self.state.set_time(reached);
                return Err(AdvanceError {
                    error: Failure::WorkBound {
                        needed: f64::from(bound) + 1.0,
                        bound,
                    },
                    last_good_time: reached,
                });
            }
            attempts += 1;
            let (h, last) = match landing.take() {
                // θh < h ≤ remaining: never the last step of the span
                Some(h) => (h, false),
                None => {
                    let proposal = self.state.control().proposal(&self.model);
                    let n = (remaining / proposal * (1.0 - 1e-9)).ceil().max(1.0);
                    if n <= 1.0 {
                        (remaining, true)
                    } else {
                        (remaining / n, false)
                    }
                }
            };
            if early {
                self.sub.copy_values_from(&self.state);
            }
            let verdict = controlled_step(&self.model, &mut self.state, h);
            match verdict {
                Ok(Verdict::Accept) => {
                    done += h;
                    remaining = if last { 0.0 } else { remaining - h };
                    let event = early && self.event_since_sub(1.0 + 1e-12).is_some();
                    if event && remaining > 0.0 {
                        // the accepted step retaken to end on the event (as a fixed step)
                        match self.land_on_event(h) {
                            Ok(Some(tau)) => {
                                done += tau - h;
                                self.state.ctrl.record(&self.sub.q, tau);
                            }
                            Ok(None) => {}
                            Err(error) => {
                                self.state.copy_values_from(&self.saved);
                                return Err(AdvanceError {
                                    error: error.into(),
                                    last_good_time: t0,
                                });
                            }
                        }
                        let reached = (t0 - self.saved.lag()) + done;
                        self.state.set_lag(0.0);
                        self.state.set_time(reached);
                        return Ok((true, Some(reached)));
                    }
                }
                Ok(Verdict::Reject) => {}
                Ok(Verdict::Land(h_land)) => landing = Some(h_land),
                Err(error) => {
                    // a failed step is retried shorter, down to the floor
                    if above_floor(&self.model, h) {
                        self.state.ctrl.shrink_after_failure(&self.model, h);
                        continue;
                    }
                    self.state.copy_values_from(&self.saved);
                    return Err(AdvanceError {
                        error: error.into(),
                        last_good_time: t0,
                    });
                }
            }
        }
        self.state.set_lag(0.0);
        self.state.set_time(t_end);
        Ok((true, None))
    }
}

/// A gap to the ground within this of zero is touching, not below the ground, m.
pub const TOUCHING: f64 = 1e-9;

/// A collision shape below the ground ([`Simulation::below_ground`]).
#[derive(Clone, Debug, PartialEq)]
pub struct BelowGround {
    /// The shape's index among the model's collision shapes (`def().contact.shapes`).
    pub shape: usize,
    /// How far its lowest point is below the ground, m (more than [`TOUCHING`]).
    pub depth: f64,
}

impl Simulation {
    /// The collision shapes whose gap to the ground (`contact.C.gap`) is below `-TOUCHING` at
    /// the current state, deepest first: right after [`Simulation::new`], the shapes that start
    /// inside the ground (their contact springs then push with `k · depth` at the first step).
    #[must_use]
    pub fn below_ground(&self) -> Vec<BelowGround> {
        let mut below: Vec<BelowGround> = self
            .state
            .outputs()
            .contacts
            .iter()
            .enumerate()
            .filter(|(_, c)| c.gap < -TOUCHING)
            .map(|(shape, c)| BelowGround {
                shape,
                depth: -c.gap,
            })
            .collect();
        below.sort_by(|a, b| b.depth.total_cmp(&a.depth));
        below
    }
}
