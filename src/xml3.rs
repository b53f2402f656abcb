//! The FMI 3.0 modelDescription.xml (FMI 3.0 §2.4), written with quick-xml from the FMI 3 view
//! of the variable table ([`Table3`]): the same variables as the FMI 2 file, vectors and
//! matrices as one array variable each, `time` the independent variable at value reference 0.
//! Deterministic like [`crate::xml`]: fixed element and attribute order, no generation date,
//! floats in the same shortest round-trip form; `<UnitDefinitions>` and `<DefaultExperiment>`
//! are the FMI 2 file's, written by the same functions.

use crate::fmu::Category;
use crate::variables::fmi3::{Table3, Var3, TIME_VR};
use crate::variables::linear::{differentiable, states};
use crate::variables::{Accessor, Causality, Initial, VarType, Variable, VariableTable};
use crate::xml::{
    common_attributes, default_experiment, real, unit_definitions, used_units, Meta,
    GENERATION_TOOL, W,
};
use quick_xml::events::{BytesDecl, BytesText, Event};
use quick_xml::Writer;
use std::io;

/// `fmiVersion`: exactly `3.0` (FMI Library 3.0.4 does not parse `3.0.x`).
pub const FMI_VERSION: &str = "3.0";

/// The `<CoSimulation>` attributes after `modelIdentifier`, in the FMI 3 spellings
/// (`fmi3InterfaceType.xsd`: `canGetAndSetFMUState`, `providesDirectionalDerivatives`, …).
/// Directional and adjoint derivatives where the model declares states
/// (`variables::linear::states`); early return at stop and contact events (when the importer
/// allows it); no event mode.
#[must_use]
pub fn co_simulation(derivatives: bool) -> [(&'static str, &'static str); 7] {
    let d = if derivatives { "true" } else { "false" };
    [
        ("canHandleVariableCommunicationStepSize", "true"),
        ("canGetAndSetFMUState", "true"),
        ("canSerializeFMUState", "true"),
        ("providesDirectionalDerivatives", d),
        ("providesAdjointDerivatives", d),
        ("mightReturnEarlyFromDoStep", "true"),
        ("hasEventMode", "false"),
    ]
}

/// The FMI 3 states: value references of each state variable (`joint.J.q`), its derivative
/// (`joint.J.qd`) and the rate's derivative (`joint.J.qdd`), one per joint.
struct States3 {
    q: Vec<u32>,
    qd: Vec<u32>,
    qdd: Vec<u32>,
    inputs: Vec<u32>,
}

fn states3(table: &VariableTable, t3: &Table3) -> Option<States3> {
    let st = states(table)?;
    let vr3 = |i: usize| -> Option<u32> {
        let vr = table.vars[i].vr;
        t3.vars
            .iter()
            .find(|v| v.members.contains(&vr))
            .map(|v| v.vr)
    };
    let uniq = |xs: &[usize]| -> Option<Vec<u32>> {
        let mut out: Vec<u32> = Vec::new();
        for &i in xs {
            let v = vr3(i)?;
            if !out.contains(&v) {
                out.push(v);
            }
        }
        Some(out)
    };
    let inputs: Vec<usize> = (0..table.vars.len())
        .filter(|&i| table.vars[i].causality == Causality::Input)
        .collect();
    Some(States3 {
        q: uniq(&st.q)?,
        qd: uniq(&st.qd)?,
        qdd: uniq(&st.qdd)?,
        inputs: uniq(&inputs)?,
    })
}

/// The `dependencies` of output `v` (FMI 3 value references), as in FMI 2 (`xml.rs`).
fn dependencies3(table: &VariableTable, st: Option<&States3>, v: &Var3) -> io::Result<String> {
    let Some(st) = st else {
        return Ok(String::new());
    };
    let f = first(table, v)?;
    if !differentiable(table, f.accessor) {
        return Ok(String::new());
    }
    let mut deps: Vec<u32> = st.q.iter().chain(&st.qd).copied().collect();
    if matches!(f.accessor, Accessor::JointQdd { .. }) {
        deps.extend(&st.inputs);
    }
    deps.sort_unstable();
    Ok(deps
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join(" "))
}

/// The unit of `time`.
const TIME_UNIT: &str = "s";

/// The table's variable of `v`'s first element: its type, causality, variability, initial and
/// unit are every element's ([`Table3::new`] groups only elements that agree).
fn first<'t>(table: &'t VariableTable, v: &Var3) -> io::Result<&'t Variable> {
    v.members
        .first()
        .and_then(|&vr| table.by_vr(vr))
        .ok_or_else(|| {
            io::Error::new(
                io::ErrorKind::InvalidData,
                format!("FMI 3 variable {} has no element in the table", v.name),
            )
        })
}

/// The `start` attribute: the elements' starts, row-major, separated by spaces; `None` when
/// an element has none.
fn start(table: &VariableTable, v: &Var3, ty: VarType) -> Option<String> {
    let starts: Option<Vec<String>> = v
        .members
        .iter()
        .map(|&vr| {
            let s = table.by_vr(vr)?.start?;
            Some(match ty {
                VarType::Real => real(s),
                VarType::Integer => format!("{}", s as i64),
            })
        })
        .collect();
    starts.map(|s| s.join(" "))
}

