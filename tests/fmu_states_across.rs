//! FMU states move between instances (FMI 2.0.4 §2.1.8 sets no rule against it, and hosts rely
//! on it: a run moved to a fresh instance, pools of instances in parallel sweeps): a state got
//! in instance A and set in B continues bit-identically, B may serialise and free it, and 8
//! threads may exchange states between their instances. What stays refused, without the
//! pointer being dereferenced: a pointer no live instance handed out (forged), a state freed
//! already (through any instance, or with its instance), and a state of another model loaded in
//! the same process (another GUID).

mod fmu_support;

use fmu_support::api::*;
use fmu_support::*;
use triad::ffi::types::*;
use triad::variables::Causality;

const H: f64 = 0.01;

/// The state's outputs after `steps` steps from `t0` with input set `k`.
fn continue_run(f: &Fmu, m: &TestModel, k: usize, t0: f64, steps: usize) -> Vec<u64> {
    let ins = m.vrs(Causality::Input);
    let outs = m.vrs(Causality::Output);
    let mut trace = Vec::new();
    for n in 0..steps {
        let u: Vec<f64> = (0..ins.len()).map(|i| input(k, n, i)).collect();
        assert_eq!(f.set_real(&ins, &u), fmi2OK);
        assert_eq!(f.step(t0 + n as f64 * H, H), fmi2OK, "{}", f.last_message());
        trace.extend(f.get_real(&outs).1.iter().map(|x| x.to_bits()));
    }
    trace
}

fn get_state(f: &Fmu) -> fmi2FMUstate {
    let mut st: fmi2FMUstate = std::ptr::null_mut();
    assert_eq!(unsafe { fmi2GetFMUstate(f.c, &mut st) }, fmi2OK);
    assert!(!st.is_null());
    st
}

#[test]
fn a_state_of_one_instance_continues_bit_identically_in_another() {
    let m = TestModel::pendulum();
    let a = Fmu::initialised(&m);
    continue_run(&a, &m, 0, 0.0, 20);
    let st = get_state(&a);
    let want = continue_run(&a, &m, 1, 20.0 * H, 30);
    // a fresh instance, and one that had run elsewhere
    for b in [Fmu::new(&m), Fmu::initialised(&m)] {
        assert_eq!(
            unsafe { fmi2SetFMUstate(b.c, st) },
            fmi2OK,
            "{}",
            b.last_message()
        );
        assert_eq!(continue_run(&b, &m, 1, 20.0 * H, 30), want);
        // B serialises A's state, and its bytes restore in A
        let mut n = 0usize;
        assert_eq!(
            unsafe { fmi2SerializedFMUstateSize(b.c, st, &mut n) },
            fmi2OK
        );
        let mut bytes = vec![0u8; n];
        assert_eq!(
            unsafe { fmi2SerializeFMUstate(b.c, st, bytes.as_mut_ptr().cast(), n) },
            fmi2OK
        );
        assert_eq!(a.deserialize(&bytes), fmi2OK);
    }
    // B may overwrite A's state in place (fmi2GetFMUstate with *state set) and free it
    let b = Fmu::initialised(&m);
    let mut slot = st;
    assert_eq!(unsafe { fmi2GetFMUstate(b.c, &mut slot) }, fmi2OK);
    assert_eq!(slot, st, "a live state of the model is reused in place");
    assert_eq!(unsafe { fmi2FreeFMUstate(b.c, &mut slot) }, fmi2OK);
    assert!(slot.is_null());
    // freed through B: refused by A and B alike
    assert_eq!(unsafe { fmi2SetFMUstate(a.c, st) }, fmi2Error);
    assert!(
        a.last_message().contains("not a live FMU state"),
        "{}",
        a.last_message()
    );
    let mut again = st;
    assert_eq!(unsafe { fmi2FreeFMUstate(b.c, &mut again) }, fmi2Error);
}

#[test]
fn states_of_a_freed_instance_are_refused() {
    let m = TestModel::pendulum();
    let b = Fmu::initialised(&m);
    let st = {
        let a = Fmu::initialised(&m);
        let st = get_state(&a);
        assert_eq!(unsafe { fmi2SetFMUstate(b.c, st) }, fmi2OK);
        st
        // A is freed here, and every state it allocated with it
    };
    assert_eq!(unsafe { fmi2SetFMUstate(b.c, st) }, fmi2Error);
    let mut n = 0usize;
    assert_eq!(
        unsafe { fmi2SerializedFMUstateSize(b.c, st, &mut n) },
        fmi2Error
    );
    assert_eq!(b.step(0.0, H), fmi2OK, "B goes on: {}", b.last_message());
}

