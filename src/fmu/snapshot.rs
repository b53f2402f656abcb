//! FMU states (FMI 2.0.4 §2.1.8): `fmi2GetFMUstate` takes a [`Snapshot`], `fmi2SetFMUstate`
//! restores it, and (de)serialisation writes it as a versioned, pointer-free little-endian byte
//! string, so a state can continue in another instance or another process bit-identically.
//!
//! Byte format, version 2 (all integers u32 LE, all reals f64 LE bit patterns):
//!
//! | field | bytes |
//! |---|---|
//! | magic `TRIADFS\0` | 8 |
//! | version = 2 | 4 |
//! | GUID length n, GUID (UTF-8) | 4 + n |
//! | mode code (`Mode` order) | 1 |
//! | start time, stop-time flag (u8) and stop time, last successful time | 8 + 1 + 8 + 8 |
//! | parameter count m, values of every parameter in table order | 4 + 8m |
//! | pending input count k, values | 4 + 8k |
//! | state flag (u8); if 1: length s and `State::snapshot()` | 1 (+ 4 + 8s) |
//! | CRC-32 (IEEE) of every byte before it | 4 |
//!
//! Reading verifies the checksum, then every field: the mode is one `fmi2GetFMUstate` records
//! (Instantiated, Initialization Mode, stepComplete, Terminated), times and all numbers are
//! finite, the stop time is not before the start; restoring then checks the sizes against the
//! model and every parameter against its range (`mechanics::ranges`). Any other buffer is
//! refused and the instance is left as it was.
use super::contract::{read_param, write_param};
use super::instance::{Instance, Mode, Op};
use super::status::{FmuError, Status};
use crate::mechanics::{ModelDef, SolverSettings};
use crate::sim::Simulation;
use crate::variables::Causality;

const MAGIC: &[u8; 8] = b"TRIADFS\0";
const VERSION: u32 = 2;

/// Everything that determines the future of an instance.
#[derive(Clone, Debug, PartialEq)]
pub struct Snapshot {
    guid: String,
    mode: Mode,
    start_time: f64,
    stop_time: Option<f64>,
    last_successful_time: f64,
    params: Vec<f64>,
    inputs: Vec<f64>,
    state: Option<Vec<f64>>,
}

impl Snapshot {
    /// The GUID of the model the state belongs to.
    #[must_use]
    pub fn guid(&self) -> &str {
        &self.guid
    }

    /// The serialised bytes (format in the module docs).
    #[must_use]
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut b = Vec::new();
        let len = |b: &mut Vec<u8>, n: usize| b.extend_from_slice(&(n as u32).to_le_bytes());
        let reals = |b: &mut Vec<u8>, xs: &[f64]| {
            len(b, xs.len());
            xs.iter()
                .for_each(|x| b.extend_from_slice(&x.to_le_bytes()));
        };
        b.extend_from_slice(MAGIC);
        b.extend_from_slice(&VERSION.to_le_bytes());
        len(&mut b, self.guid.len());
        b.extend_from_slice(self.guid.as_bytes());
        b.push(self.mode.code());
        b.extend_from_slice(&self.start_time.to_le_bytes());
        b.push(u8::from(self.stop_time.is_some()));
        b.extend_from_slice(&self.stop_time.unwrap_or(0.0).to_le_bytes());
        b.extend_from_slice(&self.last_successful_time.to_le_bytes());
        reals(&mut b, &self.params);
        reals(&mut b, &self.inputs);
        b.push(u8::from(self.state.is_some()));
        if let Some(s) = &self.state {
            reals(&mut b, s);
        }
        let crc = crc32fast::hash(&b);
        b.extend_from_slice(&crc.to_le_bytes());
        b
    }

    /// Parses and verifies bytes written by [`Snapshot::to_bytes`] (module docs).
    ///
    /// # Errors
    /// A message for a wrong magic, version or checksum, truncated or trailing data, a mode
    /// that is never recorded, non-finite numbers or inconsistent times.
    pub fn from_bytes(bytes: &[u8]) -> Result<Snapshot, String> {
        if bytes.len() < MAGIC.len() + 8 || &bytes[..MAGIC.len()] != MAGIC {
            return Err("not a triad FMU state (bad magic)".into());
        }
        let (body, crc) = bytes.split_at(bytes.len() - 4);
        let mut r = Reader { b: body, at: 0 };
        r.take(8)?;
        let version = r.u32()?;
        if version != VERSION {
            return Err(format!(
                "FMU state format version {version} is not supported (expected {VERSION})"
            ));
        }
        let stored = u32::from_le_bytes([crc[0], crc[1], crc[2], crc[3]]);
        if crc32fast::hash(body) != stored {
            return Err("FMU state is corrupted (checksum mismatch)".into());
        }
        let n = r.u32()? as usize;
        let guid =
            String::from_utf8(r.take(n)?.to_vec()).map_err(|_| "GUID is not UTF-8".to_string())?;
        let code = r.u8()?;
        let mode = Mode::from_code(code)
            .filter(|m| m.recordable())
            .ok_or_else(|| {
                format!("FMU state has mode code {code}, which fmi2GetFMUstate never records")
            })?;
        let start_time = r.f64()?;
        let has_stop = r.u8()? != 0;
        let stop = r.f64()?;
        let last_successful_time = r.f64()?;
        let params = r.reals()?;
        let inputs = r.reals()?;
        let state = if r.u8()? != 0 { Some(r.reals()?) } else { None };
        if r.at != body.len() {
            return Err(format!(
                "{} trailing bytes after the FMU state",
                body.len() - r.at
            ));
        }
        let times = [start_time, stop, last_successful_time];
        if times.iter().any(|t| !t.is_finite()) || (has_stop && stop < start_time) {
            return Err(format!("FMU state has invalid times: start {start_time}, stop {stop}, last successful {last_successful_time}"));
        }
        let lists = [("parameter", &params), ("input", &inputs)];
        for (what, xs) in lists {
            if let Some(x) = xs.iter().find(|x| !x.is_finite()) {
                return Err(format!("FMU state holds a non-finite {what} value ({x})"));
            }
        }
        if state
            .as_ref()
            .is_some_and(|s| s.iter().any(|x| !x.is_finite()))
        {
            return Err("FMU state holds a non-finite simulation value".into());
        }
        Ok(Snapshot {
            guid,
            mode,
            start_time,
            stop_time: has_stop.then_some(stop),
            last_successful_time,
            params,
            inputs,
            state,
        })
    }
}

