//! The exported `fmi2*` C functions: the only module with `unsafe` code.
//! (placeholder; filled in by the FMU work)
