//! The operating point of a linear model: the minimal coordinates of `tree_dynamics` read off
//! a state's outputs.
//!
//! ```text
//! joint J (not spherical):  q = joint.J.q (angles unwrapped),  ν = joint.J.qd
//! spherical joint J:        θ = 0, M₀ = the rotation of joint.J.quat,  ν = joint.J.w
//! free body B:              r = body.B.r, θ = 0, R₀ = body.B.R,  ν = (body.B.v, body.B.w)
//! ```
//!
//! The rates are the outputs' (admissible, `projection.rs`); damping, stiffness and inputs are
//! the state's current values.

use super::state::State;
use crate::math::{exp_so3, matrix_to_quat, quat_to_matrix, Mat3, Vec3};
use crate::mechanics::model::def::{JointInitial, ModelDef};
use crate::mechanics::model::linear::{Linear, Quantity};
use crate::mechanics::model::runtime::Model;
use crate::mechanics::model::tree_dynamics::{Coord, TreeDynamics, Unsupported};

/// A state in minimal coordinates, ready to linearise.
#[derive(Clone, Debug)]
pub struct Operating {
    /// The model's dynamics at the state's damping, stiffness and orientations.
    pub dynamics: TreeDynamics,
    /// Coordinates `q` (n).
    pub q: Vec<f64>,
    /// Rates `ν` (n).
    pub nu: Vec<f64>,
    /// Inputs `u` (m), as the state holds them (before clamping).
    pub u: Vec<f64>,
}

impl Operating {
    /// The operating point of `state` (module table).
    ///
    /// # Errors
    /// [`Unsupported`] for loops and contact.
    pub fn of(model: &Model, state: &State) -> Result<Self, Unsupported> {
        let def = model.def();
        let out = state.outputs();
        let nj = def.joints.len();
        let damping: Vec<f64> = (0..nj).map(|j| state.damping(j)).collect();
        let stiffness: Vec<f64> = (0..nj).map(|j| state.stiffness(j)).collect();
        let joint_rot0 = (0..nj)
            .map(|j| {
                let q = &out.joints[j].q;
                if q.len() == 4 {
                    quat_to_matrix(&[q[0], q[1], q[2], q[3]])
                } else {
                    Mat3::identity()
                }
            })
            .collect();
        let body_rot0 = out.bodies.iter().map(|b| b.rot).collect();
        let dynamics = TreeDynamics::new(model, &damping, &stiffness, joint_rot0, body_rot0)?;
        let n = dynamics.n();
        let (mut q, mut nu) = (vec![0.0; n], vec![0.0; n]);
        for (i, co) in dynamics.coords().iter().enumerate() {
            match *co {
                Coord::Joint { joint, k } => {
                    let jo = &out.joints[joint];
                    if !dynamics.is_spherical(joint) {
                        q[i] = jo.q[k];
                    }
                    nu[i] = jo.qd[k];
                }
                Coord::Free { body, i: c } => {
                    let bo = &out.bodies[body];
                    if c < 3 {
                        q[i] = bo.r[c];
                        nu[i] = bo.v[c];
                    } else {
                        nu[i] = bo.w[c - 3];
                    }
                }
            }
        }
        Ok(Self {
            dynamics,
            q,
            nu,
            u: state.inputs().to_vec(),
        })
    }

    /// The exact linear model at this point with outputs `ys`.
    ///
    /// # Errors
    /// A message when the joint-space mass matrix is singular.
    pub fn linearize(&self, ys: &[Quantity]) -> Result<Linear, String> {
        self.dynamics.linearize(&self.q, &self.nu, &self.u, ys)
    }

    /// `def` with its initial state at `x = (q, ν)` of this operating point's coordinates
    /// (the rotation vectors applied exactly: `M₀ exp(θ̂)`, `exp(θ̂) R₀`), so that a run
    /// started from it starts at `x`.
    ///
    /// # Panics
    /// When `x` is not `2n` long.
    #[must_use]
    pub fn initial_def(&self, def: &ModelDef, x: &[f64]) -> ModelDef {
        let n = self.q.len();
        assert_eq!(x.len(), 2 * n, "initial_def: x length");
        let (q, nu) = x.split_at(n);
        let mut out = def.clone();
        let v3 = |v: &[f64], at: usize| Vec3::new(v[at], v[at + 1], v[at + 2]);
        for (j, jd) in out.joints.iter_mut().enumerate() {
            let Some(at) = self.dynamics.joint_at(j) else {
                continue;
            };
            if self.dynamics.is_spherical(j) {
                let m = self.dynamics.joint_rot0(j) * exp_so3(&v3(q, at));
                jd.initial = JointInitial::Spherical {
                    quat: matrix_to_quat(&m),
                    w: v3(nu, at),
                };
            } else {
                let k = jd.kind.dof();
                jd.initial = JointInitial::Coords {
                    q: q[at..at + k].to_vec(),
                    qd: nu[at..at + k].to_vec(),
                };
            }
        }
        for f in &mut out.free_bodies {
            let Some(at) = self.dynamics.free_at(f.body) else {
                continue;
            };
            f.position = v3(q, at);
            f.orientation = exp_so3(&v3(q, at + 3)) * self.dynamics.body_rot0(f.body);
            f.velocity = v3(nu, at);
            f.angular_velocity = v3(nu, at + 3);
        }
        out
    }

    /// The names of the coordinates then of the rates (`joint.J.q`, `joint.J.q[k]`,
    /// `joint.J.theta[k]`, `body.B.r[i]`, `body.B.theta[i]`; `joint.J.qd`, `joint.J.qd[k]`,
    /// `joint.J.w[k]`, `body.B.v[i]`, `body.B.w[i]`; indices 1-based).
    #[must_use]
    pub fn state_names(&self, model: &Model) -> Vec<String> {
        let def = model.def();
        let coords = self.dynamics.coords();
        let name = |co: &Coord, rate: bool| match *co {
            Coord::Joint { joint, k } => {
                let jd = &def.joints[joint];
                let (qn, vn) = if self.dynamics.is_spherical(joint) {
                    ("theta", "w")
                } else {
                    ("q", "qd")
                };
                let base = if rate { vn } else { qn };
                if jd.kind.dof() == 1 {
                    format!("joint.{}.{base}", jd.name)
                } else {
                    format!("joint.{}.{base}[{}]", jd.name, k + 1)
                }
            }
            Coord::Free { body, i } => {
                let b = &def.bodies[body].name;
                let base = match (i < 3, rate) {
                    (true, false) => "r",
                    (false, false) => "theta",
                    (true, true) => "v",
                    (false, true) => "w",
                };
                format!("body.{b}.{base}[{}]", i % 3 + 1)
            }
        };
        coords
            .iter()
            .map(|c| name(c, false))
            .chain(coords.iter().map(|c| name(c, true)))
            .collect()
    }
}
