//! The built cdylib exports all 75 functions of FMI 3.0's `fmi3Functions.h` under their exact
//! names beside the 34 `fmi2*` ones (fmpy refuses an FMI 3 FMU that lacks any), checked by
//! loading the library with the system loader as an importer does.

mod fmu_support;

use triad::ffi::fmi3::types::FMI3_FUNCTIONS;
use triad::ffi::types::FMI2_CS_FUNCTIONS;

#[test]
fn all_75_fmi3_symbols_resolve_beside_the_fmi2_ones() {
    let path = fmu_support::cdylib();
    // SAFETY (test): loading our own library runs no foreign initialisers.
    let lib = unsafe { libloading::Library::new(&path) }
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut missing = Vec::new();
    for name in FMI3_FUNCTIONS.iter().chain(&FMI2_CS_FUNCTIONS) {
        // SAFETY (test): only the address is looked up, the function is not called.
        if unsafe { lib.get::<*const ()>(name.as_bytes()) }.is_err() {
            missing.push(*name);
        }
    }
    assert!(missing.is_empty(), "missing exports: {missing:?}");
    let mut sorted = FMI3_FUNCTIONS.to_vec();
    sorted.sort_unstable();
    sorted.dedup();
    assert_eq!(sorted.len(), 75);
}

#[test]
fn the_list_is_fmi3_functions_h() {
    // the 75 names of fmi3Functions.h (FMI 3.0), by group
    let common = 61;
    let model_exchange = 10;
    let co_simulation = 3;
    let scheduled_execution = 1;
    assert_eq!(
        common + model_exchange + co_simulation + scheduled_execution,
        FMI3_FUNCTIONS.len()
    );
    for name in [
        "fmi3DeserializeFMUState",
        "fmi3SetShiftFraction",
        "fmi3GetNumberOfContinuousStates",
        "fmi3EnterStepMode",
        "fmi3ActivateModelPartition",
        "fmi3InstantiateScheduledExecution",
    ] {
        assert!(FMI3_FUNCTIONS.contains(&name), "{name}");
    }
    assert!(FMI3_FUNCTIONS.iter().all(|n| n.starts_with("fmi3")));
}
