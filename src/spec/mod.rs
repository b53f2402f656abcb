//! The model spec (interface.md §2): serde structs read from TOML and JSON, validation that
//! reports every problem with file and path, lowering to `mechanics::ModelDef`.
//! (placeholder; filled in by the spec work)
