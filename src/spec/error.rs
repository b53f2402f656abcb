//! Spec problems: every problem found in one file, each with its location and reason.

use std::fmt;

/// One problem in a spec: where (`joint[1].axis`, or `line 3, column 7` for syntax errors; empty
/// for the file as a whole) and what is wrong.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Problem {
    /// Location inside the spec: a field path with 0-based array indices (`joint[1].axis`), a
    /// `line L, column C` position, or empty.
    pub path: String,
    /// What is wrong, and where useful how to fix it.
    pub message: String,
}

impl Problem {
    /// A problem at `path`.
    #[must_use]
    pub fn new(path: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            path: path.into(),
            message: message.into(),
        }
    }
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.path.is_empty() {
            write!(f, "{}", self.message)
        } else {
            write!(f, "{}: {}", self.path, self.message)
        }
    }
}

/// Every problem found in one spec. `Display` prints one line per problem, prefixed by the
/// origin (the file name): `double_pendulum.toml: joint[1].axis: zero length`; the notes
/// (stages skipped) are not part of it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SpecErrors {
    /// File name (or other origin) used in messages.
    pub origin: String,
    /// The problems, in document order where possible. Never empty.
    pub problems: Vec<Problem>,
    /// What was not checked, and why (`further checks skipped: …`): a stage that cannot run on
    /// input with these problems.
    pub notes: Vec<String>,
}

impl SpecErrors {
    /// A single problem.
    #[must_use]
    pub fn single(origin: &str, path: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            origin: origin.to_string(),
            problems: vec![Problem::new(path, message)],
            notes: Vec::new(),
        }
    }

    /// These errors with the note `note` (a stage skipped, and why).
    #[must_use]
    pub fn noting(mut self, note: impl Into<String>) -> Self {
        self.notes.push(note.into());
        self
    }
}

impl fmt::Display for SpecErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (k, p) in self.problems.iter().enumerate() {
            if k > 0 {
                writeln!(f)?;
            }
            write!(f, "{}: {p}", self.origin)?;
        }
        Ok(())
    }
}

impl std::error::Error for SpecErrors {}

/// Collects problems during validation.
#[derive(Debug, Default)]
pub(crate) struct Report {
    pub(crate) problems: Vec<Problem>,
    /// Stages skipped, and why.
    pub(crate) notes: Vec<String>,
}

impl Report {
    /// Adds a problem.
    pub(crate) fn push(&mut self, path: impl Into<String>, message: impl Into<String>) {
        self.problems.push(Problem::new(path, message));
    }

    /// True when nothing was reported.
    pub(crate) fn is_empty(&self) -> bool {
        self.problems.is_empty()
    }

    /// `Ok(())` when empty, else the errors of `origin`.
    pub(crate) fn finish(self, origin: &str) -> Result<(), SpecErrors> {
        if self.problems.is_empty() {
            Ok(())
        } else {
            Err(SpecErrors {
                origin: origin.to_string(),
                problems: self.problems,
                notes: self.notes,
            })
        }
    }
}

/// Edit distance between two short strings (for "did you mean" hints).
pub(crate) fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, cb) in b.iter().enumerate() {
            let sub = prev[j] + usize::from(ca != *cb);
            cur[j + 1] = sub.min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

/// `; did you mean "x"?` for the closest candidate within a small edit distance, else empty.
pub fn did_you_mean<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> String {
    let best = candidates
        .into_iter()
        .map(|c| (edit_distance(&word.to_lowercase(), &c.to_lowercase()), c))
        .min_by_key(|(d, _)| *d);
    match best {
        Some((d, c)) if d <= 2.max(word.len() / 3) && d > 0 => format!("; did you mean \"{c}\"?"),
        _ => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_one_line_per_problem() {
        let e = SpecErrors {
            origin: "dp.toml".into(),
            problems: vec![
                Problem::new("joint[1].axis", "zero length"),
                Problem::new("", "empty"),
            ],
            notes: Vec::new(),
        };
        assert_eq!(
            e.to_string(),
            "dp.toml: joint[1].axis: zero length\ndp.toml: empty"
        );
    }

    #[test]
    fn suggestions() {
        assert_eq!(
            did_you_mean("mas", ["mass", "name"]),
            "; did you mean \"mass\"?"
        );
        assert_eq!(did_you_mean("zzzzzz", ["mass"]), "");
    }
}
