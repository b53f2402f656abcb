//! A randomised, seeded sequence of FMI calls through the exported C functions, as a careless
//! or hostile importer would make them: every function in every state, unknown value
//! references, NULL arrays, NaN and huge values, tiny/denormal/huge/negative steps, mismatched
//! communication points, corrupted and foreign saved states, bogus state pointers, instances
//! freed with states outstanding. Two instances of the model live side by side and the calls
//! go to either, so FMU states move between instances (got in one, set, serialised or freed
//! through the other) as hosts with pools of instances do. 25 000 calls on each shipped model
//! and on the bouncing ball (contact). With `TRIAD_DYNAMIC_TESTS=1` the calls go to the shared
//! library `TRIAD_CDYLIB` loaded as an importer loads it (CI: the glibc-2.17 runtime).
//!
//! Asserted after every call: no panic and no `fmi2Fatal` (nothing reaches the poisoning
//! path), a status among the five of FMI 2.0 (never `fmi2Pending`), an `fmi2Error` changes
//! nothing observable (all variable values, the last successful time and the serialised
//! state, which holds the mode), and whenever outputs can be read they are finite.

mod fmu_support;

use fmu_support::*;
use std::ffi::CString;
// the FMI functions linked, or loaded from the runtime (TRIAD_DYNAMIC_TESTS, fmu_support::api)
use fmu_support::api::*;
use triad::ffi::types::*;
use triad::variables::{Causality, VarType};

const CALLS_PER_MODEL: usize = 25_000;

/// A shipped model with a small work bound, so that a huge step costs at most 2 000 sub-steps
/// (the integers set stay at or below 2 000 too: a legal bound of 2^31 - 1 would let one call
/// run for hours, which is what the bound is for).
fn model(text: &str) -> TestModel {
    let text = if text.contains("[solver]\n") {
        text.replace("[solver]\n", "[solver]\nmax_substeps = 2000\n")
    } else {
        format!("{text}\n[solver]\nmax_substeps = 2000\n")
    };
    TestModel::new(&text)
}

/// Everything an importer can observe without changing anything.
#[derive(PartialEq, Debug)]
struct Observed {
    reals: (i32, Vec<u64>),
    ints: (i32, Vec<i32>),
    last_time: (i32, u64),
    state: (i32, Vec<u8>),
}

fn observe(f: &Fmu, reals: &[u32], ints: &[u32]) -> Observed {
    let mut rv = vec![0.0; reals.len()];
    let rs = unsafe { fmi2GetReal(f.c, reals.as_ptr(), reals.len(), rv.as_mut_ptr()) };
    let mut iv = vec![0; ints.len()];
    let is = unsafe { fmi2GetInteger(f.c, ints.as_ptr(), ints.len(), iv.as_mut_ptr()) };
    let mut t = 0.0;
    let ts = unsafe { fmi2GetRealStatus(f.c, fmi2LastSuccessfulTime, &mut t) };
    let mut st: fmi2FMUstate = std::ptr::null_mut();
    let gs = unsafe { fmi2GetFMUstate(f.c, &mut st) };
    let mut bytes = Vec::new();
    if gs == fmi2OK {
        let mut n = 0;
        assert_eq!(
            unsafe { fmi2SerializedFMUstateSize(f.c, st, &mut n) },
            fmi2OK
        );
        bytes = vec![0u8; n];
        assert_eq!(
            unsafe { fmi2SerializeFMUstate(f.c, st, bytes.as_mut_ptr().cast(), n) },
            fmi2OK
        );
        assert_eq!(unsafe { fmi2FreeFMUstate(f.c, &mut st) }, fmi2OK);
    }
    Observed {
        reals: (rs, rv.iter().map(|x| x.to_bits()).collect()),
        ints: (is, iv),
        last_time: (ts, t.to_bits()),
        state: (gs, bytes),
    }
}

