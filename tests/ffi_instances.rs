//! No global state (fmi.md pitfall 3): two instances stepped alternately with different inputs
//! produce exactly (bit for bit) the outputs of two separate runs, and so do four instances
//! stepped concurrently on four threads.

mod fmu_support;

use fmu_support::*;
use triad::ffi::types::fmi2OK;
use triad::variables::Causality;

const STEPS: usize = 40;
const H: f64 = 0.01;

#[test]
fn interleaved_instances_equal_separate_runs() {
    let m = TestModel::pendulum();
    let separate: Vec<Vec<u64>> = (0..2).map(|k| run(&m, k, STEPS, H)).collect();
    let fs = [Fmu::initialised(&m), Fmu::initialised(&m)];
    let ins = m.vrs(Causality::Input);
    let outs = m.vrs(Causality::Output);
    let mut traces = vec![Vec::new(), Vec::new()];
    for n in 0..STEPS {
        for (k, f) in fs.iter().enumerate() {
            let u: Vec<f64> = (0..ins.len()).map(|i| input(k, n, i)).collect();
            assert_eq!(f.set_real(&ins, &u), fmi2OK);
        }
        for (k, f) in fs.iter().enumerate() {
            assert_eq!(f.step(n as f64 * H, H), fmi2OK);
            let (_, y) = f.get_real(&outs);
            traces[k].extend(y.iter().map(|x| x.to_bits()));
        }
    }
    assert_eq!(traces, separate);
}

#[test]
fn four_threads_equal_separate_runs() {
    let m = TestModel::pendulum();
    let separate: Vec<Vec<u64>> = (0..4).map(|k| run(&m, k, STEPS, H)).collect();
    let threaded: Vec<Vec<u64>> = std::thread::scope(|s| {
        let hs: Vec<_> = (0..4)
            .map(|k| {
                s.spawn({
                    let m = &m;
                    move || run(m, k, STEPS, H)
                })
            })
            .collect();
        hs.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert_eq!(threaded, separate);
}
