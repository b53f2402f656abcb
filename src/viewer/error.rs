//! The viewer's errors: each names the file and says what is wrong and what to do.

use std::path::PathBuf;

/// Why a replay could not be made. Mesh problems are not errors: a mesh that cannot be found
/// or read falls back to the body's default shape with a warning (see `Page`).
#[derive(Debug, thiserror::Error)]
pub enum ViewerError {
    /// A file could not be read.
    #[error("{}: cannot read the file: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// The result CSV is malformed (bad header, a cell that is not a number, no rows).
    #[error("{origin}: {message}")]
    Csv {
        /// The CSV file.
        origin: String,
        /// What is wrong and where (line, column).
        message: String,
    },
    /// The CSV has no `body.B.r[i]` / `body.B.R[i,j]` columns at all.
    #[error(
        "{origin}: no pose columns (body.<B>.r[1..3] and body.<B>.R[1..3,1..3]); the replay \
         places the bodies from these outputs only: write them (triad simulate writes every \
         output; under fmpy record them, e.g. simulate_fmu(..., output=[names of body.*.r and \
         body.*.R]))"
    )]
    NoPoses {
        /// The CSV file.
        origin: String,
    },
    /// The CSV's bodies or geometry do not match the model's.
    #[error("{origin}: not a result of model {model}: {reason}")]
    OtherModel {
        /// The CSV file.
        origin: String,
        /// The model's name.
        model: String,
        /// Which bodies are missing or extra, or which joint is not where the model puts it.
        reason: String,
    },
    /// The model's spec does not lower (it is validated before; kept for completeness).
    #[error("{0}")]
    Model(String),
}
