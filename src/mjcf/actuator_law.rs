//! MuJoCo's actuator parameters as its parser sets them, and the joint-actuator law they are.
//!
//! Every actuator element (`<general>` and the shortcuts `<motor>`, `<position>`,
//! `<velocity>`) compiles to one set of parameters (`gaintype`, `biastype`, `dyntype`,
//! `gainprm`, `biasprm`). Defaults come from the actuator defaults of the element's class and
//! the classes above it (nearest first), as MuJoCo 3–4 compiles them (checked against MuJoCo by
//! `tests/python/test_mjcf_actuators.py`): a servo's own gains from the defaults of its own
//! kind, else from `<general>` defaults, else MuJoCo's (kp = kv = 1); `<general>` takes every
//! default in order, root class first (a `<position kp="7">` default makes a bare `<general>`
//! that servo):
//!
//! ```text
//! motor      gainprm[0] = 1;                                     fixed, bias none, dyn none
//! position   gainprm[0] = kp;  biasprm = (0, −kp, −kv);  dyn filterexact if timeconst > 0
//!            (kp: own, position defaults, general's gainprm[0], 1;
//!             kv: own, position defaults, general's −biasprm[2], 0)          fixed, affine
//! velocity   gainprm[0] = kv;  biasprm = (0, 0, −kv)
//!            (kv: own, velocity defaults, general's gainprm[0], 1)           fixed, affine
//! general    the attributes given, over the defaults
//! ```
//!
//! The force is `F = gainprm[0] ctrl + biasprm[0] + biasprm[1] L + biasprm[2] L̇` (fixed gain,
//! affine bias; no bias: `gainprm[0] ctrl`). triad reproduces exactly three forms: the motor
//! (gain 1, no bias), the position servo (bias `0, −kp, −kv` with gain `kp`) and the velocity
//! servo (bias `0, 0, −kv` with gain `kv`); anything else (actuator dynamics, `dampratio`, other
//! gain or bias types or values) is refused.

use super::defaults::Attrs;
use super::xml::Node;
use crate::mechanics::ActuatorLaw;
use crate::spec::Problem;

/// The actuator element kinds whose defaults an actuator takes.
pub(super) const ACTUATOR_KINDS: [&str; 4] = ["general", "motor", "position", "velocity"];

/// MuJoCo's parameters of a `<general>` actuator (the ones the law depends on).
#[derive(Clone, Debug)]
struct Params {
    dyntype: String,
    gaintype: String,
    biastype: String,
    gain: [f64; 3],
    bias: [f64; 3],
}

impl Default for Params {
    fn default() -> Self {
        Self {
            dyntype: "none".into(),
            gaintype: "fixed".into(),
            biastype: "none".into(),
            gain: [1.0, 0.0, 0.0],
            bias: [0.0; 3],
        }
    }
}

/// Applies element `e` (a `<general>` actuator or any actuator default) to `p`, as MuJoCo's
/// parser does (module table).
fn apply(p: &mut Params, e: &Node) -> Result<(), Problem> {
    let own = Attrs::own(e);
    let number =
        |key: &str| -> Result<Option<f64>, Problem> { Ok(own.numbers(key, 1, 1)?.map(|v| v[0])) };
    match e.name.as_str() {
        "motor" => {
            *p = Params {
                bias: p.bias,
                ..Params::default()
            };
        }
        "position" => {
            let kp = number("kp")?.unwrap_or(p.gain[0]);
            p.gain[0] = kp;
            p.bias[1] = -kp;
            if let Some(kv) = number("kv")? {
                p.bias[2] = -kv;
            }
            if let Some(t) = number("timeconst")? {
                p.dyntype = if t == 0.0 { "none" } else { "filterexact" }.into();
            }
            p.gaintype = "fixed".into();
            p.biastype = "affine".into();
        }
        "velocity" => {
            let kv = number("kv")?.unwrap_or(p.gain[0]);
            *p = Params {
                gain: [kv, p.gain[1], p.gain[2]],
                bias: [0.0, 0.0, -kv],
                biastype: "affine".into(),
                ..Params::default()
            };
        }
        _ => {
            for (key, field) in [
                ("dyntype", &mut p.dyntype),
                ("gaintype", &mut p.gaintype),
                ("biastype", &mut p.biastype),
            ] {
                if let Some(v) = own.text(key) {
                    *field = v.to_string();
                }
            }
            if let Some(v) = own.numbers("gainprm", 1, 10)? {
                p.gain.iter_mut().zip(&v).for_each(|(g, x)| *g = *x);
            }
            if let Some(v) = own.numbers("biasprm", 1, 10)? {
                p.bias.iter_mut().zip(&v).for_each(|(b, x)| *b = *x);
            }
        }
    }
    Ok(())
}

