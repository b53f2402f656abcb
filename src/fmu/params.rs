//! `fmi2Get*`/`fmi2Set*` by value reference through the variable table (FMI 2.0.4 §2.1.7).
//! Sets are all-or-nothing: every value is checked first (known VR of the right type, finite,
//! allowed for the causality, variability and current mode — fmi.md §1.3 notes 1, 3, 6), then
//! all are applied.

use super::contract::{read_param, read_state, write_param};
use super::instance::{Instance, Mode, Op};
use super::status::{FmuError, Status};
use crate::mechanics::ModelDef;
use crate::variables::{Accessor, Causality, Initial, VarType, Variability, Variable};

/// The FMI base type a get/set call is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Base {
    Real,
    Integer,
    Boolean,
    String,
}

impl Base {
    fn name(self) -> &'static str {
        match self {
            Self::Real => "fmi2Real",
            Self::Integer => "fmi2Integer",
            Self::Boolean => "fmi2Boolean",
            Self::String => "fmi2String",
        }
    }

    fn matches(self, ty: VarType) -> bool {
        matches!(
            (self, ty),
            (Self::Real, VarType::Real) | (Self::Integer, VarType::Integer)
        )
    }
}

/// Why `v` may not be set in `mode`, if it may not (notes 1, 3 and 6 of the FMI 2.0.4 §4.2.4 table).
fn set_forbidden(mode: Mode, v: &Variable, exit_init: &str) -> Option<String> {
    let what = match (v.causality, v.variability) {
        (Causality::Output, _) => {
            return Some(format!(
                "variable '{}' is an output and cannot be set",
                v.name
            ))
        }
        (Causality::Input, _) => return None,
        (Causality::Parameter, Variability::Tunable) => "tunable parameter",
        (Causality::Parameter, _) => "fixed parameter",
    };
    if v.initial == Initial::Calculated {
        return Some(format!(
            "variable '{}' is calculated and cannot be set",
            v.name
        ));
    }
    match mode {
        Mode::Instantiated | Mode::InitializationMode => None,
        Mode::StepComplete if v.variability == Variability::Tunable => None,
        _ => Some(format!(
            "variable '{}' is a {what}; it can only be set before {exit_init}",
            v.name
        )),
    }
}

/// The joint accelerations of one get call, computed at its first `joint.J.qdd`.
pub(super) type AccCache = std::cell::OnceCell<Result<crate::sim::Accelerations, String>>;

impl Instance {
    pub(super) fn lookup(&self, vr: u32, base: Base) -> Result<&Variable, FmuError> {
        self.index
            .get(&vr)
            .and_then(|&i| self.table.vars.get(i))
            .filter(|v| base.matches(v.ty))
            .ok_or_else(|| {
                FmuError::rejected(format!("unknown value reference {vr} for {}", base.name()))
            })
    }

    /// The value of `v`; joint accelerations are computed once per call into `acc`.
    pub(super) fn value(&self, v: &Variable, acc: &AccCache) -> Result<f64, FmuError> {
        let value = match (v.causality, &self.sim, v.accessor) {
            (Causality::Parameter, _, _) => read_param(v.accessor, &self.def, &self.settings),
            (_, Some(sim), Accessor::JointQdd { joint, k }) => {
                match acc.get_or_init(|| sim.accelerations()) {
                    Ok(a) => a.get(joint, k),
                    Err(e) => {
                        return Err(FmuError::rejected(format!(
                            "variable '{}' has no value: {e}",
                            v.name
                        )))
                    }
                }
            }
            (_, Some(sim), _) => read_state(v.accessor, sim.state()),
            (_, None, Accessor::Input(i)) => self.inputs.get(i).copied(),
            _ => None,
        };
        value.ok_or_else(|| {
            FmuError::rejected(format!(
                "variable '{}' has no value in {}",
                v.name,
                self.mode.name()
            ))
        })
    }

    fn get(&self, vrs: &[u32], base: Base, function: &'static str) -> Result<Vec<f64>, FmuError> {
        self.check(Op::Get, function)?;
        let acc = AccCache::new();
        vrs.iter()
            .map(|&vr| self.lookup(vr, base).and_then(|v| self.value(v, &acc)))
            .collect()
    }

    /// `fmi2GetReal`.
    ///
    /// # Errors
    /// Wrong mode or unknown value reference; `out` is then unchanged.
    pub fn get_real(&self, vrs: &[u32], out: &mut [f64]) -> Result<Status, FmuError> {
        let values = self.get(vrs, Base::Real, "fmi2GetReal")?;
        out.copy_from_slice(&values);
        Ok(Status::Ok)
    }

    /// `fmi2GetInteger`.
    ///
    /// # Errors
    /// Wrong mode or unknown value reference; `out` is then unchanged.
    pub fn get_integer(&self, vrs: &[u32], out: &mut [i32]) -> Result<Status, FmuError> {
        let values = self.get(vrs, Base::Integer, "fmi2GetInteger")?;
        for (o, v) in out.iter_mut().zip(values) {
            *o = v as i32;
        }
        Ok(Status::Ok)
    }

    /// `fmi2GetBoolean` / `fmi2GetString`: triad has no such variables, so any value reference
    /// is unknown.
    ///
    /// # Errors
    /// Wrong mode or any value reference.
    pub fn get_other(&self, vrs: &[u32], boolean: bool) -> Result<Status, FmuError> {
        let (base, f) = if boolean {
            (Base::Boolean, "fmi2GetBoolean")
        } else {
            (Base::String, "fmi2GetString")
        };
        self.get(vrs, base, f)?;
        Ok(Status::Ok)
    }

