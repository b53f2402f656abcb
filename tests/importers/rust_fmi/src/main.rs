//! `fmi3_run FMU STOP STEP OUT.csv [NAME=VALUE ...]`: runs an FMI 3.0 Co-Simulation FMU with the
//! `fmi` crate of crates.io (rust-fmi), an importer independent of triad and of fmpy.
//!
//! The FMU's modelDescription.xml is parsed (and so checked) by the crate's schema (`fmi-schema`);
//! the FMU is instantiated for Co-Simulation, the named Float64 inputs are set to their constant
//! values in Initialization Mode and before every step, and `fmi3DoStep` advances from the
//! DefaultExperiment's start time (0 without one) to STOP on fmpy's grid
//! (`start + (n + 1) * STEP`, the last step shortened to end on STOP).
//!
//! OUT.csv holds `time` and every element of every output, named as in FMI 2 (`body.R[1,2]`:
//! arrays row-major, 1-based indices; a name with a comma in double quotes), each value printed with `{:?}` (the shortest string that
//! reads back to the same f64), so that results compare bit for bit.
//!
//! Standard output reports what was read from the model description, one fact a line:
//! `fmiVersion V`, `instantiationToken T`, `modelIdentifier M`, and `variable NAME CAUSALITY TYPE
//! DIMS` (DIMS: `-` for a scalar, else the sizes joined by `x`).

use std::{
    fs::File,
    io::{BufWriter, Write},
    process::ExitCode,
};

use fmi::{
    fmi3::{
        CoSimulation, Common, Fmi3Model, GetSet, binding::fmi3ValueReference, import::Fmi3Import,
        schema,
    },
    schema::fmi3::{ArrayableVariableTrait, Causality, Dimension, Variable},
    traits::FmiImport,
};

type Res<T> = Result<T, String>;

/// An output or input: value reference, FMI 2 names of its elements (row-major).
struct Signal {
    vr: fmi3ValueReference,
    elements: Vec<String>,
}

/// `math.isclose(a, b)` with Python's defaults (fmpy's test for "the same time").
fn isclose(a: f64, b: f64) -> bool {
    (a - b).abs() <= (1e-9 * a.abs().max(b.abs())).max(0.0)
}

/// The elements' names of an array of these sizes, as FMI 2 names its scalars.
fn element_names(name: &str, dims: &[u64]) -> Vec<String> {
    if dims.is_empty() {
        return vec![name.to_owned()];
    }
    let total: u64 = dims.iter().product();
    (0..total)
        .map(|mut flat| {
            let mut idx = vec![0u64; dims.len()];
            for k in (0..dims.len()).rev() {
                idx[k] = flat % dims[k] + 1;
                flat /= dims[k];
            }
            let idx: Vec<String> = idx.iter().map(u64::to_string).collect();
            format!("{name}[{}]", idx.join(","))
        })
        .collect()
}

fn type_name(v: &Variable) -> &'static str {
    match v {
        Variable::Int8(_) => "Int8",
        Variable::UInt8(_) => "UInt8",
        Variable::Int16(_) => "Int16",
        Variable::UInt16(_) => "UInt16",
        Variable::Int32(_) => "Int32",
        Variable::UInt32(_) => "UInt32",
        Variable::Int64(_) => "Int64",
        Variable::UInt64(_) => "UInt64",
        Variable::Float32(_) => "Float32",
        Variable::Float64(_) => "Float64",
        Variable::Boolean(_) => "Boolean",
        Variable::String(_) => "String",
        Variable::Binary(_) => "Binary",
        Variable::Clock(_) => "Clock",
    }
}

/// The fixed sizes of a Float64 variable's dimensions (an error for a size given by a structural
/// parameter: triad writes none).
fn fixed_dims(name: &str, dims: &[Dimension]) -> Res<Vec<u64>> {
    dims.iter()
        .map(|d| {
            d.as_fixed().ok_or_else(|| {
                format!("{name}: a Dimension given by a valueReference, not a start")
            })
        })
        .collect()
}

/// Attributes that FMI 3.0 gives Float32 and Float64 variables (fmi3Variable.xsd:
/// fmi3RealBaseAttributes, fmi3RealVariableAttributes) but fmi-schema 0.8.0's `FmiFloat64` lacks,
/// while it rejects unknown attributes: a gap of the importer, not a fault of the FMU.
const SCHEMA_GAPS: &[&str] = &[
    "quantity",
    "unit",
    "displayUnit",
    "relativeQuantity",
    "unbounded",
    "nominal",
];

