//! `simulate --set NAME=VALUE`: parameters changed before the run, checked as `fmi2SetReal`
//! checks them (the ranges of `mechanics::ranges`, then the rules involving several
//! parameters when the model is built).

use triad::mechanics::{ranges, ModelDef, SolverSettings};
use triad::spec::did_you_mean;
use triad::variables::{write_param, Causality, VariableTable};

/// Applies every `NAME=VALUE` to `def`/`settings`; all problems are reported together and
/// nothing is applied unless all are valid.
pub fn apply(
    sets: &[String],
    table: &VariableTable,
    def: &mut ModelDef,
    settings: &mut SolverSettings,
) -> Result<(), String> {
    let mut d = def.clone();
    let mut s = *settings;
    let mut problems = Vec::new();
    for set in sets {
        let Some((name, text)) = set.split_once('=') else {
            problems.push(format!("--set {set}: expected NAME=VALUE"));
            continue;
        };
        let (name, text) = (name.trim(), text.trim());
        let Some(v) = table.by_name(name) else {
            let params = table.with_causality(Causality::Parameter);
            let hint = did_you_mean(name, params.map(|v| v.name.as_str()));
            problems.push(format!("--set {name}: no such parameter{hint}"));
            continue;
        };
        if v.causality != Causality::Parameter {
            problems.push(format!(
                "--set {name}: an {} is not a parameter (inputs come from --input)",
                if v.causality == Causality::Input {
                    "input"
                } else {
                    "output"
                }
            ));
            continue;
        }
        let Ok(value) = text.parse::<f64>() else {
            problems.push(format!("--set {name}: \"{text}\" is not a number"));
            continue;
        };
        if let Err(e) = write_param(v.accessor, &mut d, &mut s, value) {
            problems.push(format!("--set {name}={text}: {e}"));
        }
    }
    if problems.is_empty() {
        problems.extend(
            ranges::cross_checks(&d)
                .into_iter()
                .map(|(what, e)| format!("--set: {what} {e}")),
        );
    }
    if !problems.is_empty() {
        return Err(problems.join("\n"));
    }
    *def = d;
    *settings = s;
    Ok(())
}