struct Reader<'a> {
    b: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> Result<&'a [u8], String> {
        let end = self
            .at
            .checked_add(n)
            .filter(|&e| e <= self.b.len())
            .ok_or("FMU state is truncated")?;
        let s = &self.b[self.at..end];
        self.at = end;
        Ok(s)
    }
    fn u8(&mut self) -> Result<u8, String> {
        Ok(self.take(1)?[0])
    }
    fn u32(&mut self) -> Result<u32, String> {
        let mut a = [0; 4];
        a.copy_from_slice(self.take(4)?);
        Ok(u32::from_le_bytes(a))
    }
    fn f64(&mut self) -> Result<f64, String> {
        let mut a = [0; 8];
        a.copy_from_slice(self.take(8)?);
        Ok(f64::from_le_bytes(a))
    }
    fn reals(&mut self) -> Result<Vec<f64>, String> {
        let n = self.u32()? as usize;
        if n > (self.b.len() - self.at) / 8 {
            return Err("FMU state is truncated".into());
        }
        (0..n).map(|_| self.f64()).collect()
    }
}

impl Instance {
    /// `fmi2GetFMUstate`.
    ///
    /// # Errors
    /// Wrong mode (also Error mode: a state taken there would not be valid).
    pub fn get_fmu_state(&self) -> Result<Snapshot, FmuError> {
        self.check(Op::FmuState, "fmi2GetFMUstate")?;
        if self.mode == Mode::Error {
            return Err(FmuError::IllegalCall {
                op: self.api.name("fmi2GetFMUstate"),
                mode: self.mode.name(),
            });
        }
        let params = self
            .table
            .vars
            .iter()
            .filter(|v| v.causality == Causality::Parameter)
            .map(|v| read_param(v.accessor, &self.def, &self.settings).unwrap_or(f64::NAN))
            .collect();
        Ok(Snapshot {
            guid: self.guid.clone(),
            mode: self.mode,
            start_time: self.start_time,
            stop_time: self.stop_time,
            last_successful_time: self.last_successful_time,
            params,
            inputs: self.inputs.clone(),
            state: self.sim.as_ref().map(|s| s.state().snapshot()),
        })
    }

