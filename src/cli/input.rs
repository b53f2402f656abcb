//! `--input IN.csv`: a `time` column and one column per input variable, held constant from
//! each row's time until the next row (zero-order hold); before the first row inputs are 0.

use std::path::Path;

use triad::variables::{Accessor, Causality, VariableTable};

/// Input rows: which input slot each column sets, and the rows (time, values).
pub struct InputTable {
    slots: Vec<usize>,
    rows: Vec<(f64, Vec<f64>)>,
}

fn suggest(name: &str, table: &VariableTable) -> String {
    let names: Vec<&str> = table
        .with_causality(Causality::Input)
        .map(|v| v.name.as_str())
        .collect();
    if names.is_empty() {
        return "; this model has no inputs (declare actuated = true on a joint or a [[load]])"
            .into();
    }
    let close = names
        .iter()
        .find(|n| n.eq_ignore_ascii_case(name) || n.ends_with(name));
    match close {
        Some(n) => format!("; did you mean \"{n}\"?"),
        None => format!("; the inputs are: {}", names.join(", ")),
    }
}

impl InputTable {
    /// Reads and checks the CSV against the model's input variables.
    pub fn read(path: &Path, table: &VariableTable) -> Result<Self, String> {
        let at = path.display();
        let mut reader = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .from_path(path)
            .map_err(|e| format!("{at}: {e}"))?;
        let header = reader.headers().map_err(|e| format!("{at}: {e}"))?.clone();
        let mut time_col = None;
        let mut cols = Vec::new();
        let mut problems = Vec::new();
        for (c, name) in header.iter().enumerate() {
            if name == "time" {
                time_col = Some(c);
                continue;
            }
            match table.by_name(name) {
                Some(v) if v.causality == Causality::Input => {
                    if let Accessor::Input(slot) = v.accessor {
                        cols.push((c, slot));
                    }
                }
                Some(_) => problems.push(format!(
                    "{at}: column \"{name}\" is not an input variable{}",
                    suggest(name, table)
                )),
                None => problems.push(format!(
                    "{at}: unknown column \"{name}\"{}",
                    suggest(name, table)
                )),
            }
        }
        let Some(time_col) = time_col else {
            problems.push(format!("{at}: no \"time\" column"));
            return Err(problems.join("\n"));
        };
        if !problems.is_empty() {
            return Err(problems.join("\n"));
        }
        let mut rows: Vec<(f64, Vec<f64>)> = Vec::new();
        for (r, record) in reader.records().enumerate() {
            let line = r + 2;
            let record = record.map_err(|e| format!("{at}: line {line}: {e}"))?;
            let num = |c: usize| -> Result<f64, String> {
                let cell = record.get(c).unwrap_or("");
                match cell.parse::<f64>() {
                    Ok(x) if x.is_finite() => Ok(x),
                    _ => Err(format!(
                        "{at}: line {line}, column \"{}\": \"{cell}\" is not a finite number",
                        header.get(c).unwrap_or("?")
                    )),
                }
            };
            let t = num(time_col)?;
            if let Some((prev, _)) = rows.last() {
                if t < *prev {
                    return Err(format!("{at}: line {line}: time {t} is earlier than the row before ({prev}); rows must be in time order"));
                }
            }
            let values = cols
                .iter()
                .map(|(c, _)| num(*c))
                .collect::<Result<Vec<_>, _>>()?;
            rows.push((t, values));
        }
        Ok(Self {
            slots: cols.iter().map(|(_, s)| *s).collect(),
            rows,
        })
    }

    /// The time of the first row strictly between `t` and `end` (with the slack of
    /// [`InputTable::apply`]): where the next internal step must end.
    pub fn next_row_time(&self, t: f64, end: f64) -> Option<f64> {
        let slack = 1e-12 * (1.0 + t.abs().max(end.abs()));
        self.rows
            .iter()
            .map(|(rt, _)| *rt)
            .find(|&rt| rt > t + slack && rt < end - slack)
    }

    /// Sets `inputs` to the values of the latest row with time ≤ `t` (a relative slack of
    /// 1e-12 absorbs round-off in `t`); leaves them unchanged before the first row.
    pub fn apply(&self, t: f64, inputs: &mut [f64]) {
        let slack = 1e-12 * (1.0 + t.abs());
        let Some((_, values)) = self.rows.iter().rev().find(|(rt, _)| *rt <= t + slack) else {
            return;
        };
        for (slot, v) in self.slots.iter().zip(values) {
            if let Some(x) = inputs.get_mut(*slot) {
                *x = *v;
            }
        }
    }
}
