//! One FMU instance: life-cycle calls and `fmi2DoStep`. The state machine is in `mode.rs`,
//! get/set by value reference in `params.rs`, FMU states in `snapshot.rs`.

use super::api::Api;
use super::contract::{self, Format, Spec};
use super::log::{Category, Filter, LogSink};
pub use super::mode::{allowed, Mode, Op};
use super::status::{FmuError, Status};
use crate::mechanics::{ranges, ModelDef, SolverSettings};
use crate::sim::Failure;
use crate::sim::Simulation;
use crate::variables::fmi3::Table3;
use crate::variables::{Accessor, VariableTable};
use std::collections::HashMap;
use std::path::Path;

/// One FMU instance: the model definition it was made from, the working copy that parameter
/// sets change, the simulation (from `fmi2EnterInitializationMode` on), the mode and the log.
pub struct Instance {
    pub(super) name: String,
    pub(super) guid: String,
    pub(super) spec: Spec,
    pub(super) base: (ModelDef, SolverSettings),
    pub(super) def: ModelDef,
    pub(super) settings: SolverSettings,
    pub(super) table: VariableTable,
    /// the FMI 3 view of `table` (arrays, FMI 3 value references)
    pub(super) table3: Table3,
    /// the C interface the instance was made through
    pub(super) api: Api,
    /// value reference → index into `table.vars`
    pub(super) index: HashMap<u32, usize>,
    /// input values while no simulation exists (Instantiated mode), by input slot
    pub(super) inputs: Vec<f64>,
    pub(super) sim: Option<Simulation>,
    pub(super) mode: Mode,
    pub(super) start_time: f64,
    pub(super) stop_time: Option<f64>,
    pub(super) last_successful_time: f64,
    pub(super) filter: Filter,
    sink: Box<dyn LogSink>,
}

impl std::fmt::Debug for Instance {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Instance")
            .field("name", &self.name)
            .field("mode", &self.mode)
            .finish_non_exhaustive()
    }
}

/// Relative tolerance of the communication-point check in `fmi2DoStep`.
const TIME_RTOL: f64 = 1e-9;

impl Instance {
    /// `fmi2Instantiate` for Co-Simulation: reads `resources/model.json` from `resource_dir`,
    /// builds the variable table, recomputes the GUID and refuses a mismatch. Failures are
    /// logged through `sink` (category `logStatusError`) and give `None`.
    pub fn from_resources(
        name: &str,
        guid: &str,
        resource_dir: &Path,
        logging_on: bool,
        sink: Box<dyn LogSink>,
    ) -> Option<Instance> {
        Self::from_resources_for(Api::Fmi2, name, guid, resource_dir, logging_on, sink)
    }

    /// [`Instance::from_resources`] for the C interface `api` (its messages name `api`'s
    /// functions; `fmi3InstantiateCoSimulation` passes the `instantiationToken` as `guid`).
    pub fn from_resources_for(
        api: Api,
        name: &str,
        guid: &str,
        resource_dir: &Path,
        logging_on: bool,
        sink: Box<dyn LogSink>,
    ) -> Option<Instance> {
        let path = resource_dir.join("model.json");
        let spec = std::fs::read_to_string(&path)
            .map_err(|e| format!("cannot read {}: {e}", path.display()))
            .and_then(|text| {
                Spec::from_str(&text, Format::Json, &path.display().to_string())
                    .map_err(|e| e.to_string())
            });
        match spec {
            Ok(spec) => Self::from_spec_for(api, name, guid, spec, logging_on, sink),
            Err(msg) => {
                // the runtime's id: an FMU packed with another triad's binary says so here
                sink.log(
                    name,
                    Status::Error,
                    Category::LogStatusError,
                    &format!(
                        "{}: {msg} (this binary: {})",
                        api.instantiate(),
                        super::runtime_id::RUNTIME_TAG
                    ),
                );
                None
            }
        }
    }

    /// Like [`Instance::from_resources`] for an already parsed spec.
    pub fn from_spec(
        name: &str,
        guid: &str,
        spec: Spec,
        logging_on: bool,
        sink: Box<dyn LogSink>,
    ) -> Option<Instance> {
        Self::from_spec_for(Api::Fmi2, name, guid, spec, logging_on, sink)
    }

