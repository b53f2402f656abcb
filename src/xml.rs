//! modelDescription.xml (FMI 2.0.4 §2.2) written with quick-xml from the variable table — never
//! by hand. Deterministic: fixed element and attribute order, no generation date, floats in
//! Rust's shortest round-trip form, ModelStructure indices from table order.

use crate::fmu::contract::Spec;
use crate::fmu::{Category, CAPABILITIES};
use crate::mechanics::SolverSettings;
use crate::variables::linear::{differentiable, states, States};
use crate::variables::{Accessor, Causality, Initial, VarType, Variable, VariableTable};
use quick_xml::events::{BytesDecl, BytesText, Event};
use quick_xml::Writer;
use std::collections::BTreeSet;
use std::io;

/// `generationTool`.
pub const GENERATION_TOOL: &str = concat!("triad ", env!("CARGO_PKG_VERSION"));

/// Degrees per radian, the `deg` display-unit factor.
pub const DEG_PER_RAD: f64 = 57.29577951308232;

/// What the XML needs besides the table.
#[derive(Clone, Debug, PartialEq)]
pub struct Meta {
    /// `modelName` and `modelIdentifier`.
    pub name: String,
    /// `description`.
    pub description: String,
    /// `guid` ([`crate::fmu::guid::guid`]).
    pub guid: String,
    /// DefaultExperiment `startTime`, `stopTime`, `stepSize`, s.
    pub start: f64,
    /// See `start`.
    pub stop: f64,
    /// See `start`.
    pub step: f64,
    /// DefaultExperiment `tolerance` (the Newton tolerance).
    pub tolerance: f64,
}

impl Meta {
    /// The metadata of a spec.
    #[must_use]
    pub fn new(spec: &Spec, settings: &SolverSettings, table: &VariableTable) -> Meta {
        Meta {
            name: spec.name.clone(),
            description: spec.description.clone(),
            guid: crate::fmu::guid::guid(&spec.canonical_json(), table),
            start: spec.experiment.start,
            stop: spec.experiment.stop,
            step: spec.experiment.step,
            tolerance: settings.tolerance,
        }
    }
}

/// SI base-unit exponents `(kg, m, s, rad)` of the units triad uses.
fn base_unit(unit: &str) -> Option<[i32; 4]> {
    Some(match unit {
        "1" => [0, 0, 0, 0],
        "m" => [0, 1, 0, 0],
        "m/s" => [0, 1, -1, 0],
        "m/s2" => [0, 1, -2, 0],
        "rad" => [0, 0, 0, 1],
        "rad/s" => [0, 0, -1, 1],
        "rad/s2" => [0, 0, -2, 1],
        "s" => [0, 0, 1, 0],
        "kg" => [1, 0, 0, 0],
        "kg.m2" => [1, 2, 0, 0],
        "N" => [1, 1, -2, 0],
        "N.m" | "J" => [1, 2, -2, 0],
        "N.s" => [1, 1, -1, 0],
        "N.m.s" => [1, 2, -1, 0],
        "N/m" => [1, 0, -2, 0],
        "N.s/m" => [1, 0, -1, 0],
        "N.s/m2" => [1, -1, -1, 0],
        "s/m" => [0, -1, 1, 0],
        "N.m/rad" => [1, 2, -2, -1],
        "N.m.s/rad" => [1, 2, -1, -1],
        _ => return None,
    })
}

/// Display units declared under a unit: (name, factor).
fn display_units(unit: &str) -> &'static [(&'static str, f64)] {
    match unit {
        "rad" => &[("deg", DEG_PER_RAD)],
        "rad/s" => &[("deg/s", DEG_PER_RAD)],
        _ => &[],
    }
}

/// A real as written to the XML: the shorter of Rust's two round-trip forms (`0`, `0.01`,
/// `1e-10`, `57.29577951308232`), so integral values carry no `.0`.
#[must_use]
pub fn real(x: f64) -> String {
    let plain = format!("{x}");
    let sci = format!("{x:?}");
    if sci.len() < plain.len() {
        sci
    } else {
        plain
    }
}

/// The in-memory XML writer of both model descriptions.
pub(crate) type W = Writer<Vec<u8>>;

/// The units of `table`'s variables (sorted, each once).
pub(crate) fn used_units(table: &VariableTable) -> BTreeSet<&'static str> {
    table.vars.iter().filter_map(|v| v.unit).collect()
}

/// `<UnitDefinitions>` of the units `used` (the same form in FMI 2 and FMI 3: `<Unit name>`
/// with `<BaseUnit>` and its `<DisplayUnit>`s); nothing when `used` is empty.
pub(crate) fn unit_definitions(w: &mut W, used: &BTreeSet<&str>) -> io::Result<()> {
    if used.is_empty() {
        return Ok(());
    }
    w.create_element("UnitDefinitions")
        .write_inner_content(|w| {
            for &unit in used {
                w.create_element("Unit")
                    .with_attribute(("name", unit))
                    .write_inner_content(|w| {
                        let mut base = w.create_element("BaseUnit");
                        if let Some(e) = base_unit(unit) {
                            for (name, exp) in ["kg", "m", "s", "rad"].into_iter().zip(e) {
                                if exp != 0 {
                                    base = base.with_attribute((name, exp.to_string().as_str()));
                                }
                            }
                        }
                        base.write_empty()?;
                        for (name, factor) in display_units(unit) {
                            w.create_element("DisplayUnit")
                                .with_attribute(("name", *name))
                                .with_attribute(("factor", real(*factor).as_str()))
                                .write_empty()?;
                        }
                        Ok(())
                    })?;
            }
            Ok(())
        })?;
    Ok(())
}

