//! Reading a result CSV: a `time` column and one column per variable, named as in the FMU
//! (`body.B.r[1]`, `body.B.R[1,2]`, ...), as `triad simulate` writes it and as fmpy's
//! `write_csv` does (names in double quotes, numbers in any `f64` spelling).

use std::collections::HashMap;
use std::io::Read;
use std::path::Path;

use super::error::ViewerError;

/// The columns of a result CSV that were asked for, by name; `header` lists every column.
#[derive(Clone, Debug, Default)]
pub struct ResultTable {
    /// The file name (or `-` for memory), for messages.
    pub origin: String,
    /// Every column name in file order (surrounding spaces trimmed).
    pub header: Vec<String>,
    /// The values of the kept columns, one per row, in file order.
    pub columns: HashMap<String, Vec<f64>>,
}

impl ResultTable {
    /// Reads the CSV file `path`, keeping the columns for which `keep(name)` holds (and `time`).
    ///
    /// # Errors
    /// [`ViewerError::Read`] if the file cannot be read, [`ViewerError::Csv`] if it is not a CSV
    /// with a `time` column, has no rows, or a kept cell is not a number.
    pub fn read(path: &Path, keep: &dyn Fn(&str) -> bool) -> Result<Self, ViewerError> {
        let file = std::fs::File::open(path).map_err(|source| ViewerError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        Self::parse(file, &path.display().to_string(), keep)
    }

    /// Reads CSV text from `reader` (as [`ResultTable::read`]); `origin` names it in messages.
    ///
    /// # Errors
    /// As [`ResultTable::read`].
    pub fn parse(
        reader: impl Read,
        origin: &str,
        keep: &dyn Fn(&str) -> bool,
    ) -> Result<Self, ViewerError> {
        let fail = |message: String| ViewerError::Csv {
            origin: origin.to_string(),
            message,
        };
        let mut csv = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .from_reader(reader);
        let header: Vec<String> = csv
            .headers()
            .map_err(|e| fail(format!("not a readable CSV: {e}")))?
            .iter()
            .map(|h| h.trim().to_string())
            .collect();
        if !header.iter().any(|h| h == "time") {
            return Err(fail(format!(
                "no `time` column (the first line should name the columns: time, body.<B>.r[1], ...; found: {})",
                preview(&header)
            )));
        }
        let kept: Vec<usize> = (0..header.len())
            .filter(|&k| header[k] == "time" || keep(&header[k]))
            .collect();
        let mut columns: Vec<Vec<f64>> = vec![Vec::new(); kept.len()];
        for (row, record) in csv.records().enumerate() {
            let line = row + 2;
            let record = record.map_err(|e| fail(format!("line {line}: {e}")))?;
            if record.len() != header.len() {
                return Err(fail(format!(
                    "line {line}: {} cells, the header has {}",
                    record.len(),
                    header.len()
                )));
            }
            for (c, &k) in kept.iter().enumerate() {
                let cell = record.get(k).unwrap_or_default();
                let x = number(cell).ok_or_else(|| {
                    fail(format!(
                        "line {line}, column {}: \"{cell}\" is not a number",
                        header[k]
                    ))
                })?;
                columns[c].push(x);
            }
        }
        if columns.first().is_none_or(Vec::is_empty) {
            return Err(fail("no rows after the header".into()));
        }
        let columns = kept
            .iter()
            .zip(columns)
            .map(|(&k, v)| (header[k].clone(), v))
            .collect();
        Ok(Self {
            origin: origin.to_string(),
            header,
            columns,
        })
    }

    /// The column `name`, if it was kept.
    #[must_use]
    pub fn column(&self, name: &str) -> Option<&[f64]> {
        self.columns.get(name).map(Vec::as_slice)
    }
}

/// A cell as a number: any `f64` spelling, `nan`/`inf` in any case, `true`/`false` as 1/0.
fn number(cell: &str) -> Option<f64> {
    match cell.to_ascii_lowercase().as_str() {
        "true" => Some(1.0),
        "false" => Some(0.0),
        _ => cell.parse().ok(),
    }
}

/// The first few names of a header, for messages.
fn preview(header: &[String]) -> String {
    let mut s: Vec<&str> = header.iter().take(6).map(String::as_str).collect();
    if header.len() > 6 {
        s.push("...");
    }
    if s.is_empty() {
        "nothing".into()
    } else {
        s.join(", ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_quoted_names_and_keeps_asked_columns() {
        let text = "\"time\",\"body.a.R[1,1]\",\"x\"\n0,1.0,2\n0.5,1e0,3\n";
        let t = ResultTable::parse(text.as_bytes(), "t.csv", &|n| n.starts_with("body.")).unwrap();
        assert_eq!(t.header, ["time", "body.a.R[1,1]", "x"]);
        assert_eq!(t.column("time").unwrap(), [0.0, 0.5]);
        assert_eq!(t.column("body.a.R[1,1]").unwrap(), [1.0, 1.0]);
        assert!(t.column("x").is_none());
    }

    #[test]
    fn names_the_bad_cell() {
        let text = "time,a\n0,1\n0.1,oops\n";
        let e = ResultTable::parse(text.as_bytes(), "t.csv", &|_| true).unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.csv: line 3, column a: \"oops\" is not a number"
        );
        let e = ResultTable::parse("a,b\n1,2\n".as_bytes(), "t.csv", &|_| true).unwrap_err();
        assert!(e.to_string().contains("no `time` column"), "{e}");
        let e = ResultTable::parse("time,b\n".as_bytes(), "t.csv", &|_| true).unwrap_err();
        assert!(e.to_string().contains("no rows"), "{e}");
    }
}