    /// [`Instance::from_spec`] for the C interface `api`.
    pub fn from_spec_for(
        api: Api,
        name: &str,
        guid: &str,
        spec: Spec,
        logging_on: bool,
        sink: Box<dyn LogSink>,
    ) -> Option<Instance> {
        let fail = |sink: &dyn LogSink, msg: String| {
            sink.log(
                name,
                Status::Error,
                Category::LogStatusError,
                &format!("{}: {msg}", api.instantiate()),
            );
            None
        };
        let (def, settings) = match spec.lower() {
            Ok(x) => x,
            Err(e) => {
                return fail(
                    &*sink,
                    format!("model '{}' cannot be lowered: {e}", spec.name),
                )
            }
        };
        let table = contract::table(&spec, &def, &settings);
        let expected = super::guid::guid(&spec.canonical_json(), &table);
        if guid != expected {
            return fail(
                &*sink,
                format!("{} mismatch: modelDescription.xml says {guid}, resources/model.json gives {expected} (the FMU was assembled from different builds)", api.token()),
            );
        }
        let index = table
            .vars
            .iter()
            .enumerate()
            .map(|(i, v)| (v.vr, i))
            .collect();
        let n_inputs = table.vars.iter().filter_map(|v| match v.accessor {
            Accessor::Input(i) => Some(i + 1),
            _ => None,
        });
        let inputs = vec![0.0; n_inputs.max().unwrap_or(0)];
        let table3 = Table3::new(&table);
        let start = spec.experiment.start;
        let inst = Instance {
            name: name.to_string(),
            guid: expected,
            spec,
            base: (def.clone(), settings),
            def,
            settings,
            table,
            table3,
            api,
            index,
            inputs,
            sim: None,
            mode: Mode::Instantiated,
            start_time: start,
            stop_time: None,
            last_successful_time: start,
            filter: Filter::new(logging_on),
            sink,
        };
        inst.event(&format!(
            "{}: model '{}', {} variables",
            api.instantiate(),
            inst.spec.name,
            inst.table.vars.len()
        ));
        Some(inst)
    }

    /// The current mode.
    #[must_use]
    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// The GUID this instance was checked against.
    #[must_use]
    pub fn guid(&self) -> &str {
        &self.guid
    }

    /// The variable table.
    #[must_use]
    pub fn table(&self) -> &VariableTable {
        &self.table
    }

    /// The simulation, from `fmi2EnterInitializationMode` on.
    #[must_use]
    pub fn simulation(&self) -> Option<&Simulation> {
        self.sim.as_ref()
    }

    /// Sends a message through the sink if its category is enabled.
    pub fn log(&self, status: Status, category: Category, message: &str) {
        if self.filter.enabled(category) {
            self.sink.log(&self.name, status, category, message);
        }
    }

    fn event(&self, message: &str) {
        self.log(Status::Ok, Category::LogEvents, message);
    }

    /// Checks the state machine for `op`.
    ///
    /// # Errors
    /// [`FmuError::Poisoned`] after a panic, [`FmuError::IllegalCall`] otherwise.
    pub fn check(&self, op: Op, function: &'static str) -> Result<(), FmuError> {
        if self.mode == Mode::Fatal && op != Op::FreeInstance {
            return Err(FmuError::Poisoned);
        }
        if allowed(op, self.mode) {
            Ok(())
        } else {
            Err(FmuError::IllegalCall {
                op: self.api.name(function),
                mode: self.mode.name(),
            })
        }
    }

    /// Turns a result into the status returned to the importer: logs the reason of anything
    /// but OK and escalates a failure to [`Mode::Error`].
    pub fn finish(&mut self, function: &str, result: Result<Status, FmuError>) -> Status {
        match result {
            Ok(s) => s,
            Err(e) => {
                let status = e.status();
                if matches!(e, FmuError::Failed(_)) {
                    self.mode = Mode::Error;
                }
                self.log(
                    status,
                    Category::of_status(status),
                    &format!("{function}: {e}"),
                );
                status
            }
        }
    }

    /// Marks the instance poisoned after a caught panic and logs `message` as fatal.
    pub fn poison(&mut self, message: &str) {
        self.mode = Mode::Fatal;
        self.log(Status::Fatal, Category::LogStatusFatal, message);
    }

    /// `fmi2SetDebugLogging`: switches `categories` (all when empty).
    ///
    /// # Errors
    /// An unknown category name; nothing changed.
    pub fn set_debug_logging(&mut self, on: bool, categories: &[&str]) -> Result<Status, FmuError> {
        self.check(Op::SetDebugLogging, "fmi2SetDebugLogging")?;
        let mut filter = self.filter;
        if categories.is_empty() {
            filter.set_all(on);
        }
        for name in categories {
            let c = Category::from_name(name).ok_or_else(|| {
                let known: Vec<_> = Category::ALL.iter().map(|c| c.name()).collect();
                FmuError::rejected(format!(
                    "unknown log category '{name}' (declared: {})",
                    known.join(", ")
                ))
            })?;
            filter.set(c, on);
        }
        self.filter = filter;
        Ok(Status::Ok)
    }

