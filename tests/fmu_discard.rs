//! A communication step that cannot be completed returns `fmi2Discard` (FMI 2.0.4 §4.2.2), logs
//! why (`logStatusDiscard`), reports `fmi2LastSuccessfulTime` = the start of the step, and leaves
//! the instance usable there: outputs are those of the last good time, and the next
//! `fmi2DoStep` from that time with a reasonable input succeeds.
//!
//! The failure is provoked with an absurd actuator torque (1e300 N·m over one 0.5 s sub-step):
//! the Newton iteration overflows or diverges, which the mechanics reports as a failed step.

mod fmu_support;

use fmu_support::*;
use triad::ffi::types::*;
use triad::variables::Causality;

#[test]
fn failed_step_discards_and_continues_from_the_last_good_time() {
    let m = TestModel::pendulum();
    let f = Fmu::new(&m);
    let ms = m.vr("solver.max_step");
    assert_eq!(f.set_real(&[ms], &[0.5]), fmi2OK);
    assert_eq!(f.setup(0.0), fmi2OK);
    assert_eq!(
        unsafe { triad::ffi::common::fmi2EnterInitializationMode(f.c) },
        fmi2OK
    );
    assert_eq!(
        unsafe { triad::ffi::common::fmi2ExitInitializationMode(f.c) },
        fmi2OK
    );
    let ins = m.vrs(Causality::Input);
    // the outputs that are values of the state (the accelerations also follow the inputs held)
    let outs: Vec<u32> = m
        .table
        .with_causality(Causality::Output)
        .filter(|v| !matches!(v.accessor, triad::variables::Accessor::JointQdd { .. }))
        .map(|v| v.vr)
        .collect();
    assert_eq!(f.step(0.0, 0.1), fmi2OK);
    let (_, good) = f.get_real(&outs);

    assert_eq!(f.set_real(&ins[..1], &[1e300]), fmi2OK);
    assert_eq!(f.step(0.1, 0.5), fmi2Discard);
    let (status, cat, msg) = f.messages().last().cloned().unwrap();
    assert_eq!((status, cat.as_str()), (fmi2Discard, "logStatusDiscard"));
    assert!(msg.contains("rolled back to t = 0.1"), "{msg}");
    assert_eq!(f.last_successful_time(), 0.1);
    assert_eq!(
        f.get_real(&outs)
            .1
            .iter()
            .map(|x| x.to_bits())
            .collect::<Vec<_>>(),
        good.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
    );

    // continue from the last good time
    assert_eq!(f.set_real(&ins[..1], &[0.0]), fmi2OK);
    assert_eq!(f.step(0.1, 0.1), fmi2OK, "{:?}", f.messages());
    assert_eq!(f.last_successful_time(), 0.2);
}