/// `attr="..."` removed from every `<Float32 ...>` and `<Float64 ...>` start tag.
fn strip_float_attribute(xml: &str, attr: &str) -> String {
    let needle = format!(" {attr}=\"");
    let mut out = String::with_capacity(xml.len());
    let mut rest = xml;
    while let Some(at) = rest.find('<') {
        out.push_str(&rest[..at]);
        rest = &rest[at..];
        let end = rest.find('>').map_or(rest.len(), |e| e + 1);
        let mut tag = rest[..end].to_owned();
        if tag.starts_with("<Float64 ") || tag.starts_with("<Float32 ") {
            while let Some(a) = tag.find(&needle) {
                let value_end = tag[a + needle.len()..]
                    .find('"')
                    .map_or(tag.len(), |q| a + needle.len() + q + 1);
                tag.replace_range(a..value_end, "");
            }
        }
        out.push_str(&tag);
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

/// The FMU unpacked into a temporary folder, and its model description parsed by fmi-schema
/// (the crate's own check of triad's XML). The parse is strict (unknown attributes and elements
/// are errors); where it fails on a standard attribute of SCHEMA_GAPS, that attribute is reported
/// (`schema-gap ATTRIBUTE ELEMENT`), removed from the Float variables, and the parse repeated;
/// any other failure is an error. `schema ok` when the description parses as it is.
fn open(fmu: &str) -> Res<Fmi3Import> {
    use fmi::schema::traits::FmiModelDescription;
    let file = File::open(fmu).map_err(|e| format!("{fmu}: {e}"))?;
    let mut archive = zip::ZipArchive::new(file).map_err(|e| format!("{fmu}: {e}"))?;
    let dir = tempfile::Builder::new()
        .prefix("fmi3_run")
        .tempdir()
        .map_err(|e| format!("temporary folder: {e}"))?;
    archive
        .extract(dir.path())
        .map_err(|e| format!("{fmu}: unpacking: {e}"))?;
    let mut xml = std::fs::read_to_string(dir.path().join("modelDescription.xml"))
        .map_err(|e| format!("{fmu}: modelDescription.xml: {e}"))?;
    let mut clean = true;
    loop {
        match schema::Fmi3ModelDescription::deserialize(&xml) {
            Ok(_) => break,
            Err(e) => {
                let msg = e.to_string();
                // hard-xml: `unknown field "unit" in element "FmiFloat64"`
                let quoted: Vec<&str> = msg.split('"').skip(1).step_by(2).collect();
                let gap = match quoted.as_slice() {
                    [attr, elem]
                        if msg.contains("unknown field")
                            && SCHEMA_GAPS.contains(attr)
                            && (*elem == "FmiFloat64" || *elem == "FmiFloat32") =>
                    {
                        attr.to_string()
                    }
                    _ => {
                        return Err(format!(
                            "{fmu}: fmi-schema rejects modelDescription.xml: {msg}"
                        ));
                    }
                };
                println!("schema-gap {gap} {}", quoted[1]);
                clean = false;
                let stripped = strip_float_attribute(&xml, &gap);
                if stripped == xml {
                    return Err(format!("{fmu}: {msg}, and no {gap}= to remove"));
                }
                xml = stripped;
            }
        }
    }
    if clean {
        println!("schema ok");
    }
    Fmi3Import::new(dir, &xml).map_err(|e| format!("{fmu}: import failed: {e}"))
}

fn run(args: &[String]) -> Res<()> {
    let [fmu, stop, step, out, inputs @ ..] = args else {
        return Err("usage: fmi3_run FMU STOP STEP OUT.csv [NAME=VALUE ...]".into());
    };
    let stop: f64 = stop.parse().map_err(|e| format!("STOP {stop:?}: {e}"))?;
    let step: f64 = step.parse().map_err(|e| format!("STEP {step:?}: {e}"))?;
    if !(step > 0.0) {
        return Err(format!("STEP must be > 0, not {step}"));
    }

    let import = open(fmu)?;
    let md: &schema::Fmi3ModelDescription = import.model_description();
    let cs = md
        .co_simulation
        .as_ref()
        .ok_or("the model description has no <CoSimulation>")?;
    println!("fmiVersion {}", md.fmi_version);
    println!("instantiationToken {}", md.instantiation_token);
    println!("modelIdentifier {}", cs.model_identifier);

    let mut outputs = Vec::new();
    let mut settable = Vec::new();
    for (v, a) in md
        .model_variables
        .variables
        .iter()
        .zip(md.model_variables.iter_abstract())
    {
        let Variable::Float64(f) = v else {
            if a.causality() == Causality::Output || a.causality() == Causality::Input {
                return Err(format!(
                    "{}: a {} {}: fmi3_run reads and sets Float64 variables only",
                    a.name(),
                    type_name(v),
                    a.causality()
                ));
            }
            println!("variable {} {} {} ?", a.name(), a.causality(), type_name(v));
            continue;
        };
        let dims = fixed_dims(a.name(), f.dimensions())?;
        let shown = if dims.is_empty() {
            "-".to_owned()
        } else {
            dims.iter()
                .map(u64::to_string)
                .collect::<Vec<_>>()
                .join("x")
        };
        println!(
            "variable {} {} {} {shown}",
            a.name(),
            a.causality(),
            type_name(v)
        );
        let signal = Signal {
            vr: a.value_reference(),
            elements: element_names(a.name(), &dims),
        };
        match a.causality() {
            Causality::Output => outputs.push(signal),
            Causality::Input => settable.push((a.name().to_owned(), signal)),
            _ => {}
        }
    }

    // NAME=VALUE: scalar Float64 inputs, held constant
    let mut held: Vec<(fmi3ValueReference, f64)> = Vec::new();
    for arg in inputs {
        let (name, value) = arg
            .split_once('=')
            .ok_or_else(|| format!("{arg:?} is not NAME=VALUE"))?;
        let value: f64 = value.parse().map_err(|e| format!("{arg:?}: {e}"))?;
        let (_, s) = settable
            .iter()
            .find(|(n, _)| n == name)
            .ok_or_else(|| format!("{name:?} is not a Float64 input of the FMU"))?;
        if s.elements.len() != 1 {
            return Err(format!(
                "{name:?} is an array: only scalar inputs can be set"
            ));
        }
        held.push((s.vr, value));
    }
    let (in_vrs, in_values): (Vec<_>, Vec<_>) = held.into_iter().unzip();

    let start = md
        .default_experiment
        .as_ref()
        .and_then(|e| e.start_time)
        .unwrap_or(0.0);

    let mut inst = import
        .instantiate_cs("fmi3_run", false, false, false, false, &[])
        .map_err(|e| format!("fmi3InstantiateCoSimulation: {e}"))?;
    let fail = |what: &str, e: fmi::fmi3::Fmi3Error| format!("{what} returned {e}");
    inst.enter_initialization_mode(None, start, Some(stop))
        .map_err(|e| fail("fmi3EnterInitializationMode", e))?;
    if !in_vrs.is_empty() {
        inst.set_float64(&in_vrs, &in_values)
            .map_err(|e| fail("fmi3SetFloat64", e))?;
    }
    inst.exit_initialization_mode()
        .map_err(|e| fail("fmi3ExitInitializationMode", e))?;

    let file = File::create(out).map_err(|e| format!("{out}: {e}"))?;
    let mut csv = BufWriter::new(file);
    let mut header = vec!["time".to_owned()];
    for s in &outputs {
        header.extend(s.elements.iter().cloned());
    }
    let io = |e: std::io::Error| format!("{out}: {e}");
    // names with a comma (`R[1,2]`) quoted, as in RFC 4180
    let quoted: Vec<String> = header
        .iter()
        .map(|h| {
            if h.contains([',', '"']) {
                format!("\"{}\"", h.replace('"', "\"\""))
            } else {
                h.clone()
            }
        })
        .collect();
    writeln!(csv, "{}", quoted.join(",")).map_err(io)?;

    let mut buf: Vec<f64> = Vec::new();
    let mut sample = |inst: &mut <Fmi3Import as Fmi3Model>::InstanceCS,
                      time: f64,
                      csv: &mut BufWriter<File>|
     -> Res<()> {
        let mut row = vec![format!("{time:?}")];
        for s in &outputs {
            buf.resize(s.elements.len(), f64::NAN);
            inst.get_float64(&[s.vr], &mut buf)
                .map_err(|e| fail("fmi3GetFloat64", e))?;
            row.extend(buf.iter().map(|x| format!("{x:?}")));
        }
        writeln!(csv, "{}", row.join(",")).map_err(io)
    };

    // fmpy's Co-Simulation loop (simulation.py, simulateCS), so that both run the same steps
    let mut time = start;
    sample(&mut inst, time, &mut csv)?;
    let mut n: u64 = 0;
    while !(time > stop || isclose(time, stop)) {
        let mut next = start + (n + 1) as f64 * step;
        if next > stop && !isclose(next, stop) {
            next = stop;
        }
        if !in_vrs.is_empty() {
            inst.set_float64(&in_vrs, &in_values)
                .map_err(|e| fail("fmi3SetFloat64", e))?;
        }
        let (mut event, mut terminate, mut early, mut last) = (false, false, false, 0.0);
        inst.do_step(
            time,
            next - time,
            true,
            &mut event,
            &mut terminate,
            &mut early,
            &mut last,
        )
        .map_err(|e| format!("fmi3DoStep at t = {time:?} returned {e}"))?;
        if terminate {
            return Err(format!("the FMU asked to terminate at t = {time:?}"));
        }
        time = next;
        n += 1;
        sample(&mut inst, time, &mut csv)?;
    }
    csv.flush().map_err(io)?;
    inst.terminate().map_err(|e| fail("fmi3Terminate", e))?;
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("fmi3_run: {e}");
            ExitCode::FAILURE
        }
    }
}
