//! The seam to the spec and variable-table work: everything the FMU layer needs from
//! `crate::spec` and `crate::variables`, imported in one place.
//!
//! TEMPORARY: until the spec branch is merged this module holds minimal stand-ins with exactly
//! the contracted names (a one-pendulum model and a small table). After the merge it shrinks to
//! `pub use` lines and nothing else in `fmu`, `ffi`, `xml` or `package` changes.

use crate::math::{Mat3, Vec3};
use crate::mechanics::{
    BodyDef, Frame, JointDef, JointInitial, JointType, ModelDef, SolverSettings, State,
};
use crate::variables::{
    Accessor, Causality, Initial, VarType, Variability, Variable, VariableTable,
};
use std::path::Path;

/// Stand-in for `crate::spec::Format`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// JSON text.
    Json,
    /// TOML text.
    Toml,
}

/// Stand-in for `crate::spec::SpecErrors`.
#[derive(Debug, Clone)]
pub struct SpecErrors(pub String);

impl std::fmt::Display for SpecErrors {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for SpecErrors {}

/// Stand-in for `crate::spec::Experiment`.
#[derive(Clone, Debug, PartialEq)]
pub struct Experiment {
    /// Start time, s.
    pub start: f64,
    /// Stop time, s.
    pub stop: f64,
    /// Communication step hint, s.
    pub step: f64,
}

/// Stand-in for `crate::spec::Spec`: reads `name`, `description` and `experiment` only and
/// lowers to one actuated pendulum.
#[derive(Clone, Debug)]
pub struct Spec {
    /// modelIdentifier.
    pub name: String,
    /// Description.
    pub description: String,
    /// Default experiment.
    pub experiment: Experiment,
}

impl Spec {
    /// Reads a spec file.
    ///
    /// # Errors
    /// I/O or parse problems.
    pub fn from_path(path: &Path) -> Result<Spec, SpecErrors> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| SpecErrors(format!("{}: {e}", path.display())))?;
        let format = if path.extension().is_some_and(|e| e == "toml") {
            Format::Toml
        } else {
            Format::Json
        };
        Self::from_str(&text, format, &path.display().to_string())
    }

    /// Parses spec text.
    ///
    /// # Errors
    /// Parse problems.
    pub fn from_str(text: &str, format: Format, origin: &str) -> Result<Spec, SpecErrors> {
        let value: serde_json::Value = match format {
            Format::Json => {
                serde_json::from_str(text).map_err(|e| SpecErrors(format!("{origin}: {e}")))?
            }
            Format::Toml => {
                let v: toml::Value =
                    toml::from_str(text).map_err(|e| SpecErrors(format!("{origin}: {e}")))?;
                serde_json::to_value(v).map_err(|e| SpecErrors(format!("{origin}: {e}")))?
            }
        };
        let name = value["name"]
            .as_str()
            .ok_or_else(|| SpecErrors(format!("{origin}: name missing")))?;
        let num = |k: &str, d: f64| value["experiment"][k].as_f64().unwrap_or(d);
        Ok(Spec {
            name: name.to_string(),
            description: value["description"].as_str().unwrap_or("").to_string(),
            experiment: Experiment {
                start: num("start", 0.0),
                stop: num("stop", 1.0),
                step: num("step", 1e-2),
            },
        })
    }

    /// Canonical JSON text.
    #[must_use]
    pub fn canonical_json(&self) -> String {
        serde_json::json!({
            "name": self.name,
            "description": self.description,
            "experiment": {"start": self.experiment.start, "stop": self.experiment.stop, "step": self.experiment.step},
        })
        .to_string()
    }

    /// Lowers to a one-pendulum model.
    ///
    /// # Errors
    /// Never in the stand-in.
    pub fn lower(&self) -> Result<(ModelDef, SolverSettings), SpecErrors> {
        let body = BodyDef {
            name: "link1".into(),
            mass: 1.0,
            com: Vec3::new(0.0, 0.0, -0.5),
            inertia: Mat3::from_diagonal(&Vec3::new(0.0834, 0.0834, 1e-4)),
        };
        let joint = JointDef {
            name: "shoulder".into(),
            kind: JointType::Revolute,
            parent: None,
            child: 0,
            parent_frame: Frame::identity(),
            child_frame: Frame::identity(),
            axis: Vec3::new(0.0, 1.0, 0.0),
            axis2: Vec3::new(1.0, 0.0, 0.0),
            actuated: true,
            damping: 0.0,
            stiffness: 0.0,
            loop_closing: false,
            initial: JointInitial::Coords {
                q: vec![1.0],
                qd: vec![0.0],
            },
        };
        let def = ModelDef {
            gravity: Vec3::new(0.0, 0.0, -9.81),
            bodies: vec![body],
            joints: vec![joint],
            loads: vec![],
            free_bodies: vec![],
        };
        Ok((def, SolverSettings::default()))
    }
}

