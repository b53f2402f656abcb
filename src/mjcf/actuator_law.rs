//! MuJoCo's actuator parameters as its parser sets them, and the joint-actuator law they are.
//!
//! Every actuator element (`<general>` and the shortcuts `<motor>`, `<position>`,
//! `<velocity>`) writes one set of parameters (`gaintype`, `biastype`, `dyntype`, `gainprm`,
//! `biasprm`), starting from MuJoCo's defaults (fixed gain 1, no bias, no dynamics); the
//! actuator defaults of its class and the classes above it are applied first, root class
//! first, as MuJoCo keeps one actuator default per class:
//!
//! ```text
//! motor      gainprm[0] = 1;                                      fixed, bias none, dyn none
//! position   gainprm[0] = kp (else as is); biasprm[1] = −kp;
//!            biasprm[2] = −kv if kv given; dyn filterexact if timeconst > 0;  fixed, affine
//! velocity   biasprm = 0; gainprm[0] = kv (else as is); biasprm[2] = −kv;     fixed, affine
//! general    the attributes given
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

/// MuJoCo's parameters of one actuator (the ones the law depends on).
#[derive(Clone, Debug)]
struct Params {
    dyntype: String,
    gaintype: String,
    biastype: String,
    gain: [f64; 3],
    bias: [f64; 3],
    /// `dampratio` was given (a positive `biasprm[2]`).
    dampratio: bool,
}

impl Default for Params {
    fn default() -> Self {
        Self {
            dyntype: "none".into(),
            gaintype: "fixed".into(),
            biastype: "none".into(),
            gain: [1.0, 0.0, 0.0],
            bias: [0.0; 3],
            dampratio: false,
        }
    }
}

/// One number of `e`'s attribute `key`, if given.
fn number(e: &Node, key: &str) -> Result<Option<f64>, Problem> {
    Ok(Attrs::own(e).numbers(key, 1, 1)?.map(|v| v[0]))
}

/// Applies element `e` (the actuator or one of its class's defaults) to `p`, as MuJoCo's
/// parser does (module table).
fn apply(p: &mut Params, e: &Node) -> Result<(), Problem> {
    let own = Attrs::own(e);
    match e.name.as_str() {
        "motor" => {
            p.gain[0] = 1.0;
            p.dyntype = "none".into();
            p.gaintype = "fixed".into();
            p.biastype = "none".into();
        }
        "position" => {
            if number(e, "dampratio")?.is_some() {
                p.dampratio = true;
            }
            let kp = number(e, "kp")?.unwrap_or(p.gain[0]);
            p.gain[0] = kp;
            p.bias[1] = -kp;
            if let Some(kv) = number(e, "kv")? {
                p.bias[2] = -kv;
                p.dampratio = false;
            }
            if let Some(t) = number(e, "timeconst")? {
                p.dyntype = if t == 0.0 { "none" } else { "filterexact" }.into();
            }
            if number(e, "inheritrange")?.is_some_and(|r| r > 0.0) {
                return Err(e.problem(
                    "inheritrange is not supported: give ctrlrange (the joint's range) instead",
                ));
            }
            p.gaintype = "fixed".into();
            p.biastype = "affine".into();
        }
        "velocity" => {
            let kv = number(e, "kv")?.unwrap_or(p.gain[0]);
            p.bias = [0.0, 0.0, -kv];
            p.gain[0] = kv;
            p.dyntype = "none".into();
            p.gaintype = "fixed".into();
            p.biastype = "affine".into();
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
                p.dampratio = false;
            }
        }
    }
    Ok(())
}

/// The law of actuator `a` (the element with its class's actuator defaults behind it), or a
/// problem at the element saying why triad cannot reproduce it.
pub(super) fn law(a: &Attrs) -> Result<ActuatorLaw, Problem> {
    let e = a.node;
    let mut p = Params::default();
    for d in a.chain().iter().rev() {
        apply(&mut p, d)?;
    }
    apply(&mut p, e)?;
    let refuse = |why: String| Err(e.problem(why));
    if p.dampratio {
        return refuse("dampratio is not supported: give the damping gain kv instead".into());
    }
    if p.dyntype != "none" {
        return refuse(format!(
            "actuator dynamics (dyntype=\"{}\", or a position servo's timeconst > 0) are not supported: triad's actuators act at once",
            p.dyntype
        ));
    }
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
