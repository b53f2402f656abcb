//! Reading a spec: file or text → parsed (`load`) → validated (`validate`), every problem
//! reported at once; and lowering a spec to the mechanics' definition (`lower`).

use std::path::Path;

use super::error::SpecErrors;
use super::schema::{Format, Spec};
use super::{load, lower, prune, validate};
use crate::mechanics::{ModelDef, SolverSettings};

impl Spec {
    /// Reads and validates a spec file; the format follows the extension (`.toml`, `.json`).
    ///
    /// # Errors
    /// Every problem found, each with the file name and the location inside it.
    pub fn from_path(path: &Path) -> Result<Spec, SpecErrors> {
        let origin = path.display().to_string();
        let format = match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("toml") => Format::Toml,
            Some("json") => Format::Json,
            _ => {
                return Err(SpecErrors::single(
                    &origin,
                    "",
                    "unknown file type: a model spec ends in .toml or .json",
                ))
            }
        };
        let text = std::fs::read_to_string(path)
            .map_err(|e| SpecErrors::single(&origin, "", format!("cannot read the file: {e}")))?;
        Self::from_str(&text, format, &origin)
    }

    /// Parses and validates spec text; `origin` (a file name) prefixes every message.
    ///
    /// # Errors
    /// Every problem found: syntax (with line and column), structure, and model consistency.
    #[allow(clippy::should_implement_trait)]
    pub fn from_str(text: &str, format: Format, origin: &str) -> Result<Spec, SpecErrors> {
        let parsed = load::parse(text, format, origin)?;
        match parsed.spec {
            Some(spec) if parsed.problems.is_empty() => {
                validate::validate(&spec, origin)?;
                Ok(spec)
            }
            spec => {
                // shape problems first, then the consistency problems of what could be read
                let mut problems = parsed.problems;
                if let Some(spec) = spec {
                    let more = validate::structure(&spec).problems;
                    problems.extend(
                        more.into_iter()
                            .filter(|p| !parsed.pruned.iter().any(|q| prune::related(&p.path, q))),
                    );
                }
                Err(SpecErrors {
                    origin: origin.to_string(),
                    problems,
                    notes: vec![validate::SKIPPED_UNREAD.to_string()],
                })
            }
        }
    }

    /// Validates a spec built in code (e.g. by URDF import) as [`Spec::from_str`] validates a
    /// file: structure, loop closure and the mechanics' own set-up; `origin` prefixes every
    /// message.
    ///
    /// # Errors
    /// Every problem found.
    pub fn validate(&self, origin: &str) -> Result<(), SpecErrors> {
        validate::validate(self, origin)
    }

    /// Lowers to the mechanics' definition and solver settings (axes normalised, frames as
    /// matrices, tree joints first, then loop-closing ones).
    ///
    /// # Errors
    /// The structural problems of [`Spec::from_str`] validation, for a spec built in code.
    pub fn lower(&self) -> Result<(ModelDef, SolverSettings), SpecErrors> {
        validate::structure(self).finish(&self.name)?;
        Ok(lower::build(self))
    }
}
