//! Variable communication steps (`canHandleVariableCommunicationStepSize="true"`): every
//! `fmi2DoStep(t, H)` with a different H lands exactly on `t + H`
//! (`fmi2LastSuccessfulTime == t + H` bit for bit), and the outputs equal, bit for bit, those of
//! the in-process `Simulation` advanced by the same H — the one stepping path shared with
//! `triad simulate` (ceil(H/max_step) equal sub-steps).

mod fmu_support;

use fmu_support::*;
use triad::ffi::types::fmi2OK;
use triad::fmu::contract::read_state;
use triad::sim::Simulation;
use triad::variables::Causality;

#[test]
fn varying_steps_land_exactly_and_match_the_simulation() {
    let m = TestModel::pendulum();
    let (def, settings) = m.spec.lower().unwrap();
    let mut sim = Simulation::new(&def, settings, 0.0).unwrap();
    let f = Fmu::initialised(&m);
    let ins = m.vrs(Causality::Input);
    let outs: Vec<_> = m
        .table
        .vars
        .iter()
        .filter(|v| v.causality == Causality::Output)
        .collect();
    let mut t = 0.0_f64;
    for (n, h) in [0.01, 0.0037, 0.025, 0.001, 0.0105, 1e-5, 0.04]
        .into_iter()
        .enumerate()
    {
        let u: Vec<f64> = (0..ins.len()).map(|i| input(2, n, i)).collect();
        assert_eq!(f.set_real(&ins, &u), fmi2OK);
        sim.state_mut().inputs_mut().copy_from_slice(&u);
        assert_eq!(f.step(t, h), fmi2OK, "{:?}", f.messages());
        sim.advance(h).unwrap();
        t += h;
        assert_eq!(
            f.last_successful_time().to_bits(),
            t.to_bits(),
            "lands on t + H"
        );
        assert_eq!(sim.time().to_bits(), t.to_bits());
        let vrs: Vec<u32> = outs.iter().map(|v| v.vr).collect();
        let (_, got) = f.get_real(&vrs);
        for (v, y) in outs.iter().zip(got) {
            let want = match v.accessor {
                triad::variables::Accessor::JointQdd { joint, k } => {
                    sim.accelerations().unwrap().get(joint, k)
                }
                a => read_state(a, sim.state()),
            }
            .unwrap();
            assert_eq!(y.to_bits(), want.to_bits(), "{} after step {n}", v.name);
        }
    }
}

/// `Simulation::advance_state` steps like `advance` but leaves the outputs at their last
/// refresh; a refresh then gives, bit for bit, the outputs `advance` gives.
#[test]
fn advance_state_defers_the_outputs() {
    let m = TestModel::pendulum();
    let (def, settings) = m.spec.lower().unwrap();
    let mut a = Simulation::new(&def, settings, 0.0).unwrap();
    let mut b = Simulation::new(&def, settings, 0.0).unwrap();
    let before = format!("{:?}", b.state().outputs());
    for _ in 0..5 {
        a.advance(0.01).unwrap();
        b.advance_state(0.01).unwrap();
    }
    assert_eq!(a.state().time().to_bits(), b.state().time().to_bits());
    assert_eq!(
        format!("{:?}", b.state().outputs()),
        before,
        "outputs moved"
    );
    b.refresh_outputs();
    assert_eq!(
        format!("{:?}", b.state().outputs()),
        format!("{:?}", a.state().outputs())
    );
}
