//! The error of a time step that could not be completed.

use thiserror::Error;

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
    /// Newton failed ([`StepError::NoConvergence`] or [`StepError::Singular`], the `error`)
    /// where the motion is nearly undetermined: bodies without mass or inertia whose softest
    /// motion moves almost no mass. `detail` names them and their joints, estimates the kinetic
    /// energy of that motion relative to the model's scale, and gives a hint.
    #[error("{error}; {detail}")]
    NearlyUndetermined {
        /// The failure as the iteration saw it.
        error: Box<StepError>,
        /// The diagnosis.
        detail: String,
    },
    /// Step size not positive and finite.
    #[error("invalid step size {0}")]
    BadStep(f64),
}
