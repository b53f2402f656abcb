//! Errors of the mechanics core: set-up errors and failed steps (numbers fail as values).

use thiserror::Error;

/// A model that cannot be built or started.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ModelError {
    /// A definition that is inconsistent (the spec layer reports these first, with file paths).
    #[error("{0}")]
    Invalid(String),
    /// A loop-closing joint that the initial pose does not satisfy.
    #[error("joint '{joint}': loop closure violated at the initial pose by {residual:.3e}")]
    LoopNotClosed {
        /// Joint name.
        joint: String,
        /// Largest constraint violation, m or 1.
        residual: f64,
    },
}

/// A time step that could not be completed; the state is left as it was before the step.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum StepError {
    /// Newton did not reach the tolerance within the iteration limit.
    #[error("Newton did not converge in {iterations} iterations (scaled residual {residual:.3e})")]
    NoConvergence {
        /// Iterations taken.
        iterations: usize,
        /// Last scaled residual norm.
        residual: f64,
    },
    /// The iteration matrix was singular.
    #[error("singular iteration matrix")]
    Singular,
    /// A NaN or infinity appeared (inputs or state).
    #[error("non-finite value in {0}")]
    NonFinite(&'static str),
    /// Step size not positive and finite.
    #[error("invalid step size {0}")]
    BadStep(f64),
}