    /// `fmi2SetupExperiment`: start time and optional stop time; a defined tolerance must be
    /// positive and finite and is otherwise not used (the Newton tolerance is the parameter
    /// `solver.tolerance`).
    ///
    /// # Errors
    /// Wrong mode, non-finite times, a stop before the start, a non-finite or non-positive
    /// tolerance; nothing changed.
    pub fn setup_experiment(
        &mut self,
        start: f64,
        stop: Option<f64>,
        tolerance: Option<f64>,
    ) -> Result<Status, FmuError> {
        self.check(Op::SetupExperiment, "fmi2SetupExperiment")?;
        if !start.is_finite() || stop.is_some_and(|s| !s.is_finite() || s < start) {
            return Err(FmuError::rejected(format!(
                "invalid experiment: startTime {start}, stopTime {stop:?}"
            )));
        }
        if let Some(tol) = tolerance.filter(|t| !(t.is_finite() && *t > 0.0)) {
            return Err(FmuError::rejected(format!(
                "invalid experiment: toleranceDefined with tolerance {tol} (must be positive and finite)"
            )));
        }
        self.start_time = start;
        self.stop_time = stop;
        self.last_successful_time = start;
        Ok(Status::Ok)
    }

    /// `fmi2EnterInitializationMode`: builds the simulation at the start time.
    ///
    /// # Errors
    /// Wrong mode; parameters that break a rule involving several of them (an inertia tensor,
    /// `lower < upper`) or a model that cannot be built: rejected, still in Instantiated mode,
    /// so the parameters can be corrected.
    pub fn enter_initialization_mode(&mut self) -> Result<Status, FmuError> {
        self.check(Op::EnterInitializationMode, "fmi2EnterInitializationMode")?;
        let sim = self
            .build(&self.def, &self.settings, &self.inputs)
            .map_err(FmuError::Rejected)?;
        self.sim = Some(sim);
        self.mode = Mode::InitializationMode;
        self.event("fmi2EnterInitializationMode: simulation built");
        Ok(Status::Ok)
    }

    /// Builds a simulation of `def` at the start time with the given input values, after the
    /// rules that involve several parameters ([`ranges::cross_checks`]).
    pub(super) fn build(
        &self,
        def: &ModelDef,
        settings: &SolverSettings,
        inputs: &[f64],
    ) -> Result<Simulation, String> {
        let broken: Vec<String> = ranges::cross_checks(def)
            .into_iter()
            .map(|(what, e)| format!("{what} {e}"))
            .collect();
        if !broken.is_empty() {
            return Err(format!("invalid parameters: {}", broken.join("; ")));
        }
        let mut sim = Simulation::new(def, *settings, self.start_time)
            .map_err(|e| format!("model cannot be built: {e}"))?;
        let dst = sim.state_mut().inputs_mut();
        let n = dst.len().min(inputs.len());
        dst[..n].copy_from_slice(&inputs[..n]);
        if let Some(what) = sim.state().outputs().first_non_finite() {
            return Err(format!(
                "the parameters give a non-finite initial output ({what})"
            ));
        }
        Ok(sim)
    }

    /// `fmi2ExitInitializationMode`; logs a warning when collision shapes start below the
    /// ground.
    ///
    /// # Errors
    /// Wrong mode.
    pub fn exit_initialization_mode(&mut self) -> Result<Status, FmuError> {
        self.check(Op::ExitInitializationMode, "fmi2ExitInitializationMode")?;
        self.mode = Mode::StepComplete;
        if let Some(msg) = self.sim.as_ref().and_then(super::start_gap::below_ground) {
            self.log(Status::Warning, Category::LogStatusWarning, &msg);
        }
        Ok(Status::Ok)
    }

    /// `fmi2Terminate`.
    ///
    /// # Errors
    /// Wrong mode.
    pub fn terminate(&mut self) -> Result<Status, FmuError> {
        self.check(Op::Terminate, "fmi2Terminate")?;
        self.mode = Mode::Terminated;
        Ok(Status::Ok)
    }

    /// `fmi2Reset`: back to Instantiated mode with the spec's parameter and start values.
    ///
    /// # Errors
    /// Only when poisoned.
    pub fn reset(&mut self) -> Result<Status, FmuError> {
        self.check(Op::Reset, "fmi2Reset")?;
        (self.def, self.settings) = self.base.clone();
        self.inputs.iter_mut().for_each(|u| *u = 0.0);
        self.sim = None;
        self.start_time = self.spec.experiment.start;
        self.stop_time = None;
        self.last_successful_time = self.start_time;
        self.mode = Mode::Instantiated;
        Ok(Status::Ok)
    }

