//! Frames and orientations as MuJoCo reads them.
//!
//! `<compiler angle>` (MuJoCo's default: `degree`) is the unit of `euler`, `axisangle`, joint
//! `range`, `ref` and `springref` of hinges; `<compiler eulerseq>` (default `xyz`) names the
//! axes of `euler`, one letter per angle: lower case rotates about the axes of the frame being
//! rotated (intrinsic, `R = R·Rₐ(θ)`), upper case about the fixed axes (extrinsic,
//! `R = Rₐ(θ)·R`), letter by letter from `R = I`.
//!
//! ```text
//! quat w x y z           R(q/|q|)
//! axisangle x y z a      rotation by a about the unit axis
//! xyaxes x₁ x₂ x₃ y₁ y₂ y₃  columns x/|x|, y' = y − (x·y)x normalised, x × y'
//! zaxis z₁ z₂ z₃         the shortest rotation taking (0, 0, 1) to z/|z|
//! ```

use super::defaults::Attrs;
use crate::import::frame::Iso;
use crate::math::{exp_so3, quat_to_matrix, Mat3, Vec3};
use crate::spec::Problem;

/// The angle settings of `<compiler>`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Angles {
    /// `angle="radian"` (MuJoCo's default is degree).
    pub radian: bool,
    /// `eulerseq`, three of `xyzXYZ`.
    pub seq: [u8; 3],
}

impl Default for Angles {
    fn default() -> Self {
        Self {
            radian: false,
            seq: *b"xyz",
        }
    }
}

impl Angles {
    /// `x` in the compiler's unit, in radians.
    pub fn rad(&self, x: f64) -> f64 {
        if self.radian {
            x
        } else {
            x.to_radians()
        }
    }

    /// The rotation of `euler` angles (in the compiler's unit).
    pub fn euler(&self, e: [f64; 3]) -> Mat3 {
        let mut r = Mat3::identity();
        for (k, &c) in self.seq.iter().enumerate() {
            let axis = match c.to_ascii_lowercase() {
                b'x' => Vec3::x(),
                b'y' => Vec3::y(),
                _ => Vec3::z(),
            };
            let rk = exp_so3(&(axis * self.rad(e[k])));
            r = if c.is_ascii_lowercase() {
                r * rk
            } else {
                rk * r
            };
        }
        r
    }
}

/// The shortest rotation taking `(0, 0, 1)` to the unit vector `z`.
pub(super) fn z_to(z: Vec3) -> Mat3 {
    let e = Vec3::z();
    let c = e.dot(&z);
    let s = e.cross(&z);
    if s.norm() < 1e-14 {
        // z along ±e: identity, or a half turn about x
        return if c > 0.0 {
            Mat3::identity()
        } else {
            Mat3::new(1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, -1.0)
        };
    }
    exp_so3(&(s.normalize() * s.norm().atan2(c)))
}

/// A unit vector from `v`, or a problem naming `what` when it has no length.
pub(super) fn unit(v: [f64; 3], what: &str, a: &Attrs) -> Result<Vec3, Problem> {
    let v = Vec3::from(v);
    if v.norm() < 1e-12 {
        return Err(a.node.problem(format!("{what} has zero length")));
    }
    Ok(v.normalize())
}

/// The orientation `a` gives (identity when none); more than one form is a problem.
pub(super) fn orientation(a: &Attrs, angles: &Angles) -> Result<Mat3, Problem> {
    let src = a.orientation_source();
    let given: Vec<&str> = super::defaults::ORIENTATIONS
        .iter()
        .copied()
        .filter(|k| src.attr(k).is_some())
        .collect();
    let Some(&form) = given.first() else {
        return Ok(Mat3::identity());
    };
    if given.len() > 1 {
        return Err(a.node.problem(format!(
            "orientation given twice ({}): give one of quat, axisangle, euler, xyaxes, zaxis",
            given.join(", ")
        )));
    }
    let text = src.attr(form).unwrap_or_default();
    let n = match form {
        "quat" | "axisangle" => 4,
        "xyaxes" => 6,
        _ => 3,
    };
    let v = super::defaults::numbers_of(text, form, n, n, a.node, src)?;
    match form {
        "quat" => {
            let q = [v[0], v[1], v[2], v[3]];
            if q.iter().map(|x| x * x).sum::<f64>() < 1e-24 {
                return Err(a.node.problem("quat has zero length"));
            }
            Ok(quat_to_matrix(&q))
        }
        "axisangle" => {
            let axis = unit([v[0], v[1], v[2]], "the axis of axisangle", a)?;
            Ok(exp_so3(&(axis * angles.rad(v[3]))))
        }
        "euler" => Ok(angles.euler([v[0], v[1], v[2]])),
        "xyaxes" => {
            let x = unit([v[0], v[1], v[2]], "the x axis of xyaxes", a)?;
            let y = Vec3::new(v[3], v[4], v[5]);
            let y = y - x * x.dot(&y);
            if y.norm() < 1e-12 {
                return Err(a
                    .node
                    .problem("xyaxes: the y axis is parallel to the x axis"));
            }
            let y = y.normalize();
            Ok(Mat3::from_columns(&[x, y, x.cross(&y)]))
        }
        _ => Ok(z_to(unit([v[0], v[1], v[2]], "zaxis", a)?)),
    }
}

/// The frame `pos` + orientation of `a` in its parent's frame.
pub(super) fn frame(a: &Attrs, angles: &Angles) -> Result<Iso, Problem> {
    Ok(Iso {
        r: orientation(a, angles)?,
        p: Vec3::from(a.array("pos", [0.0; 3])?),
    })
}