/// The actuator element `e` and its class's actuator defaults, nearest first, by kind.
pub(super) struct Element<'a> {
    /// The element.
    pub node: &'a Node,
    /// Its class's defaults of every actuator kind, nearest first (`Classes::defaults_of`).
    pub all: Vec<&'a Node>,
    /// Those of its own kind.
    pub same: Vec<&'a Node>,
    /// The `<general>` ones.
    pub general: Vec<&'a Node>,
}

/// The law of actuator `a`, or a problem at the element saying why triad cannot reproduce it.
pub(super) fn law(a: &Element) -> Result<ActuatorLaw, Problem> {
    let e = a.node;
    let refuse = |why: String| Err(e.problem(why));
    // the <general> defaults in order, for what a servo takes from them
    let mut general = Params::default();
    for d in a.general.iter().rev() {
        apply(&mut general, d)?;
    }
    let own = Attrs::with_chain(e, a.same.clone());
    let dynamics = |p: &Params| -> Result<(), Problem> {
        if p.dyntype == "none" {
            Ok(())
        } else {
            Err(e.problem(format!(
                "actuator dynamics (dyntype=\"{}\", or a position servo's timeconst > 0) are not supported: triad's actuators act at once",
                p.dyntype
            )))
        }
    };
    match e.name.as_str() {
        "motor" => return Ok(ActuatorLaw::Motor),
        "velocity" => {
            let kv = own.number("kv", general.gain[0])?;
            return Ok(ActuatorLaw::Velocity { kv });
        }
        "position" => {
            if own.get("dampratio").is_some() && own.get("kv").is_none() {
                return refuse(
                    "dampratio is not supported: give the damping gain kv instead".into(),
                );
            }
            if own.number("inheritrange", 0.0)? > 0.0 {
                return refuse(
                    "inheritrange is not supported: give ctrlrange (the joint's range) instead"
                        .into(),
                );
            }
            match own.get("timeconst") {
                Some(_) if own.number("timeconst", 0.0)? != 0.0 => {
                    dynamics(&Params {
                        dyntype: "filterexact".into(),
                        ..Params::default()
                    })?;
                }
                Some(_) => {}
                None => dynamics(&general)?,
            }
            let kp = own.number("kp", general.gain[0])?;
            let kv = own.number("kv", -general.bias[2])?;
            if kv < 0.0 {
                return refuse(
                    "dampratio (a positive biasprm[2]) is not supported: give kv".into(),
                );
            }
            return Ok(ActuatorLaw::Position { kp, kv });
        }
        _ => {}
    }
    // <general>: every default in order, root class first, then the element
    let mut p = Params::default();
    for d in a.all.iter().rev() {
        apply(&mut p, d)?;
    }
    apply(&mut p, e)?;
    dynamics(&p)?;
    if p.gaintype != "fixed" {
        return refuse(format!(
            "gaintype=\"{}\" is not supported (fixed is)",
            p.gaintype
        ));
    }
    let [g, _, _] = p.gain;
    let [b0, b1, b2] = p.bias;
    #[allow(clippy::float_cmp)]
    let law = match p.biastype.as_str() {
        "none" if g == 1.0 => Some(ActuatorLaw::Motor),
        "affine" if b0 == 0.0 && b1 == -g && b2 <= 0.0 => {
            Some(ActuatorLaw::Position { kp: g, kv: -b2 })
        }
        "affine" if b0 == 0.0 && b1 == 0.0 && b2 == -g => Some(ActuatorLaw::Velocity { kv: g }),
        _ => None,
    };
    law.map_or_else(
        || refuse(format!(
            "gaintype fixed, gainprm {g}, biastype {} with biasprm {b0} {b1} {b2} is none of the laws triad reproduces: a motor (gain 1, no bias), a position servo (gain kp, bias 0 −kp −kv) or a velocity servo (gain kv, bias 0 0 −kv)",
            p.biastype
        )),
        Ok,
    )
}