    /// `fmi2SetBoolean` / `fmi2SetString`: no such variables, any value reference is unknown.
    ///
    /// # Errors
    /// Wrong mode or any value reference.
    pub fn set_other(&mut self, vrs: &[u32], boolean: bool) -> Result<Status, FmuError> {
        let (base, f) = if boolean {
            (Base::Boolean, "fmi2SetBoolean")
        } else {
            (Base::String, "fmi2SetString")
        };
        self.check(Op::Set, f)?;
        for &vr in vrs {
            self.lookup(vr, base)?;
        }
        Ok(Status::Ok)
    }

    /// `fmi2SetReal`.
    ///
    /// # Errors
    /// Wrong mode, unknown value reference, forbidden set or a non-finite/invalid value; nothing
    /// is changed then.
    pub fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> Result<Status, FmuError> {
        self.set(vrs, values, Base::Real, "fmi2SetReal")
    }

    /// `fmi2SetInteger`.
    ///
    /// # Errors
    /// As [`Instance::set_real`].
    pub fn set_integer(&mut self, vrs: &[u32], values: &[i32]) -> Result<Status, FmuError> {
        let values: Vec<f64> = values.iter().map(|&v| f64::from(v)).collect();
        self.set(vrs, &values, Base::Integer, "fmi2SetInteger")
    }

    pub(super) fn set(
        &mut self,
        vrs: &[u32],
        values: &[f64],
        base: Base,
        function: &'static str,
    ) -> Result<Status, FmuError> {
        self.check(Op::Set, function)?;
        // check everything first
        // the definition is copied only when a parameter is set (not for the per-step inputs)
        let mut def: Option<ModelDef> = None;
        let mut settings = self.settings;
        let mut updates = Vec::with_capacity(vrs.len());
        for (&vr, &value) in vrs.iter().zip(values) {
            let v = self.lookup(vr, base)?;
            if !value.is_finite() {
                return Err(FmuError::rejected(format!(
                    "value {value} for '{}' is not finite",
                    v.name
                )));
            }
            if let Some(why) =
                set_forbidden(self.mode, v, self.api.name("fmi2ExitInitializationMode"))
            {
                return Err(FmuError::rejected(format!(
                    "{why} (in {})",
                    self.mode.name()
                )));
            }
            if v.causality == Causality::Parameter {
                let d = def.get_or_insert_with(|| self.def.clone());
                write_param(v.accessor, d, &mut settings, value)
                    .map_err(|e| FmuError::rejected(format!("'{}' = {value}: {e}", v.name)))?;
            }
            updates.push((v.accessor, value));
        }
        // a parameter change during Initialization Mode rebuilds the simulation (inputs kept)
        let rebuilt = match (&def, self.mode) {
            (Some(def), Mode::InitializationMode) => {
                let mut inputs = self.inputs.clone();
                if let Some(sim) = &self.sim {
                    inputs = sim.state().inputs().to_vec();
                }
                Some(
                    self.build(def, &settings, &inputs)
                        .map_err(FmuError::Rejected)?,
                )
            }
            _ => None,
        };
        // a new stiffness shows in the spring energy output at once, not after a step: set it and
        // refresh the outputs on a copy, which replaces the simulation only if they are finite
        let respring = self.mode == Mode::StepComplete
            && updates
                .iter()
                .any(|(acc, _)| matches!(acc, Accessor::Stiffness(_)));
        let resprung = match (&self.sim, respring) {
            (Some(sim), true) => {
                let mut sim = sim.clone();
                for (acc, value) in &updates {
                    if let Accessor::Stiffness(j) = acc {
                        sim.state_mut().set_stiffness(*j, *value);
                    }
                }
                sim.refresh_outputs();
                if let Some(what) = sim.state().outputs().first_non_finite() {
                    return Err(FmuError::rejected(format!(
                        "the new stiffness gives a non-finite output ({what})"
                    )));
                }
                Some(sim)
            }
            _ => None,
        };
        // apply
        if let Some(sim) = resprung {
            self.sim = Some(sim);
        }
        if let Some(def) = def {
            self.def = def;
            self.settings = settings;
        }
        if rebuilt.is_some() {
            self.sim = rebuilt;
        }
        for (acc, value) in updates {
            match (acc, self.sim.as_mut()) {
                (Accessor::Input(i), Some(sim)) => {
                    if let Some(u) = sim.state_mut().inputs_mut().get_mut(i) {
                        *u = value;
                    }
                }
                (Accessor::Input(i), None) => {
                    if let Some(u) = self.inputs.get_mut(i) {
                        *u = value;
                    }
                }
                (Accessor::Damping(j), Some(sim)) if self.mode == Mode::StepComplete => {
                    sim.state_mut().set_damping(j, value)
                }
                (Accessor::ActuatorKp(a), Some(sim)) if self.mode == Mode::StepComplete => {
                    sim.state_mut().set_gain(a, 0, value)
                }
                (Accessor::ActuatorKv(a), Some(sim)) if self.mode == Mode::StepComplete => {
                    sim.state_mut().set_gain(a, 1, value)
                }
                _ => {}
            }
        }
        Ok(Status::Ok)
    }
}