    /// `fmi2DoStep(t, H)`: checks `t` against the instance time (relative tolerance 1e-9),
    /// then advances by `H` in `ceil(H/max_step)` equal sub-steps landing on `t + H` (a step
    /// shorter than `1e-6 max_step` is carried into the next one, see [`crate::sim`]).
    ///
    /// # Errors
    /// Wrong mode, bad arguments (rejected, nothing changed); a failed sub-step or a non-finite
    /// output gives [`FmuError::Discard`] with the state rolled back to `t`, a step needing more
    /// than `solver.max_substeps` sub-steps [`FmuError::Discard`] at the time reached (usable
    /// there either way).
    pub fn do_step(&mut self, t: f64, h: f64) -> Result<Status, FmuError> {
        self.step_with(t, h, false).map(|(status, _)| status)
    }

    /// `fmi3DoStep`: [`Instance::do_step`], and with `earlyReturnAllowed` the step returns early
    /// at the time a joint reaches or leaves a stop or a contact touches or leaves
    /// ([`Simulation::advance_early`]): then `true`, and the time reached is that time.
    ///
    /// # Errors
    /// As [`Instance::do_step`].
    pub fn do_step3(&mut self, t: f64, h: f64) -> Result<(Status, bool), FmuError> {
        let early = self.early_return_allowed();
        self.step_with(t, h, early)
    }

    fn step_with(&mut self, t: f64, h: f64, early: bool) -> Result<(Status, bool), FmuError> {
        self.check(Op::DoStep, "fmi2DoStep")?;
        let stop = self.stop_time;
        let sim = self
            .sim
            .as_mut()
            .ok_or_else(|| FmuError::Failed("no simulation".into()))?;
        let now = sim.time();
        if !(h.is_finite() && h > 0.0) {
            return Err(FmuError::rejected(format!(
                "communicationStepSize must be positive and finite, got {h}"
            )));
        }
        if !t.is_finite() || (t - now).abs() > TIME_RTOL * now.abs().max(t.abs()).max(h) {
            return Err(FmuError::rejected(format!(
                "currentCommunicationPoint {t} does not match the instance time {now}"
            )));
        }
        if let Some(stop) = stop {
            if t + h > stop + TIME_RTOL * stop.abs().max(h) {
                return Err(FmuError::rejected(format!(
                    "step to {} goes beyond stopTime {stop}",
                    t + h
                )));
            }
        }
        // land on the master's time grid exactly
        sim.state_mut().set_time(t);
        let clamped = sim.clamp_notice();
        let result = if early {
            sim.advance_early(h)
        } else {
            sim.advance(h).map(|()| None)
        };
        let now = sim.time();
        let order2 = sim.order2_notice();
        if let Some(msg) = clamped {
            self.log(Status::Warning, Category::LogStatusWarning, &msg);
        }
        if let Some(msg) = order2 {
            self.log(Status::Warning, Category::LogStatusWarning, &msg);
        }
        match result {
            Ok(event) => {
                self.last_successful_time = now;
                Ok((Status::Ok, event.is_some()))
            }
            Err(e) => {
                self.last_successful_time = e.last_good_time;
                let what = match e.error {
                    Failure::WorkBound { .. } | Failure::EffortBound { .. } => format!("stopped at t = {} ({}); continue from there with shorter communication steps, or raise solver.max_substeps", e.last_good_time, e.error),
                    _ => format!("failed ({}); state rolled back to t = {}, continue from there with a smaller step or other inputs", e.error, e.last_good_time),
                };
                Err(FmuError::Discard(format!(
                    "step from t = {t} by H = {h} {what}"
                )))
            }
        }
    }

    /// `fmi2GetRealStatus(fmi2LastSuccessfulTime)`.
    ///
    /// # Errors
    /// Wrong mode.
    pub fn last_successful_time(&self) -> Result<f64, FmuError> {
        self.check(Op::GetStatus, "fmi2GetRealStatus")?;
        Ok(self.last_successful_time)
    }

    /// Whether the FMU wants the master to stop (`fmi2GetBooleanStatus(fmi2Terminated)`):
    /// never, a triad model has no end.
    ///
    /// # Errors
    /// Wrong mode.
    pub fn terminated_status(&self) -> Result<bool, FmuError> {
        self.check(Op::GetStatus, "fmi2GetBooleanStatus")?;
        Ok(false)
    }
}
