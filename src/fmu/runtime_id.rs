//! The runtime id: which sources a runtime binary was built from (`build.rs` hashes them), so
//! that `triad build` packs only runtimes of its own sources (`platforms.rs`).

/// The runtime id: 16 hex digits hashing the sources this runtime compiles (`build.rs`), the
/// same for the CLI and every platform's runtime built from one tree.
pub const RUNTIME_ID: &str = env!("TRIAD_RUNTIME_ID");

/// The runtime id as it stands in every runtime binary (in the message of an FMU whose model
/// cannot be read), where `triad build` looks for it: `triad-runtime-id:` and [`RUNTIME_ID`].
pub const RUNTIME_TAG: &str = concat!("triad-runtime-id:", env!("TRIAD_RUNTIME_ID"));
