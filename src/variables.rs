//! THE variable table (style.md §3 rule 2): every FMU variable and `simulate` CSV column, with
//! its value reference, name, causality, variability, initial, start, unit and accessor. The XML
//! writer, fmi2Get/Set, ModelStructure, the GUID, `describe` and `simulate` all read it; nothing
//! else invents a name or a value reference.
//!
//! Names follow interface.md §3 (structured, 1-based indices, matrices `[row,col]`).

mod access;
mod builder;
pub mod fmi3;
pub mod linear;
mod params;
mod table;
mod types;

pub use access::{read_param, read_state, write_param};
pub use types::{
    Accessor, Causality, Initial, LoopStates, VarType, Variability, Variable, VariableTable,
};
