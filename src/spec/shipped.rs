//! The shipped example models, embedded at build time (`build.rs`).

include!(concat!(env!("OUT_DIR"), "/bundled.rs"));

/// The shipped example models: (folder name under `modelDescription/`, `spec.toml` text).
#[must_use]
pub fn bundled() -> &'static [(&'static str, &'static str)] {
    BUNDLED
}
