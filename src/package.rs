//! `triad build`: the .fmu archive. (placeholder; filled in by the FMU work)

use std::path::{Path, PathBuf};

/// Packages the FMU of the spec at `spec_path` into `out` (placeholder until the FMU work lands).
///
/// # Errors
/// Always, until the FMU packaging is merged.
pub fn build_fmu(spec_path: &Path, out: &Path) -> Result<PathBuf, Box<dyn std::error::Error>> {
    let _ = (spec_path, out);
    Err("FMU packaging is not yet built".into())
}