/// Stand-in for `crate::spec::bundled`: no shipped models yet.
#[must_use]
pub fn bundled() -> &'static [(&'static str, &'static str)] {
    &[]
}

/// Stand-in for `VariableTable::new`: a small table over the first joint.
#[must_use]
pub fn table(def: &ModelDef, settings: &SolverSettings) -> VariableTable {
    let _ = settings;
    let mut vars = Vec::new();
    let mut push = |name: &str, ty, causality, variability, initial, start, unit, accessor| {
        vars.push(Variable {
            vr: vars.len() as u32,
            name: name.to_string(),
            ty,
            causality,
            variability,
            initial,
            start,
            unit,
            display_unit: if unit == Some("rad") {
                Some("deg")
            } else {
                None
            },
            description: format!("stand-in {name}"),
            accessor,
        });
    };
    use Causality as C;
    use Variability as V;
    if let Some(j) = def.joints.first() {
        push(
            &format!("joint.{}.tau", j.name),
            VarType::Real,
            C::Input,
            V::Continuous,
            Initial::None,
            Some(0.0),
            Some("N.m"),
            Accessor::Input(0),
        );
        push(
            &format!("joint.{}.q", j.name),
            VarType::Real,
            C::Output,
            V::Continuous,
            Initial::Calculated,
            None,
            Some("rad"),
            Accessor::JointQ { joint: 0, k: 0 },
        );
        push(
            &format!("joint.{}.damping", j.name),
            VarType::Real,
            C::Parameter,
            V::Tunable,
            Initial::Exact,
            Some(j.damping),
            Some("N.m.s"),
            Accessor::Damping(0),
        );
    }
    push(
        "system.energy",
        VarType::Real,
        C::Output,
        V::Continuous,
        Initial::Calculated,
        None,
        Some("J"),
        Accessor::Energy,
    );
    push(
        "system.work",
        VarType::Real,
        C::Output,
        V::Continuous,
        Initial::Calculated,
        None,
        Some("J"),
        Accessor::Work,
    );
    push(
        "solver.max_step",
        VarType::Real,
        C::Parameter,
        V::Fixed,
        Initial::Exact,
        Some(settings.max_step),
        Some("s"),
        Accessor::MaxStep,
    );
    push(
        "solver.order",
        VarType::Integer,
        C::Parameter,
        V::Fixed,
        Initial::Exact,
        Some(f64::from(settings.order)),
        None,
        Accessor::Order,
    );
    VariableTable { vars }
}

/// Stand-in for `variables::read_state`.
#[must_use]
pub fn read_state(acc: Accessor, state: &State) -> Option<f64> {
    let out = state.outputs();
    match acc {
        Accessor::Input(i) => state.inputs().get(i).copied(),
        Accessor::JointQ { joint, k } => Some(
            out.joints
                .get(joint)
                .and_then(|j| j.q.get(k).copied())
                .unwrap_or(0.0),
        ),
        Accessor::Energy => Some(out.energy),
        Accessor::Work => Some(out.work),
        _ => None,
    }
}

/// Stand-in for `variables::read_param`.
#[must_use]
pub fn read_param(acc: Accessor, def: &ModelDef, settings: &SolverSettings) -> Option<f64> {
    match acc {
        Accessor::Damping(j) => def.joints.get(j).map(|j| j.damping),
        Accessor::MaxStep => Some(settings.max_step),
        Accessor::Order => Some(f64::from(settings.order)),
        _ => None,
    }
}

/// Stand-in for `variables::write_param`.
///
/// # Errors
/// Invalid values.
pub fn write_param(
    acc: Accessor,
    def: &mut ModelDef,
    settings: &mut SolverSettings,
    value: f64,
) -> Result<(), String> {
    match acc {
        Accessor::Damping(j) if value >= 0.0 => {
            def.joints.get_mut(j).ok_or("no such joint")?.damping = value;
            Ok(())
        }
        Accessor::MaxStep if value > 0.0 => {
            settings.max_step = value;
            Ok(())
        }
        Accessor::Order if value == 2.0 || value == 4.0 => {
            settings.order = value as u8;
            Ok(())
        }
        _ => Err(format!("value {value} not allowed")),
    }
}