/// `<DefaultExperiment>` of `meta` (the same in FMI 2 and FMI 3).
pub(crate) fn default_experiment(w: &mut W, meta: &Meta) -> io::Result<()> {
    w.create_element("DefaultExperiment")
        .with_attribute(("startTime", real(meta.start).as_str()))
        .with_attribute(("stopTime", real(meta.stop).as_str()))
        .with_attribute(("tolerance", real(meta.tolerance).as_str()))
        .with_attribute(("stepSize", real(meta.step).as_str()))
        .write_empty()?;
    Ok(())
}

/// The attributes both FMI versions give a variable, in their order: `name`,
/// `valueReference`, `description` (if any), `causality`, `variability`, `initial` (`exact`
/// but for inputs, or `calculated`); `v` gives the kinds, `name` and `vr` may be FMI 3's.
pub(crate) fn common_attributes<'a>(
    mut e: quick_xml::writer::ElementWriter<'a, Vec<u8>>,
    name: &'a str,
    vr: u32,
    description: &'a str,
    v: &Variable,
) -> quick_xml::writer::ElementWriter<'a, Vec<u8>> {
    e = e
        .with_attribute(("name", name))
        .with_attribute(("valueReference", vr.to_string().as_str()));
    if !description.is_empty() {
        e = e.with_attribute(("description", description));
    }
    e = e.with_attribute(("causality", v.causality.fmi_name()));
    e = e.with_attribute(("variability", v.variability.fmi_name()));
    match v.initial {
        Initial::Exact if v.causality != Causality::Input => {
            e = e.with_attribute(("initial", "exact"));
        }
        Initial::Calculated => e = e.with_attribute(("initial", "calculated")),
        _ => {}
    }
    e
}

/// The 1-based index of the state whose derivative variable `i` (0-based) is: `joint.J.qd` of
/// `joint.J.q`, `joint.J.qdd` of `joint.J.qd` (models that declare states).
fn derivative_of(st: Option<&States>, i: usize) -> Option<usize> {
    let st = st?;
    let find = |xs: &[usize]| xs.iter().position(|&x| x == i);
    find(&st.qd)
        .map(|k| st.q[k] + 1)
        .or_else(|| find(&st.qdd).map(|k| st.qd[k] + 1))
}

/// The `dependencies` of output `i` (0-based) when the model declares states: every state,
/// and every input too for an acceleration (direct feedthrough); none for what has no
/// directional derivatives (`variables::linear::differentiable`: `system.work` and the
/// constraint residual, accumulated or solver quantities; loop-closing joints' coordinates and
/// rates); without states, none (outputs are values of the last step, not of the inputs).
fn output_dependencies(table: &VariableTable, st: Option<&States>, i: usize) -> String {
    let Some(st) = st else {
        return String::new();
    };
    let v = &table.vars[i];
    if !differentiable(table, v.accessor) {
        return String::new();
    }
    let mut deps: Vec<usize> = st.q.iter().chain(&st.qd).map(|k| k + 1).collect();
    if matches!(v.accessor, Accessor::JointQdd { .. }) {
        deps.extend(
            table
                .vars
                .iter()
                .enumerate()
                .filter(|(_, w)| w.causality == Causality::Input)
                .map(|(k, _)| k + 1),
        );
    }
    deps.sort_unstable();
    deps.iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join(" ")
}

fn scalar_variable(w: &mut W, v: &Variable, derivative: Option<usize>) -> io::Result<()> {
    let e = common_attributes(
        w.create_element("ScalarVariable"),
        &v.name,
        v.vr,
        &v.description,
        v,
    );
    e.write_inner_content(|w| {
        let (tag, start) = match v.ty {
            VarType::Real => ("Real", v.start.map(real)),
            VarType::Integer => ("Integer", v.start.map(|s| format!("{}", s as i64))),
        };
        let mut t = w.create_element(tag);
        if let Some(unit) = v.unit.filter(|_| v.ty == VarType::Real) {
            t = t.with_attribute(("unit", unit));
            if let Some(d) = v.display_unit {
                t = t.with_attribute(("displayUnit", d));
            }
        }
        if v.initial != Initial::Calculated {
            if let Some(s) = &start {
                t = t.with_attribute(("start", s.as_str()));
            }
        }
        if let Some(d) = derivative {
            t = t.with_attribute(("derivative", d.to_string().as_str()));
        }
        t.write_empty()?;
        Ok(())
    })?;
    Ok(())
}

