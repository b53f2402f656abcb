//! The error of building a model: an inconsistent definition or an open loop.

use thiserror::Error;

/// A model that cannot be built or started.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ModelError {
    /// A definition that is inconsistent (the spec layer reports these first, with file paths).
    #[error("{0}")]
    Invalid(String),
    /// A body whose motion the model leaves undetermined (no mass or inertia in a direction its
    /// joints let it move without moving any body with mass).
    #[error("body '{body}' {why}")]
    Undetermined {
        /// Body name.
        body: String,
        /// What it lacks and how its joints leave it free, with the remedy.
        why: String,
    },
    /// A loop-closing joint that the initial pose does not satisfy.
    #[error("joint '{joint}': loop closure violated at the initial pose by {residual:.3e}")]
    LoopNotClosed {
        /// Joint name.
        joint: String,
        /// Largest constraint violation, m or 1.
        residual: f64,
    },
}
