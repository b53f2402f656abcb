//! The seam to the spec and variable-table work: everything the FMU layer needs from
//! `crate::spec` and `crate::variables`, imported in one place.

use crate::mechanics::{ModelDef, SolverSettings};
use crate::variables::VariableTable;

pub use crate::spec::{bundled, Format, Spec, SpecErrors};
pub use crate::variables::{read_param, read_state, write_param};

/// The variable table of a lowered model ([`VariableTable::new`]), with the spec's labels
/// (original URDF names) in the descriptions.
#[must_use]
pub fn table(spec: &Spec, def: &ModelDef, settings: &SolverSettings) -> VariableTable {
    VariableTable::new(def, settings).with_labels(&spec.labels())
}
