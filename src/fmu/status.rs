//! FMI return statuses and the FMU layer's error type.

use thiserror::Error;

/// `fmi2Status` without the C representation (FMI 2.0.4 §2.1.3). `Pending` is never returned:
/// `fmi2DoStep` is synchronous.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Status {
    /// `fmi2OK`.
    Ok,
    /// `fmi2Warning`.
    Warning,
    /// `fmi2Discard`: the step or value was rejected, the instance is usable.
    Discard,
    /// `fmi2Error`.
    Error,
    /// `fmi2Fatal`.
    Fatal,
}

/// Why an FMU call did not succeed. The message says what and where; [`FmuError::status`] gives
/// the FMI status it maps to.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FmuError {
    /// A call not allowed in the current mode (FMI 2.0.4 §4.2.4); nothing changed.
    #[error("{op} is not allowed in {mode}")]
    IllegalCall {
        /// The function, e.g. `fmi2DoStep`.
        op: &'static str,
        /// The current mode.
        mode: &'static str,
    },
    /// A call rejected for its arguments (unknown VR, forbidden set, non-finite value, NULL
    /// pointer, wrong communication point); nothing changed.
    #[error("{0}")]
    Rejected(String),
    /// A failure that leaves the instance in Error mode (reset or restore an FMU state).
    #[error("{0}")]
    Failed(String),
    /// A step that could only be completed up to an earlier time; the instance is usable there.
    #[error("{0}")]
    Discard(String),
    /// The function is exported but not supported (capability flag false).
    #[error("{0}")]
    Unsupported(String),
    /// The instance was poisoned by an earlier panic.
    #[error("instance is unusable after an earlier fatal error; only freeing it (fmi2FreeInstance, fmi3FreeInstance) is allowed")]
    Poisoned,
}

impl FmuError {
    /// The FMI status this error is reported with.
    #[must_use]
    pub fn status(&self) -> Status {
        match self {
            Self::Discard(_) => Status::Discard,
            _ => Status::Error,
        }
    }

    /// Shorthand for a rejected call.
    #[must_use]
    pub fn rejected(msg: impl Into<String>) -> Self {
        Self::Rejected(msg.into())
    }
}