#[test]
fn forged_pointers_and_other_models_states_are_refused() {
    let m = TestModel::pendulum();
    let f = Fmu::initialised(&m);
    // a pointer that is no state at all is never dereferenced (its bytes are not a snapshot)
    let mut junk = [0u64; 8];
    let fake: fmi2FMUstate = junk.as_mut_ptr().cast();
    assert_eq!(unsafe { fmi2SetFMUstate(f.c, fake) }, fmi2Error);
    let mut n = 0usize;
    assert_eq!(
        unsafe { fmi2SerializedFMUstateSize(f.c, fake, &mut n) },
        fmi2Error
    );
    let mut fake_slot = fake;
    assert_eq!(unsafe { fmi2FreeFMUstate(f.c, &mut fake_slot) }, fmi2Error);
    assert_eq!(fake_slot, fake, "a refused free leaves the pointer");
    // fmi2GetFMUstate with a forged *state allocates a new one instead of writing through it
    let mut slot = fake;
    assert_eq!(unsafe { fmi2GetFMUstate(f.c, &mut slot) }, fmi2OK);
    assert_ne!(slot, fake);
    assert_eq!(junk, [0u64; 8]);
    // a second model in the same process: its states are not this model's
    let dp = triad::spec::bundled()
        .iter()
        .find(|(n, _)| *n == "double_pendulum")
        .expect("the double pendulum is shipped")
        .1;
    let other = TestModel::new(dp);
    let g = Fmu::initialised(&other);
    let theirs = get_state(&g);
    let before = f.serialize();
    assert_eq!(unsafe { fmi2SetFMUstate(f.c, theirs) }, fmi2Error);
    assert!(
        f.last_message().contains("belongs to model"),
        "{}",
        f.last_message()
    );
    assert_eq!(
        unsafe { fmi2SerializedFMUstateSize(f.c, theirs, &mut n) },
        fmi2Error
    );
    let mut slot = theirs;
    assert_eq!(unsafe { fmi2FreeFMUstate(f.c, &mut slot) }, fmi2Error);
    assert_eq!(slot, theirs, "another model's state is not freed");
    // reusing another model's state as the slot of fmi2GetFMUstate leaves it alone
    let mut slot = theirs;
    assert_eq!(unsafe { fmi2GetFMUstate(f.c, &mut slot) }, fmi2OK);
    assert_ne!(slot, theirs);
    assert_eq!(f.serialize(), before, "nothing changed");
    assert_eq!(
        unsafe { fmi2SetFMUstate(g.c, theirs) },
        fmi2OK,
        "still live for its own model"
    );
}

#[test]
fn eight_threads_exchange_states_between_their_instances() {
    let m = TestModel::pendulum();
    const THREADS: usize = 8;
    const ROUNDS: usize = 10;
    // one shared pool of states, all of the same model; each thread sets a state from the pool
    // into its own instance, steps, and puts its own state back, so states made by one instance
    // are continued by others all the time
    let seed = Fmu::initialised(&m);
    let seeds: Vec<usize> = (0..THREADS).map(|_| get_state(&seed) as usize).collect();
    let pool = std::sync::Mutex::new(seeds);
    let results: Vec<Vec<(f64, Vec<u64>)>> = std::thread::scope(|s| {
        let hs: Vec<_> = (0..THREADS)
            .map(|k| {
                let (m, pool) = (&m, &pool);
                s.spawn(move || {
                    let f = Fmu::initialised(m);
                    let outs = m.vrs(Causality::Output);
                    let mut seen = Vec::new();
                    for r in 0..ROUNDS {
                        let st = {
                            let p = pool.lock().unwrap();
                            p[(k + r) % THREADS] as fmi2FMUstate
                        };
                        assert_eq!(
                            unsafe { fmi2SetFMUstate(f.c, st) },
                            fmi2OK,
                            "{}",
                            f.last_message()
                        );
                        let t = f.last_successful_time();
                        assert_eq!(f.step(t, H), fmi2OK, "{}", f.last_message());
                        seen.push((
                            t + H,
                            f.get_real(&outs).1.iter().map(|x| x.to_bits()).collect(),
                        ));
                        // put this instance's state back into a pool slot: overwrite in place
                        let p = pool.lock().unwrap();
                        let mut slot = p[(k + r) % THREADS] as fmi2FMUstate;
                        assert_eq!(unsafe { fmi2GetFMUstate(f.c, &mut slot) }, fmi2OK);
                        assert_eq!(slot as usize, p[(k + r) % THREADS]);
                    }
                    seen
                })
            })
            .collect();
        hs.into_iter().map(|h| h.join().unwrap()).collect()
    });
    // every continuation equals an unshared run of the pendulum to that time (it has no inputs
    // set, so the trajectory is one: the state at time t determines the outputs)
    let single = Fmu::initialised(&m);
    let outs = m.vrs(Causality::Output);
    let mut truth = std::collections::HashMap::new();
    let mut t = 0.0;
    for _ in 0..=THREADS * ROUNDS {
        assert_eq!(single.step(t, H), fmi2OK);
        t += H;
        truth.insert(
            t.to_bits(),
            single
                .get_real(&outs)
                .1
                .iter()
                .map(|x| x.to_bits())
                .collect::<Vec<u64>>(),
        );
    }
    for (t, y) in results.iter().flatten() {
        assert_eq!(truth.get(&t.to_bits()), Some(y), "continuation at t = {t}");
    }
}
