//! The error of a command: spec problems (one line each) or one message.

use triad::spec::SpecErrors;

/// A failed command: the message to print.
#[derive(Debug)]
pub enum CliError {
    /// Problems in the spec (one line each).
    Spec(SpecErrors),
    /// Anything else.
    Other(String),
}

impl From<SpecErrors> for CliError {
    fn from(e: SpecErrors) -> Self {
        Self::Spec(e)
    }
}

impl From<String> for CliError {
    fn from(e: String) -> Self {
        Self::Other(e)
    }
}