    /// `fmi2SetFMUstate`: everything is rebuilt on temporaries first, so a state that does not
    /// fit leaves the instance unchanged.
    ///
    /// # Errors
    /// Wrong mode, a state of another model (GUID), or one that does not fit the model.
    pub fn set_fmu_state(&mut self, snap: &Snapshot) -> Result<Status, FmuError> {
        self.check(Op::FmuState, "fmi2SetFMUstate")?;
        let (def, settings, sim) = self.prepare(snap)?;
        self.def = def;
        self.settings = settings;
        self.sim = sim;
        self.inputs.clone_from(&snap.inputs);
        self.mode = snap.mode;
        self.start_time = snap.start_time;
        self.stop_time = snap.stop_time;
        self.last_successful_time = snap.last_successful_time;
        Ok(Status::Ok)
    }

    /// Checks that `snap` can be restored into this instance (GUID, mode, sizes, parameter
    /// ranges, the simulation state), building everything on temporaries: what
    /// `fmi2DeSerializeFMUstate` asks before it hands out a state.
    ///
    /// # Errors
    /// As [`Instance::set_fmu_state`]; nothing is changed.
    pub fn verify_fmu_state(&self, snap: &Snapshot) -> Result<(), FmuError> {
        self.prepare(snap).map(drop)
    }

    /// The definition, settings and simulation `snap` restores to.
    #[allow(clippy::type_complexity)]
    fn prepare(
        &self,
        snap: &Snapshot,
    ) -> Result<(ModelDef, SolverSettings, Option<Simulation>), FmuError> {
        if !snap.mode.recordable() {
            return Err(FmuError::rejected(format!(
                "FMU state is in {}, which fmi2GetFMUstate never records",
                snap.mode.name()
            )));
        }
        if snap.guid != self.guid {
            return Err(FmuError::rejected(format!(
                "FMU state belongs to model {} (this is {})",
                snap.guid, self.guid
            )));
        }
        let (mut def, mut settings) = self.base.clone();
        let params = self
            .table
            .vars
            .iter()
            .filter(|v| v.causality == Causality::Parameter);
        let mut count = 0;
        for (v, &x) in params.zip(&snap.params) {
            write_param(v.accessor, &mut def, &mut settings, x)
                .map_err(|e| FmuError::rejected(format!("FMU state: '{}': {e}", v.name)))?;
            count += 1;
        }
        if count != snap.params.len() || snap.inputs.len() != self.inputs.len() {
            return Err(FmuError::rejected(
                "FMU state does not match this model's variables",
            ));
        }
        let sim = match &snap.state {
            None => None,
            Some(data) => {
                let reuse = self
                    .sim
                    .as_ref()
                    .filter(|s| s.model().def() == &def && s.model().settings() == &settings);
                let mut sim = match reuse {
                    Some(s) => s.clone(),
                    None => self
                        .build(&def, &settings, &snap.inputs)
                        .map_err(FmuError::Rejected)?,
                };
                let model = sim.model().clone();
                sim.state_mut()
                    .restore(&model, data)
                    .map_err(|e| FmuError::rejected(format!("FMU state: {e}")))?;
                let lag = sim.state().lag();
                if !(0.0..crate::sim::MIN_STEP_RATIO * settings.max_step).contains(&lag) {
                    return Err(FmuError::rejected(format!(
                        "FMU state: lag {lag} s is outside [0, {:e}) s",
                        crate::sim::MIN_STEP_RATIO * settings.max_step
                    )));
                }
                if let Some(what) = sim.state().outputs().first_non_finite() {
                    return Err(FmuError::rejected(format!(
                        "FMU state: the restored state gives a non-finite output ({what})"
                    )));
                }
                Some(sim)
            }
        };
        // fmi2GetFMUstate records a simulation state exactly when the mode has one
        if snap.state.is_some() != (snap.mode != Mode::Instantiated) {
            return Err(FmuError::rejected(format!(
                "FMU state in {} {} a simulation state",
                snap.mode.name(),
                if snap.state.is_some() {
                    "holds"
                } else {
                    "lacks"
                }
            )));
        }
        Ok((def, settings, sim))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bytes_roundtrip_and_rejects() {
        let s = Snapshot {
            guid: "{g}".into(),
            mode: Mode::StepComplete,
            start_time: 0.5,
            stop_time: Some(2.0),
            last_successful_time: 1.25,
            params: vec![1.0, -0.0, f64::MIN_POSITIVE],
            inputs: vec![3.0],
            state: Some(vec![1.0, 2.0]),
        };
        let b = s.to_bytes();
        assert_eq!(Snapshot::from_bytes(&b).unwrap(), s);
        assert!(Snapshot::from_bytes(&b[..b.len() - 1]).is_err());
        let mut long = b.clone();
        long.push(0);
        assert!(Snapshot::from_bytes(&long).is_err());
        assert!(Snapshot::from_bytes(b"garbage!").is_err());
    }
}
