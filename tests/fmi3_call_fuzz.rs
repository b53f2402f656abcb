//! A randomised, seeded sequence of FMI 3 calls through the exported C functions, as a careless
//! or hostile importer makes them: the lifecycle in any order, Float64 gets and sets with
//! unknown value references, wrong `nValues`, NULL arrays, NaN and huge values, odd steps and
//! communication points (one instance with early return allowed), directional and adjoint
//! derivatives with any references and sizes, FMU states got, set, freed, serialised and
//! deserialised (truncated and corrupted too), reset and terminate. 6 000 calls on each of the
//! robot arm (derivatives), the bouncing ball (contact, early return) and the four-bar (a loop).
//!
//! Asserted after every call: no `fmi3Fatal`, a status among OK, Warning, Discard and Error, and
//! an `fmi3Error` changes nothing observable (every Float64 value and the serialised state).

mod fmu_support;

use fmu_support::fmi3::{instantiate3, shipped, Fmu3};
use fmu_support::*;
// the FMI 3 functions linked, or loaded from the runtime (TRIAD_DYNAMIC_TESTS, fmu_support::api3)
use fmu_support::api3::*;
use triad::ffi::fmi3::types::*;
use triad::variables::fmi3::Table3;

const CALLS: usize = 6_000;

/// Every Float64 value (bits, or the status that refused them) and the serialised state.
fn observe(f: &Fmu3, vrs: &[u32], n: usize) -> (i32, Vec<u64>, i32, Vec<u8>) {
    let (s, v) = f.get_f64(vrs, n);
    let mut st: fmi3FMUState = std::ptr::null_mut();
    let gs = unsafe { fmi3GetFMUState(f.c, &mut st) };
    let mut bytes = Vec::new();
    if gs == fmi3OK {
        let mut size = 0;
        assert_eq!(
            unsafe { fmi3SerializedFMUStateSize(f.c, st, &mut size) },
            fmi3OK
        );
        bytes = vec![0u8; size];
        assert_eq!(
            unsafe { fmi3SerializeFMUState(f.c, st, bytes.as_mut_ptr(), size) },
            fmi3OK
        );
        assert_eq!(unsafe { fmi3FreeFMUState(f.c, &mut st) }, fmi3OK);
    }
    let bits = if s == fmi3OK {
        v.iter().map(|x| x.to_bits()).collect()
    } else {
        Vec::new()
    };
    (s, bits, gs, bytes)
}

