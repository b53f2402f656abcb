//! FMI 3.0 Co-Simulation on the same [`Instance`]: `fmi3EnterInitializationMode` (the
//! experiment and the initialisation in one call) and get/set by FMI 3 value reference with
//! `nValues`, through the FMI 3 view of the variable table ([`Table3`]): an array variable
//! takes or gives its elements in row-major order, [`TIME_VR`] reads the current time.
//!
//! Get and set are all-or-nothing: every value reference is resolved and `nValues` compared
//! with the sum of the variables' sizes before anything is read or written; a set then goes
//! through the FMI 2 set of the elements (`params.rs`), which checks every value first.
//! `Float64` covers the table's Real variables, `Int32` its Integer ones; there are no
//! variables of any other FMI 3 type.

use super::api::Api;
use super::instance::{Instance, Op};
use super::params::Base;
use super::status::{FmuError, Status};
use crate::variables::fmi3::{Table3, Var3, TIME_VR};

impl Base {
    /// The FMI 3 type of this base type's variables.
    fn name3(self) -> &'static str {
        match self {
            Self::Real => "Float64",
            Self::Integer => "Int32",
            Self::Boolean => "Boolean",
            Self::String => "String",
        }
    }
}

impl Instance {
    /// The FMI 3 view of the variable table.
    #[must_use]
    pub fn table3(&self) -> &Table3 {
        &self.table3
    }

    /// The C interface this instance was made through.
    #[must_use]
    pub fn api(&self) -> Api {
        self.api
    }

    /// `earlyReturnAllowed` of `fmi3InstantiateCoSimulation` (false for FMI 2 instances).
    #[must_use]
    pub fn early_return_allowed(&self) -> bool {
        matches!(
            self.api,
            Api::Fmi3 {
                early_return_allowed: true
            }
        )
    }

    /// The independent variable: the simulation's time, or the start time before there is one.
    #[must_use]
    pub fn time(&self) -> f64 {
        self.sim.as_ref().map_or(self.start_time, |s| s.time())
    }

    /// The time the last communication step reached (after a Discard, the time the state was
    /// left at): `fmi3DoStep`'s `lastSuccessfulTime`.
    #[must_use]
    pub fn time_reached(&self) -> f64 {
        self.last_successful_time
    }

    /// `fmi3EnterInitializationMode`: what `fmi2SetupExperiment` and
    /// `fmi2EnterInitializationMode` do, as one call that changes nothing when it fails.
    ///
    /// # Errors
    /// As [`Instance::setup_experiment`] and [`Instance::enter_initialization_mode`]; the
    /// instance is then unchanged (still Instantiated, with its former experiment).
    pub fn enter_initialization_mode3(
        &mut self,
        tolerance: Option<f64>,
        start: f64,
        stop: Option<f64>,
    ) -> Result<Status, FmuError> {
        self.check(Op::EnterInitializationMode, "fmi3EnterInitializationMode")?;
        let saved = (self.start_time, self.stop_time, self.last_successful_time);
        self.setup_experiment(start, stop, tolerance)?;
        let entered = self.enter_initialization_mode();
        if entered.is_err() {
            (self.start_time, self.stop_time, self.last_successful_time) = saved;
        }
        entered
    }

    /// The FMI 3 variable `vr` of type `base`.
    fn var3(&self, vr: u32, base: Base) -> Result<&Var3, FmuError> {
        self.table3
            .by_vr(vr)
            .filter(|v| {
                v.members
                    .first()
                    .is_some_and(|&m| self.lookup(m, base).is_ok())
            })
            .ok_or_else(|| {
                FmuError::rejected(format!("unknown value reference {vr} for {}", base.name3()))
            })
    }

    /// Refuses `n_values` unless it is `want`, the sum of the variables' sizes.
    fn count(n_values: usize, want: usize, nvr: usize) -> Result<(), FmuError> {
        if n_values == want {
            Ok(())
        } else {
            Err(FmuError::rejected(format!(
                "nValues is {n_values}, but the {nvr} value references hold {want} values"
            )))
        }
    }

    /// Checks a get of `vrs` into `n_values` values of type `base` (mode, references, count)
    /// without reading anything; allocates nothing.
    fn check_get3(
        &self,
        vrs: &[u32],
        n_values: usize,
        base: Base,
        function: &'static str,
    ) -> Result<(), FmuError> {
        self.check(Op::Get, function)?;
        let mut want = 0;
        for &vr in vrs {
            want += if vr == TIME_VR && base == Base::Real {
                1
            } else {
                self.var3(vr, base)?.len()
            };
        }
        Self::count(n_values, want, vrs.len())
    }