/// The time the instance stands at (its last successful time), or 0.
fn now(f: &Fmu) -> f64 {
    let mut t = 0.0;
    let s = unsafe { fmi2GetRealStatus(f.c, fmi2LastSuccessfulTime, &mut t) };
    if s == fmi2OK {
        t
    } else {
        0.0
    }
}

struct Driver<'a> {
    m: &'a TestModel,
    rng: Rng,
    reals: Vec<u32>,
    ints: Vec<u32>,
    inputs: Vec<u32>,
    params: Vec<u32>,
    outputs: Vec<u32>,
    /// FMU states handed out by either instance, with the serial number of the instance that
    /// made it (some freed behind our back on purpose).
    states: Vec<(fmi2FMUstate, usize)>,
    /// The serial number of the instance the next call goes to.
    serial: usize,
    /// States set into an instance that did not make them.
    moved: usize,
    /// Serialised states seen so far (valid ones, to corrupt or restore).
    saved: Vec<Vec<u8>>,
    foreign: Vec<u8>,
    /// The kind of the last call (for messages).
    last: usize,
}

impl Driver<'_> {
    fn vrs(&mut self, from: &[u32]) -> Vec<u32> {
        let n = self.rng.below(4) + 1;
        (0..n)
            .map(|_| {
                if self.rng.chance(0.1) || from.is_empty() {
                    self.rng.pick(&[9_999_999, u32::MAX, 123_456])
                } else {
                    self.rng.pick(from)
                }
            })
            .collect()
    }

    fn real(&mut self) -> f64 {
        let specials = [
            f64::NAN,
            f64::INFINITY,
            -f64::INFINITY,
            0.0,
            -0.0,
            1e-300,
            4.9e-324,
            1e300,
            -1.0,
            2.0,
            4.0,
            1e-3,
            0.5,
        ];
        if self.rng.chance(0.5) {
            self.rng.pick(&specials)
        } else {
            (self.rng.next() as f64 / u64::MAX as f64 - 0.5) * 20.0
        }
    }

    fn step_size(&mut self) -> f64 {
        self.rng.pick(&[
            1e-3,
            1e-2,
            0.05,
            1e-10,
            1e-300,
            4.9e-324,
            2.2e-308,
            1e6,
            0.0,
            -1e-3,
            f64::NAN,
            f64::INFINITY,
        ])
    }

    /// One random call; returns its status.
    fn call(&mut self, f: &Fmu) -> i32 {
        let c = f.c;
        let kind = self.rng.below(26);
        self.last = kind;
        match kind {
            0 => {
                let (tol_def, stop_def) = (self.rng.below(2) as i32, self.rng.below(2) as i32);
                let (tol, start, stop) = (self.real(), self.real(), self.real());
                let start = if self.rng.chance(0.7) { 0.0 } else { start };
                unsafe { fmi2SetupExperiment(c, tol_def, tol, start, stop_def, stop) }
            }
            1 | 2 => unsafe { fmi2EnterInitializationMode(c) },
            3 | 4 => unsafe { fmi2ExitInitializationMode(c) },
            5 => unsafe { fmi2Terminate(c) },
            6 => {
                if self.rng.chance(0.3) {
                    unsafe { fmi2Reset(c) }
                } else {
                    unsafe { fmi2CancelStep(c) }
                }
            }
            7..=11 => {
                let t = now(f);
                let t = if self.rng.chance(0.9) {
                    t
                } else {
                    t + self.real()
                };
                let h = self.step_size();
                unsafe { fmi2DoStep(c, t, h, fmi2False) }
            }
            12 | 13 => {
                let pool = if self.rng.chance(0.6) {
                    self.inputs.clone()
                } else {
                    self.params.clone()
                };
                let vrs = self.vrs(&pool);
                let vals: Vec<f64> = vrs.iter().map(|_| self.real()).collect();
                if self.rng.chance(0.05) {
                    unsafe { fmi2SetReal(c, vrs.as_ptr(), vrs.len(), std::ptr::null()) }
                } else {
                    unsafe { fmi2SetReal(c, vrs.as_ptr(), vrs.len(), vals.as_ptr()) }
                }
            }
            14 => {
                let vrs = self.vrs(&self.ints.clone());
                let vals: Vec<i32> = vrs
                    .iter()
                    .map(|_| self.rng.pick(&[-1, 0, 1, 2, 3, 4, 100, 2000, i32::MIN]))
                    .collect();
                unsafe { fmi2SetInteger(c, vrs.as_ptr(), vrs.len(), vals.as_ptr()) }
            }
            15 => {
                let vrs = self.vrs(&self.reals.clone());
                let mut out = vec![0.0; vrs.len()];
                if self.rng.chance(0.05) {
                    unsafe { fmi2GetReal(c, vrs.as_ptr(), vrs.len(), std::ptr::null_mut()) }
                } else {
                    unsafe { fmi2GetReal(c, vrs.as_ptr(), vrs.len(), out.as_mut_ptr()) }
                }
            }
            16 => {
                let vrs = self.vrs(&[]);
                let mut b = vec![0; vrs.len()];
                let mut s: Vec<fmi2String> = vec![std::ptr::null(); vrs.len()];
                match self.rng.below(4) {
                    0 => unsafe { fmi2GetBoolean(c, vrs.as_ptr(), vrs.len(), b.as_mut_ptr()) },
                    1 => unsafe { fmi2GetString(c, vrs.as_ptr(), vrs.len(), s.as_mut_ptr()) },
                    2 => unsafe { fmi2SetBoolean(c, vrs.as_ptr(), vrs.len(), b.as_ptr()) },
                    _ => unsafe { fmi2SetString(c, vrs.as_ptr(), vrs.len(), s.as_ptr()) },
                }
            }
            17 => {
                let mut st: fmi2FMUstate = std::ptr::null_mut();
                let s = unsafe { fmi2GetFMUstate(c, &mut st) };
                if s == fmi2OK {
                    self.states.push((st, self.serial));
                }
                s
            }
            18 => {
                let mut junk = [0u64; 4];
                let (st, from) = if self.states.is_empty() || self.rng.chance(0.2) {
                    (junk.as_mut_ptr().cast(), self.serial)
                } else {
                    self.rng.pick(&self.states)
                };
                let s = unsafe { fmi2SetFMUstate(c, st) };
                if s == fmi2OK && from != self.serial {
                    self.moved += 1;
                }
                s
            }
            19 => {
                if self.states.is_empty() {
                    let mut null: fmi2FMUstate = std::ptr::null_mut();
                    return unsafe { fmi2FreeFMUstate(c, &mut null) };
                }
                let k = self.rng.below(self.states.len());
                let mut st = self.states[k].0;
                let s = unsafe { fmi2FreeFMUstate(c, &mut st) };
                if s == fmi2OK {
                    // keep the dangling copy now and then: using it must be refused
                    if self.rng.chance(0.7) {
                        self.states.swap_remove(k);
                    }
                }
                s
            }
            20 => {
                // serialise a held state
                let Some(&(st, _)) = self.states.first() else {
                    return fmi2OK;
                };
                let mut n = 0;
                let s = unsafe { fmi2SerializedFMUstateSize(c, st, &mut n) };
                if s != fmi2OK {
                    return s;
                }
                let mut buf = vec![0u8; n];
                let small = if self.rng.chance(0.1) { n / 2 } else { n };
                let s = unsafe { fmi2SerializeFMUstate(c, st, buf.as_mut_ptr().cast(), small) };
                if s == fmi2OK && self.saved.len() < 16 {
                    self.saved.push(buf);
                }
                s
            }
            21 | 22 => {
                // deserialise: valid, bit-flipped, truncated, foreign, garbage
                let mut bytes = if !self.saved.is_empty() && self.rng.below(5) < 3 {
                    let k = self.rng.below(self.saved.len());
                    self.saved[k].clone()
                } else {
                    self.foreign.clone()
                };
                match self.rng.below(4) {
                    0 if !bytes.is_empty() => {
                        let i = self.rng.below(bytes.len());
                        bytes[i] ^= 1 << self.rng.below(8);
                    }
                    1 => bytes.truncate(self.rng.below(bytes.len() + 1)),
                    2 => {
                        bytes = (0..self.rng.below(64))
                            .map(|_| self.rng.next() as u8)
                            .collect()
                    }
                    _ => {}
                }
                let mut st: fmi2FMUstate = std::ptr::null_mut();
                let s = unsafe {
                    fmi2DeSerializeFMUstate(c, bytes.as_ptr().cast(), bytes.len(), &mut st)
                };
                if s == fmi2OK {
                    self.states.push((st, self.serial));
                }
                s
            }
            23 => {
                let mut v = 0.0;
                let mut st = 0;
                let mut b = 0;
                let kind = self.rng.below(4) as i32;
                match self.rng.below(4) {
                    0 => unsafe { fmi2GetRealStatus(c, kind, &mut v) },
                    1 => unsafe { fmi2GetStatus(c, kind, &mut st) },
                    2 => unsafe { fmi2GetBooleanStatus(c, kind, &mut b) },
                    _ => unsafe { fmi2GetRealStatus(c, kind, std::ptr::null_mut()) },
                }
            }
            24 => {
                let (u, k) = (
                    self.vrs(&self.outputs.clone()),
                    self.vrs(&self.inputs.clone()),
                );
                let dv = vec![1.0; k.len()];
                let mut out = vec![0.0; u.len()];
                let order = vec![1; u.len()];
                match self.rng.below(3) {
                    0 => unsafe {
                        fmi2GetDirectionalDerivative(
                            c,
                            u.as_ptr(),
                            u.len(),
                            k.as_ptr(),
                            k.len(),
                            dv.as_ptr(),
                            out.as_mut_ptr(),
                        )
                    },
                    1 => unsafe {
                        fmi2SetRealInputDerivatives(
                            c,
                            k.as_ptr(),
                            k.len(),
                            order.as_ptr(),
                            dv.as_ptr(),
                        )
                    },
                    _ => unsafe {
                        fmi2GetRealOutputDerivatives(
                            c,
                            u.as_ptr(),
                            u.len(),
                            order.as_ptr(),
                            out.as_mut_ptr(),
                        )
                    },
                }
            }
            _ => {
                let names = ["logAll", "logEvents", "nonsense", "logStatusError"];
                let cats: Vec<CString> = (0..self.rng.below(3))
                    .map(|_| CString::new(self.rng.pick(&names)).unwrap())
                    .collect();
                let ptrs: Vec<fmi2String> = cats.iter().map(|s| s.as_ptr()).collect();
                unsafe {
                    fmi2SetDebugLogging(c, self.rng.below(2) as i32, ptrs.len(), ptrs.as_ptr())
                }
            }
        }
    }
}