fn variable(w: &mut W, table: &VariableTable, v: &Var3, derivative: Option<u32>) -> io::Result<()> {
    let f = first(table, v)?;
    let tag = match f.ty {
        VarType::Real => "Float64",
        VarType::Integer => "Int32",
    };
    let mut e = common_attributes(w.create_element(tag), &v.name, v.vr, &v.description, f);
    if let Some(unit) = f.unit.filter(|_| f.ty == VarType::Real) {
        e = e.with_attribute(("unit", unit));
        if let Some(d) = f.display_unit {
            e = e.with_attribute(("displayUnit", d));
        }
    }
    let start = (f.initial != Initial::Calculated)
        .then(|| start(table, v, f.ty))
        .flatten();
    if let Some(s) = &start {
        e = e.with_attribute(("start", s.as_str()));
    }
    if let Some(d) = derivative {
        e = e.with_attribute(("derivative", d.to_string().as_str()));
    }
    if v.dims.is_empty() {
        e.write_empty()?;
    } else {
        e.write_inner_content(|w| {
            for d in &v.dims {
                w.create_element("Dimension")
                    .with_attribute(("start", d.to_string().as_str()))
                    .write_empty()?;
            }
            Ok(())
        })?;
    }
    Ok(())
}

fn model_structure(
    w: &mut W,
    table: &VariableTable,
    t3: &Table3,
    st: Option<&States3>,
) -> io::Result<()> {
    let mut outputs = Vec::new();
    let mut initial = Vec::new();
    for v in &t3.vars {
        let f = first(table, v)?;
        if f.causality == Causality::Output {
            outputs.push((v.vr, dependencies3(table, st, v)?));
            if f.initial == Initial::Calculated {
                initial.push(v.vr);
            }
        }
    }
    let derivatives: Vec<(u32, String)> = match st {
        Some(st) => {
            let mut d: Vec<(u32, String)> = st.qd.iter().map(|&vr| (vr, vr.to_string())).collect();
            for &vr in &st.qdd {
                let v = t3.by_vr(vr).ok_or_else(|| {
                    io::Error::new(io::ErrorKind::InvalidData, "no acceleration variable")
                })?;
                d.push((vr, dependencies3(table, Some(st), v)?));
            }
            d
        }
        None => Vec::new(),
    };
    w.create_element("ModelStructure")
        .write_inner_content(|w| {
            for (vr, deps) in &outputs {
                w.create_element("Output")
                    .with_attribute(("valueReference", vr.to_string().as_str()))
                    .with_attribute(("dependencies", deps.as_str()))
                    .write_empty()?;
            }
            for (vr, deps) in &derivatives {
                w.create_element("ContinuousStateDerivative")
                    .with_attribute(("valueReference", vr.to_string().as_str()))
                    .with_attribute(("dependencies", deps.as_str()))
                    .write_empty()?;
            }
            for vr in &initial {
                // dependencies omitted: may depend on every parameter (as in FMI 2)
                w.create_element("InitialUnknown")
                    .with_attribute(("valueReference", vr.to_string().as_str()))
                    .write_empty()?;
            }
            Ok(())
        })?;
    Ok(())
}

/// Writes the FMI 3.0 modelDescription.xml of `table` (through its FMI 3 view, [`Table3`]).
/// `meta.guid` is the `instantiationToken`: the FMI 2 file's GUID, so both files of a model
/// name the same model.
///
/// # Errors
/// Only I/O errors of the in-memory writer (none in practice).
pub fn write_model_description3(table: &VariableTable, meta: &Meta) -> io::Result<String> {
    let t3 = Table3::new(table);
    let st = states3(table, &t3);
    let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
    w.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None)))?;
    w.write_event(Event::Comment(BytesText::from_escaped(
        " Generated by triad from the model spec (FMI 3.0); do not edit ",
    )))?;
    w.create_element("fmiModelDescription")
        .with_attribute(("fmiVersion", FMI_VERSION))
        .with_attribute(("modelName", meta.name.as_str()))
        .with_attribute(("instantiationToken", meta.guid.as_str()))
        .with_attribute(("description", meta.description.as_str()))
        .with_attribute(("generationTool", GENERATION_TOOL))
        .with_attribute(("variableNamingConvention", "structured"))
        .write_inner_content(|w| {
            let mut cs = w
                .create_element("CoSimulation")
                .with_attribute(("modelIdentifier", meta.name.as_str()));
            for (k, v) in co_simulation(st.is_some()) {
                cs = cs.with_attribute((k, v));
            }
            cs.write_empty()?;
            let mut units = used_units(table);
            units.insert(TIME_UNIT);
            unit_definitions(w, &units)?;
            w.create_element("LogCategories").write_inner_content(|w| {
                for c in Category::ALL {
                    w.create_element("Category")
                        .with_attribute(("name", c.name()))
                        .with_attribute((
                            "description",
                            c.description().replace("fmi2", "fmi3").as_str(),
                        ))
                        .write_empty()?;
                }
                Ok(())
            })?;
            default_experiment(w, meta)?;
            w.create_element("ModelVariables")
                .write_inner_content(|w| {
                    w.create_element("Float64")
                        .with_attribute(("name", "time"))
                        .with_attribute(("valueReference", TIME_VR.to_string().as_str()))
                        .with_attribute(("description", "simulation time"))
                        .with_attribute(("causality", "independent"))
                        .with_attribute(("variability", "continuous"))
                        .with_attribute(("unit", TIME_UNIT))
                        .write_empty()?;
                    for v in &t3.vars {
                        let derivative = st.as_ref().and_then(|st| {
                            let of = |from: &[u32], to: &[u32]| {
                                from.iter().position(|&x| x == v.vr).map(|k| to[k])
                            };
                            of(&st.qd, &st.q).or_else(|| of(&st.qdd, &st.qd))
                        });
                        variable(w, table, v, derivative)?;
                    }
                    Ok(())
                })?;
            model_structure(w, table, &t3, st.as_ref())?;
            Ok(())
        })?;
    let mut bytes = w.into_inner();
    bytes.push(b'\n');
    String::from_utf8(bytes).map_err(|e| io::Error::new(io::ErrorKind::InvalidData, e))
}