fn fuzz(m: &TestModel, name: &str, seed: u64) {
    if std::env::var_os("TRIAD_DYNAMIC_TESTS").is_some() {
        assert!(
            fmu_support::api3::dynamic(),
            "TRIAD_DYNAMIC_TESTS is set, yet the runtime was not loaded"
        );
    }
    let t3 = Table3::new(&m.table);
    let path = m.resources().to_string_lossy().into_owned();
    let fmus: Vec<Fmu3> = [false, true]
        .iter()
        .map(|&early| {
            let (c, log) = instantiate3(&m.guid, Some(&path), false, early);
            assert!(!c.is_null());
            Fmu3 {
                c,
                log,
                t3: Table3::new(&m.table),
            }
        })
        .collect();
    let all: Vec<u32> = t3
        .vars
        .iter()
        .filter(|v| {
            m.table
                .by_vr(v.members[0])
                .is_some_and(|w| w.ty == triad::variables::VarType::Real)
        })
        .map(|v| v.vr)
        .collect();
    let n_all: usize = all
        .iter()
        .map(|&vr| t3.by_vr(vr).map_or(0, |v| v.members.len()))
        .sum();
    let mut rng = Rng(seed);
    let mut states: Vec<fmi3FMUState> = Vec::new();
    let mut saved: Vec<Vec<u8>> = Vec::new();
    let mut t = [0.0_f64; 2];
    // successes per kind of call: the run must reach every part, not only refusals
    let mut ok = [0usize; 16];
    for call in 0..CALLS {
        let which = rng.below(2);
        let f = &fmus[which];
        let c = f.c;
        let before = observe(f, &all, n_all);
        let pick_vrs = |rng: &mut Rng| -> Vec<u32> {
            (0..rng.below(4) + 1)
                .map(|_| {
                    if rng.below(10) == 0 {
                        rng.pick(&[0, 999_999, u32::MAX])
                    } else {
                        rng.pick(&all)
                    }
                })
                .collect()
        };
        let size_of = |vrs: &[u32]| -> usize {
            vrs.iter()
                .map(|&vr| t3.by_vr(vr).map_or(1, |v| v.members.len()))
                .sum()
        };
        let odd = [
            f64::NAN,
            f64::INFINITY,
            -1.0,
            0.0,
            1e300,
            4.9e-324,
            1e-3,
            0.01,
            0.3,
            2.0,
        ];
        let kind = rng.below(16);
        let status = match kind {
            0 => unsafe {
                fmi3EnterInitializationMode(c, false, 0.0, 0.0, rng.below(2) == 1, rng.pick(&odd))
            },
            1 => unsafe { fmi3ExitInitializationMode(c) },
            2..=4 => {
                let h = rng.pick(&[1e-3, 0.01, 0.05, 0.3, 1e-300, 0.0, -1e-3, f64::NAN, 1e6]);
                let at = if rng.below(8) == 0 {
                    rng.pick(&odd)
                } else {
                    t[which]
                };
                let (mut e, mut term, mut early, mut last) = (false, false, false, f64::NAN);
                let s = unsafe {
                    fmi3DoStep(
                        c,
                        at,
                        h.min(0.5),
                        false,
                        &mut e,
                        &mut term,
                        &mut early,
                        &mut last,
                    )
                };
                if s == fmi3OK || s == fmi3Discard {
                    t[which] = last;
                }
                s
            }
            5 | 6 => {
                let vrs = pick_vrs(&mut rng);
                let n = size_of(&vrs) + usize::from(rng.below(6) == 0);
                let vals: Vec<f64> = (0..n).map(|_| rng.pick(&odd)).collect();
                unsafe { fmi3SetFloat64(c, vrs.as_ptr(), vrs.len(), vals.as_ptr(), n) }
            }
            7 => {
                let vrs = pick_vrs(&mut rng);
                let n = size_of(&vrs);
                let mut out = vec![0.0; n];
                if rng.below(5) == 0 {
                    unsafe { fmi3GetFloat64(c, vrs.as_ptr(), vrs.len(), std::ptr::null_mut(), n) }
                } else {
                    unsafe { fmi3GetFloat64(c, vrs.as_ptr(), vrs.len(), out.as_mut_ptr(), n) }
                }
            }
            8 | 9 => {
                let (u, k) = (pick_vrs(&mut rng), pick_vrs(&mut rng));
                let (nu, nk) = (size_of(&u), size_of(&k) + usize::from(rng.below(8) == 0));
                let seed: Vec<f64> = (0..nk.max(nu)).map(|_| rng.pick(&odd)).collect();
                let mut out = vec![0.0; nk.max(nu)];
                if kind == 8 {
                    unsafe {
                        fmi3GetDirectionalDerivative(
                            c,
                            u.as_ptr(),
                            u.len(),
                            k.as_ptr(),
                            k.len(),
                            seed.as_ptr(),
                            nk,
                            out.as_mut_ptr(),
                            nu,
                        )
                    }
                } else {
                    unsafe {
                        fmi3GetAdjointDerivative(
                            c,
                            u.as_ptr(),
                            u.len(),
                            k.as_ptr(),
                            k.len(),
                            seed.as_ptr(),
                            nu,
                            out.as_mut_ptr(),
                            nk,
                        )
                    }
                }
            }
            10 => {
                let mut st: fmi3FMUState = std::ptr::null_mut();
                let s = unsafe { fmi3GetFMUState(c, &mut st) };
                if s == fmi3OK {
                    states.push(st);
                }
                s
            }
            11 if !states.is_empty() => {
                let st = states[rng.below(states.len())];
                unsafe { fmi3SetFMUState(c, st) }
            }
            12 if !states.is_empty() => {
                let k = rng.below(states.len());
                let mut st = states.swap_remove(k);
                unsafe { fmi3FreeFMUState(c, &mut st) }
            }
            13 if !states.is_empty() => {
                let st = states[rng.below(states.len())];
                let mut size = 0;
                let s = unsafe { fmi3SerializedFMUStateSize(c, st, &mut size) };
                if s != fmi3OK {
                    s
                } else {
                    let mut bytes = vec![0u8; size];
                    let s = unsafe { fmi3SerializeFMUState(c, st, bytes.as_mut_ptr(), size) };
                    if s == fmi3OK {
                        saved.push(bytes);
                    }
                    s
                }
            }
            14 if !saved.is_empty() => {
                let mut bytes = saved[rng.below(saved.len())].clone();
                match rng.below(3) {
                    0 => bytes.truncate(bytes.len() / 2),
                    1 => {
                        let at = rng.below(bytes.len());
                        bytes[at] ^= 0x41;
                    }
                    _ => {}
                }
                let mut st: fmi3FMUState = std::ptr::null_mut();
                let s = unsafe { fmi3DeserializeFMUState(c, bytes.as_ptr(), bytes.len(), &mut st) };
                if s == fmi3OK {
                    states.push(st);
                }
                s
            }
            _ => match rng.below(3) {
                0 => {
                    t[which] = 0.0;
                    unsafe { fmi3Reset(c) }
                }
                1 => unsafe { fmi3Terminate(c) },
                _ => unsafe { fmi3EnterInitializationMode(c, false, 0.0, 0.0, false, 0.0) },
            },
        };
        assert!(
            matches!(status, s if s == fmi3OK || s == fmi3Warning || s == fmi3Discard || s == fmi3Error),
            "{name} call {call} (kind {kind}): status {status}: {:?}",
            f.messages().last()
        );
        if status == fmi3OK {
            ok[kind] += 1;
        }
        if status == fmi3Error {
            assert_eq!(
                observe(f, &all, n_all),
                before,
                "{name} call {call} (kind {kind}) refused but changed something: {:?}",
                f.messages().last()
            );
        }
        // the instance time after a reset or a failed step, as the FMU reports it
        if kind >= 15 || status == fmi3Discard {
            let mut vr_time = [0u32];
            let mut out = [0.0];
            if unsafe { fmi3GetFloat64(c, vr_time.as_mut_ptr(), 1, out.as_mut_ptr(), 1) } == fmi3OK
            {
                t[which] = out[0];
            }
        }
    }
    for mut st in states {
        unsafe { fmi3FreeFMUState(fmus[0].c, &mut st) };
    }
    eprintln!("{name}: successful calls by kind {ok:?}");
    let steps: usize = ok[2..=4].iter().sum();
    assert!(
        steps >= 100 && ok[5] + ok[6] >= 20 && ok[7] >= 20 && ok[10] >= 20,
        "{name}: {ok:?}"
    );
    if name == "robot_arm" {
        assert!(ok[8] + ok[9] >= 3, "no derivative was taken: {ok:?}");
    }
}

#[test]
fn robot_arm_survives_random_fmi3_calls() {
    fuzz(&shipped("robot_arm"), "robot_arm", 1);
}

#[test]
fn bouncing_ball_survives_random_fmi3_calls() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/specs/bouncing_ball.toml"
    ))
    .unwrap();
    fuzz(&TestModel::new(&text), "bouncing_ball", 2);
}

#[test]
fn four_bar_survives_random_fmi3_calls() {
    fuzz(&shipped("four_bar"), "four_bar", 3);
}