fn model_structure(w: &mut W, table: &VariableTable) -> io::Result<()> {
    let st = states(table);
    let outputs: Vec<usize> = table
        .vars
        .iter()
        .enumerate()
        .filter(|(_, v)| v.causality == Causality::Output)
        .map(|(i, _)| i + 1)
        .collect();
    let initial: Vec<usize> = table
        .vars
        .iter()
        .enumerate()
        .filter(|(_, v)| v.causality == Causality::Output && v.initial == Initial::Calculated)
        .map(|(i, _)| i + 1)
        .collect();
    w.create_element("ModelStructure")
        .write_inner_content(|w| {
            if !outputs.is_empty() {
                w.create_element("Outputs").write_inner_content(|w| {
                    for i in &outputs {
                        let deps = output_dependencies(table, st.as_ref(), i - 1);
                        w.create_element("Unknown")
                            .with_attribute(("index", i.to_string().as_str()))
                            .with_attribute(("dependencies", deps.as_str()))
                            .write_empty()?;
                    }
                    Ok(())
                })?;
            }
            if let Some(st) = &st {
                // the state vector (q…, qd…): its derivatives qd… then qdd…
                w.create_element("Derivatives").write_inner_content(|w| {
                    for (k, &i) in st.qd.iter().enumerate() {
                        w.create_element("Unknown")
                            .with_attribute(("index", (i + 1).to_string().as_str()))
                            .with_attribute(("dependencies", (st.qd[k] + 1).to_string().as_str()))
                            .write_empty()?;
                    }
                    for &i in &st.qdd {
                        let deps = output_dependencies(table, Some(st), i);
                        w.create_element("Unknown")
                            .with_attribute(("index", (i + 1).to_string().as_str()))
                            .with_attribute(("dependencies", deps.as_str()))
                            .write_empty()?;
                    }
                    Ok(())
                })?;
            }
            if !initial.is_empty() {
                w.create_element("InitialUnknowns")
                    .write_inner_content(|w| {
                        for i in &initial {
                            // dependencies omitted: may depend on every parameter
                            w.create_element("Unknown")
                                .with_attribute(("index", i.to_string().as_str()))
                                .write_empty()?;
                        }
                        Ok(())
                    })?;
            }
            Ok(())
        })?;
    Ok(())
}

/// Writes modelDescription.xml.
///
/// # Errors
/// Only I/O errors of the in-memory writer (none in practice).
pub fn write_model_description(table: &VariableTable, meta: &Meta) -> io::Result<String> {
    let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
    w.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None)))?;
    w.write_event(Event::Comment(BytesText::from_escaped(
        " Generated by triad from the model spec; do not edit. Regenerate it by running the golden_xml test with UPDATE_GOLDEN=1 ",
    )))?;
    let n_vars = table.vars.len();
    let st = states(table);
    w.create_element("fmiModelDescription")
        .with_attribute(("fmiVersion", "2.0"))
        .with_attribute(("modelName", meta.name.as_str()))
        .with_attribute(("guid", meta.guid.as_str()))
        .with_attribute(("description", meta.description.as_str()))
        .with_attribute(("generationTool", GENERATION_TOOL))
        .with_attribute(("variableNamingConvention", "structured"))
        .with_attribute(("numberOfEventIndicators", "0"))
        .write_inner_content(|w| {
            let attrs = CAPABILITIES.with_directional(st.is_some()).attributes();
            let mut cs = w
                .create_element("CoSimulation")
                .with_attribute(("modelIdentifier", meta.name.as_str()));
            for (k, v) in &attrs {
                cs = cs.with_attribute((*k, v.as_str()));
            }
            cs.write_empty()?;
            unit_definitions(w, &used_units(table))?;
            w.create_element("LogCategories").write_inner_content(|w| {
                for c in Category::ALL {
                    w.create_element("Category")
                        .with_attribute(("name", c.name()))
                        .with_attribute(("description", c.description()))
                        .write_empty()?;
                }
                Ok(())
            })?;
            default_experiment(w, meta)?;
            w.create_element("ModelVariables")
                .write_inner_content(|w| {
                    for (i, v) in table.vars.iter().enumerate() {
                        w.write_event(Event::Comment(BytesText::from_escaped(format!(
                            " index {} of {n_vars} ",
                            i + 1
                        ))))?;
                        scalar_variable(w, v, derivative_of(st.as_ref(), i))?;
                    }
                    Ok(())
                })?;
            model_structure(w, table)?;
            Ok(())
        })?;
    let mut bytes = w.into_inner();
    bytes.push(b'\n');
    String::from_utf8(bytes).map_err(|e| io::Error::new(io::ErrorKind::InvalidData, e))
}

/// Units used by the table that [`write_model_description`] cannot give base units for (a table
/// bug; tested to be empty for every shipped model).
#[must_use]
pub fn unknown_units(table: &VariableTable) -> Vec<&'static str> {
    let mut v: Vec<_> = table
        .vars
        .iter()
        .filter_map(|v| v.unit)
        .filter(|u| base_unit(u).is_none())
        .collect();
    v.sort_unstable();
    v.dedup();
    v
}
