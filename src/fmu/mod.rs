//! Safe FMI 2.0 Co-Simulation semantics: instance state machine, get/set by value reference,
//! snapshots, GUID. No `unsafe`, no C types. (placeholder; filled in by the FMU work)