    /// The values of `vrs` (checked by [`Instance::check_get3`]) in order, into `put`.
    fn read3(
        &self,
        vrs: &[u32],
        base: Base,
        mut put: impl FnMut(usize, f64),
    ) -> Result<(), FmuError> {
        let mut k = 0;
        let acc = super::params::AccCache::new();
        for &vr in vrs {
            if vr == TIME_VR && base == Base::Real {
                put(k, self.time());
                k += 1;
                continue;
            }
            // checked: the variable exists and is of type `base`, and so are its members
            let var = self
                .table3
                .by_vr(vr)
                .map_or_else(|| self.var3(vr, base), Ok)?;
            for &m in &var.members {
                let element = self
                    .table
                    .by_vr(m)
                    .map_or_else(|| self.lookup(m, base), Ok)?;
                put(k, self.value(element, &acc)?);
                k += 1;
            }
        }
        Ok(())
    }

    fn set3(
        &mut self,
        vrs: &[u32],
        values: &[f64],
        base: Base,
        function: &'static str,
    ) -> Result<Status, FmuError> {
        self.check(Op::Set, function)?;
        let mut members = Vec::with_capacity(values.len());
        for &vr in vrs {
            if vr == TIME_VR {
                return Err(FmuError::rejected(format!(
                    "value reference {TIME_VR} is time, the independent variable: it cannot be set"
                )));
            }
            members.extend_from_slice(&self.var3(vr, base)?.members);
        }
        Self::count(values.len(), members.len(), vrs.len())?;
        self.set(&members, values, base, function)
    }

    /// `fmi3GetFloat64`: `out.len()` is `nValues`.
    ///
    /// # Errors
    /// Wrong mode, an unknown value reference or one of another type, `nValues` not the sum
    /// of the variables' sizes; `out` is then unchanged.
    pub fn get_float64(&self, vrs: &[u32], out: &mut [f64]) -> Result<Status, FmuError> {
        self.check_get3(vrs, out.len(), Base::Real, "fmi3GetFloat64")?;
        self.read3(vrs, Base::Real, |k, v| out[k] = v)?;
        Ok(Status::Ok)
    }

    /// `fmi3SetFloat64`: `values.len()` is `nValues`.
    ///
    /// # Errors
    /// As [`Instance::get_float64`], `time`, a forbidden set or a non-finite or invalid value;
    /// nothing is changed then.
    pub fn set_float64(&mut self, vrs: &[u32], values: &[f64]) -> Result<Status, FmuError> {
        self.set3(vrs, values, Base::Real, "fmi3SetFloat64")
    }

    /// `fmi3GetInt32`.
    ///
    /// # Errors
    /// As [`Instance::get_float64`].
    pub fn get_int32(&self, vrs: &[u32], out: &mut [i32]) -> Result<Status, FmuError> {
        self.check_get3(vrs, out.len(), Base::Integer, "fmi3GetInt32")?;
        self.read3(vrs, Base::Integer, |k, v| out[k] = v as i32)?;
        Ok(Status::Ok)
    }

    /// `fmi3SetInt32`.
    ///
    /// # Errors
    /// As [`Instance::set_float64`].
    pub fn set_int32(&mut self, vrs: &[u32], values: &[i32]) -> Result<Status, FmuError> {
        let values: Vec<f64> = values.iter().map(|&v| f64::from(v)).collect();
        self.set3(vrs, &values, Base::Integer, "fmi3SetInt32")
    }

    /// Get or set of an FMI 3 type this FMU has no variables of (`type_name`, e.g. `Float32`):
    /// OK for no value references, otherwise the first is unknown.
    ///
    /// # Errors
    /// Wrong mode, or any value reference.
    pub fn access_absent_type(
        &self,
        set: bool,
        vrs: &[u32],
        type_name: &str,
        function: &'static str,
    ) -> Result<Status, FmuError> {
        self.check(if set { Op::Set } else { Op::Get }, function)?;
        match vrs.first() {
            Some(vr) => Err(FmuError::rejected(format!(
                "unknown value reference {vr} for {type_name} (this FMU has no {type_name} variables)"
            ))),
            None => Ok(Status::Ok),
        }
    }
}