#[test]
fn random_call_sequences_keep_every_promise() {
    if std::env::var_os("TRIAD_DYNAMIC_TESTS").is_some() {
        assert!(
            dynamic(),
            "TRIAD_DYNAMIC_TESTS is set, yet the runtime was not loaded"
        );
    }
    let mut total = 0usize;
    let mut moved = 0usize;
    // (call kind, status) → count: the sequence must reach every state and outcome
    let mut seen = std::collections::HashMap::<(usize, i32), usize>::new();
    let foreign = {
        let dp = triad::spec::bundled()
            .iter()
            .find(|(n, _)| *n == "pendulum")
            .unwrap()
            .1;
        let f = Fmu::initialised(&TestModel::new(dp));
        f.serialize()
    };
    // every shipped model, and a model with contact (ground, friction bristles in the state)
    let contact: [(&str, &str); 1] = [(
        "bouncing_ball",
        include_str!("../examples/specs/bouncing_ball.toml"),
    )];
    let models = triad::spec::bundled().iter().chain(contact.iter());
    for (k, (name, text)) in models.enumerate() {
        let m = model(text);
        let of = |c: Causality, ty: VarType| -> Vec<u32> {
            m.table
                .vars
                .iter()
                .filter(|v| v.causality == c && v.ty == ty)
                .map(|v| v.vr)
                .collect()
        };
        let reals: Vec<u32> = m
            .table
            .vars
            .iter()
            .filter(|v| v.ty == VarType::Real)
            .map(|v| v.vr)
            .collect();
        let mut d = Driver {
            m: &m,
            rng: Rng(0x0074_7269_6164 + k as u64),
            ints: of(Causality::Parameter, VarType::Integer),
            inputs: of(Causality::Input, VarType::Real),
            params: of(Causality::Parameter, VarType::Real),
            outputs: of(Causality::Output, VarType::Real),
            reals,
            states: Vec::new(),
            serial: 0,
            moved: 0,
            saved: Vec::new(),
            foreign: foreign.clone(),
            last: 0,
        };
        // two instances side by side, each with its serial number
        let mut pair = [(Fmu::new(d.m), 0usize), (Fmu::new(d.m), 1usize)];
        let mut next_serial = 2;
        for i in 0..CALLS_PER_MODEL {
            if d.rng.chance(0.001) {
                // free an instance with states outstanding (they die with it: some copies are
                // kept, and using them must be refused), start a new one
                let k = d.rng.below(2);
                let dead = pair[k].1;
                let keep = d.rng.chance(0.5);
                d.states.retain(|&(_, from)| from != dead || keep);
                pair[k] = (Fmu::new(d.m), next_serial);
                next_serial += 1;
            }
            let (f, serial) = &pair[d.rng.below(2)];
            d.serial = *serial;
            let before = observe(f, &d.reals, &d.ints);
            let status = d.call(f);
            total += 1;
            *seen.entry((d.last, status)).or_default() += 1;
            assert!(
                (fmi2OK..=fmi2Error).contains(&status),
                "{name} call {i}: status {status}: {:?}",
                f.messages().last()
            );
            let after = observe(f, &d.reals, &d.ints);
            if status == fmi2Error {
                assert_eq!(
                    before,
                    after,
                    "{name} call {i}: fmi2Error changed something ({:?})",
                    f.messages().last()
                );
            }
            let (s, out) = f.get_real(&d.outputs);
            if s == fmi2OK {
                assert!(
                    out.iter().all(|x| x.is_finite()),
                    "{name} call {i} (kind {}): non-finite output after status {status}: {:?}",
                    d.last,
                    f.messages().last()
                );
            }
            if f.log.lock().unwrap().len() > 1000 {
                f.log.lock().unwrap().clear();
            }
        }
        moved += d.moved;
    }
    assert!(total >= 200_000, "{total} calls");
    let count = |kinds: std::ops::RangeInclusive<usize>, status: i32| -> usize {
        kinds
            .map(|k| seen.get(&(k, status)).copied().unwrap_or(0))
            .sum()
    };
    let coverage = [
        ("steps taken", count(7..=11, fmi2OK)),
        ("steps discarded", count(7..=11, fmi2Discard)),
        ("steps refused", count(7..=11, fmi2Error)),
        ("initialisations", count(1..=2, fmi2OK)),
        ("sets refused", count(12..=14, fmi2Error)),
        ("states restored", count(18..=18, fmi2OK)),
        ("states refused", count(18..=18, fmi2Error)),
        ("states moved between instances", moved),
        ("buffers deserialised", count(21..=22, fmi2OK)),
        ("buffers refused", count(21..=22, fmi2Error)),
    ];
    println!("{coverage:?}");
    for (what, n) in coverage {
        assert!(
            n >= 20,
            "only {n} {what}: the sequence does not exercise them"
        );
    }
}
