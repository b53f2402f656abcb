//! What URDF and MJCF import share: the XML element tree with lines (`xml`), identifiers from
//! names (`names`), spec entries to start from (`entries`), rigid placements (`frame`), inertials merged (`inertia`) and the TOML
//! text of an imported spec (`toml_text`).

pub(crate) mod entries;
pub(crate) mod frame;
pub(crate) mod inertia;
pub(crate) mod names;
pub(crate) mod toml_text;
pub(crate) mod xml;
