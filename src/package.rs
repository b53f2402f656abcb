//! `triad build`: the .fmu archive. (placeholder; filled in by the FMU work)
