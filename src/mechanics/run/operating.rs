//! The operating point of a linear model: the minimal coordinates of `tree_dynamics` read off
//! a state's outputs.
//!
//! ```text
//! joint J (not spherical):  q = joint.J.q (angles unwrapped),  ν = joint.J.qd
//! spherical joint J:        θ = 0, M₀ = the rotation of joint.J.quat,  ν = joint.J.w
//! free body B:              r = body.B.r, θ = 0, R₀ = body.B.R,  ν = (body.B.v, body.B.w)
//! ```
//!
//! The rates are the outputs' (admissible, `projection.rs`); damping, stiffness, actuator gains
//! and inputs are the state's current values.
//!
//! ```text
//! touching contacts, joint friction: their sticking bristles σ (`sticking`) follow, x = (q, ν, σ):
//!   the state's, or (a result's row, which does not record them) fitted to the accelerations
//! closed loops: q, ν above are the tree's (every tree joint); the loops' split (`loop_closure`)
//!   picks I, then q_D, ν_D are solved from q_I, ν_I (the point closes the loops to round-off)
//!   and the state is x = (q_I, ν_I)
//! ```

use super::state::State;
use crate::math::{exp_so3, matrix_to_quat, quat_to_matrix, Mat3, Vec3};
use crate::mechanics::model::def::{JointInitial, ModelDef, SolverSettings};
use crate::mechanics::model::linear::lift;
use crate::mechanics::model::linear::{Linear, Quantity};
use crate::mechanics::model::loop_closure::{Closure, Independent};
use crate::mechanics::model::runtime::Model;
use crate::mechanics::model::sticking::Sticking;
use crate::mechanics::model::tree_dynamics::{Coord, TreeDynamics, Unsupported};
use nalgebra::{DMatrix, DVector};
use num_dual::Dual64;

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
    /// The loops' closure and split into independent coordinates (`None`: a tree).
    pub loops: Option<Closure>,
    /// The state's contact bristles (3 per ground point, world) and joint friction bristles,
    /// from which [`Operating::pick`] takes the sticking ones; `None` when unknown (a point
    /// read from a result): then they are fitted ([`Operating::fit_bristles`]).
    bristles: Option<(Vec<f64>, Vec<f64>)>,
    /// `|ν̇|` before and after the last fit of the bristles, if they were fitted.
    pub fitted: Option<(f64, f64)>,
}

impl Operating {
    /// The operating point of `state` (module table); closed loops in the independent
    /// coordinates triad picks ([`Independent::Auto`]).
    ///
    /// # Errors
    /// [`Unsupported`] for contact and joint friction, or loops that cannot be split here.
    pub fn of(model: &Model, state: &State) -> Result<Self, Unsupported> {
        Self::picked(model, state, &Independent::Auto)
    }

    /// [`Operating::of`] with the independent coordinates `pick` of closed loops.
    ///
    /// # Errors
    /// As [`Operating::of`]; a `pick` that is not independent here, or for a tree.
    pub fn picked(model: &Model, state: &State, pick: &Independent) -> Result<Self, Unsupported> {
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
        let gains = &state.gains;
        let dynamics =
            TreeDynamics::new(model, &damping, &stiffness, gains, joint_rot0, body_rot0)?;
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
        let mut op = Self {
            dynamics,
            q,
            nu,
            u: state.inputs().to_vec(),
            loops: None,
            bristles: Some((state.bristle.clone(), state.fric.clone())),
            fitted: None,
        };
        op.pick(model, pick).map_err(Unsupported::Closure)?;
        Ok(op)
    }

    /// Splits closed loops into the independent coordinates `pick` at the current `q` and
    /// closes them: `q_D`, `ν_D` solved from `q_I`, `ν_I` (module docs). Nothing for a tree
    /// (but a named pick is refused).
    ///
    /// # Errors
    /// A message: `pick` not independent here, or the loops do not close near `q`.
    pub fn pick(&mut self, model: &Model, pick: &Independent) -> Result<(), String> {
        self.loops = Closure::new(&self.dynamics, model, &self.q, pick)?;
        if let Some(cl) = &self.loops {
            let (qi, vi) = (cl.pick(&self.q), cl.pick(&self.nu));
            let (q, nu) = cl.complete(&self.dynamics, &self.q, &qi, &vi)?;
            self.q = q;
            self.nu = nu;
        }
        self.touch(model).map_err(|e| e.to_string())
    }

    /// Takes the touching ground points and the joints' friction bristles at this point
    /// (`sticking`), the bristles from the state or, unknown, fitted; checks that they stick.
    fn touch(&mut self, model: &Model) -> Result<(), Unsupported> {
        let n3 = 3 * model.contact.bristles();
        let (bristle, fric) = self
            .bristles
            .clone()
            .unwrap_or_else(|| (vec![0.0; n3], vec![0.0; model.nfric]));
        let s = Sticking::at(&self.dynamics, model, &self.q, &bristle, &fric)?;
        if self.loops.is_some() && !s.is_empty() {
            return Err(Unsupported::LoopSticking);
        }
        self.dynamics.set_sticking(s);
        if self.bristles.is_none() {
            self.fitted = Some(self.fit_bristles().map_err(Unsupported::Closure)?);
        }
        self.dynamics
            .sticking()
            .check(&self.dynamics, &self.q, &self.nu)
    }

    /// Forgets the state's bristles (a point read from a result, which does not record them):
    /// the next [`Operating::pick`] fits them.
    pub fn forget_bristles(&mut self) {
        self.bristles = None;
    }

    /// Fits the sticking bristles `σ` to the point: the accelerations `ν̇ = ν̇₀ + G σ` (affine
    /// in `σ`) closest to 0 in the kinetic metric, `min |Lᵀ(ν̇₀ + G σ)|` (`M = L Lᵀ`), the
    /// least-norm `σ` (bristle stresses that move nothing stay 0). Returns `|ν̇|` before and
    /// after (0, 0 without bristles).
    ///
    /// # Errors
    /// A singular mass matrix.
    pub fn fit_bristles(&mut self) -> Result<(f64, f64), String> {
        let td = &self.dynamics;
        let ns = td.sticking().n();
        if ns == 0 {
            return Ok((0.0, 0.0));
        }
        let (q, nu, u) = (&self.q, &self.nu, &self.u);
        let n = q.len();
        // ν̇₀ = −M⁻¹ res(σ = 0)
        let zero = vec![0.0; ns];
        let res0 = td.residual_with(q, nu, &vec![0.0; n], u, &zero, false);
        let chol = td
            .mass_matrix(q)
            .cholesky()
            .ok_or("the joint-space mass matrix is not positive definite")?;
        let nud0 = chol.solve(&-DVector::from_vec(res0));
        let before = nud0.norm();
        let lt = chol.l().transpose();
        // G = ∂ν̇/∂σ = −M⁻¹ ∂res/∂σ, one dual pass per bristle
        let (qd, vd, ud) = (lift(q, None), lift(nu, None), lift(u, None));
        let nud_d: Vec<Dual64> = nud0.iter().map(|&x| Dual64::from(x)).collect();
        let mut g = DMatrix::zeros(n, ns);
        for j in 0..ns {
            let res = td.residual_with(&qd, &vd, &nud_d, &ud, &lift(&zero, Some(j)), false);
            let r = DVector::from_iterator(n, res.iter().map(|x| -x.eps));
            g.set_column(j, &chol.solve(&r));
        }
        let a = &lt * &g;
        let b = -(&lt * nud0);
        let svd = a.svd(true, true);
        let tol = 1e-12 * svd.singular_values.max();
        let sigma = svd.solve(&b, tol)?;
        self.dynamics.set_sticking({
            let mut s = self.dynamics.sticking().clone();
            s.set_sigma0(sigma.as_slice());
            s
        });
        let (after, _) = self.dynamics.accelerations(q, nu, u)?;
        Ok((before, after.iter().map(|x| x * x).sum::<f64>().sqrt()))
    }

    /// The state `x`: `(q, ν, σ)` (`σ` the sticking bristles, `sticking`), or `(q_I, ν_I)`
    /// with closed loops.
    #[must_use]
    pub fn x(&self) -> Vec<f64> {
        match &self.loops {
            Some(cl) => cl
                .pick(&self.q)
                .into_iter()
                .chain(cl.pick(&self.nu))
                .collect(),
            None => self
                .q
                .iter()
                .chain(&self.nu)
                .chain(self.dynamics.sticking().sigma0())
                .copied()
                .collect(),
        }
    }

    /// The bristles of a state at this point: the contact bristles (`State::contact_bristles`:
    /// 3 per ground point, world, then 3 per body–body feature, m), each touching point's
    /// sticking bristle `Σᵢ σᵢ tᵢ` on the ground's tangent axes, the others 0; and the joint
    /// friction bristles (`State::joint_bristles`, rad or m), those of `σ`, the others 0.
    #[must_use]
    pub fn bristles(&self, model: &Model) -> (Vec<f64>, Vec<f64>) {
        let mut contact = vec![0.0; 3 * model.contact.bristles()];
        let sticking = self.dynamics.sticking();
        let axes = sticking.contact_axes();
        let sigma = sticking.sigma0();
        for ((k, axis), s) in axes.iter().zip(sigma) {
            for i in 0..3 {
                contact[3 * k + i] += s * axis[i];
            }
        }
        let mut joints = vec![0.0; model.nfric];
        for (i, s) in sticking
            .joint_bristles()
            .into_iter()
            .zip(&sigma[axes.len()..])
        {
            joints[i] = *s;
        }
        (contact, joints)
    }

    /// The tree's `(q, ν)` at the state `x` (with closed loops: completed, module docs).
    ///
    /// # Errors
    /// A message when the loops do not close near `x`.
    pub fn tree_of(&self, x: &[f64]) -> Result<(Vec<f64>, Vec<f64>), String> {
        match &self.loops {
            Some(cl) => {
                let k = cl.indep.len();
                cl.complete(&self.dynamics, &self.q, &x[..k], &x[k..])
            }
            None => {
                let n = self.q.len();
                Ok((x[..n].to_vec(), x[n..2 * n].to_vec()))
            }
        }
    }

    /// The exact linear model at this point with outputs `ys`.
    ///
    /// # Errors
    /// A message when the joint-space (or the loops' constrained) mass matrix is singular.
    pub fn linearize(&self, ys: &[Quantity]) -> Result<Linear, String> {
        match &self.loops {
            Some(cl) => cl.linearize(&self.dynamics, &self.q, &self.nu, &self.u, ys),
            None => self.dynamics.linearize(&self.q, &self.nu, &self.u, ys),
        }
    }

    /// The directional derivative of the outputs `ys` along `(δx, δu)` at this point:
    /// `C δx + D δu`, `δx` over [`Operating::x`] (one dual pass; with closed loops
    /// `Closure::directional`, whose unit directions give [`Operating::linearize`]'s columns).
    ///
    /// # Errors
    /// A message when the (constrained) mass matrix is singular or a loop does not close;
    /// `dx` not as long as [`Operating::x`].
    pub fn directional(&self, dx: &[f64], du: &[f64], ys: &[Quantity]) -> Result<Vec<f64>, String> {
        let nx = self.x().len();
        if dx.len() != nx || du.len() != self.u.len() {
            return Err(format!(
                "directional: {} state and {} input directions for {nx} states and {} inputs",
                dx.len(),
                du.len(),
                self.u.len()
            ));
        }
        if !self.dynamics.sticking().is_empty() {
            return Err(
                "directional: the bristle states of contact and joint friction are \
                        not covered here (Operating::linearize has them)"
                    .into(),
            );
        }
        let (dq, dnu) = dx.split_at(nx / 2);
        match &self.loops {
            Some(cl) => Ok(cl
                .directional(
                    &self.dynamics,
                    &self.q,
                    &self.nu,
                    &self.u,
                    (dq, dnu, du),
                    ys,
                )?
                .1),
            None => self
                .dynamics
                .directional(&self.q, &self.nu, &self.u, dq, dnu, du, ys),
        }
    }

    /// With closed loops or couplings, the tree coordinates that are the state's independent
    /// ones (`Closure::indep`, ascending); `None` for a tree.
    #[must_use]
    pub fn independent(&self) -> Option<Vec<Coord>> {
        let coords = self.dynamics.coords();
        self.loops
            .as_ref()
            .map(|cl| cl.indep.iter().map(|&i| coords[i]).collect())
    }

    /// The independent coordinates `triad linearize` picks by default
    /// ([`Independent::Auto`]) at the initial state of `def` with `settings` (the state a
    /// simulation starts from: `Model::new`, `State::new`, [`Operating::of`]); `None` for a
    /// tree. The FMU of a model with closed loops or couplings declares these as its states.
    ///
    /// # Errors
    /// The model is invalid, has no linear model (contact, joint friction), or its loops
    /// cannot be split at the initial state.
    pub fn initial_independent(
        def: &ModelDef,
        settings: SolverSettings,
    ) -> Result<Option<Vec<Coord>>, String> {
        let model = Model::new(def, settings).map_err(|e| e.to_string())?;
        let state = State::new(&model);
        let op = Self::of(&model, &state).map_err(|e| e.to_string())?;
        Ok(op.independent())
    }

    /// Whether output `y` can be differentiated here: not the joint values of loop-closing
    /// joints (they are no coordinates of the tree).
    #[must_use]
    pub fn differentiable(&self, y: &Quantity) -> bool {
        match *y {
            Quantity::JointQ(j, _) | Quantity::JointQd(j, _) | Quantity::JointQdd(j, _) => {
                self.dynamics.joint_at(j).is_some()
            }
            // the contact springs' and bristles' energy is not part of `tree_dynamics`'s
            Quantity::Energy => self.dynamics.sticking().is_empty(),
            _ => true,
        }
    }

    /// The tree's accelerations `ν̇` at this point (on the loops, with closed loops).
    ///
    /// # Errors
    /// A message when the mass matrix is singular.
    pub fn accelerations(&self) -> Result<Vec<f64>, String> {
        match &self.loops {
            Some(cl) => cl.accelerations(&self.dynamics, &self.q, &self.nu, &self.u),
            None => Ok(self.dynamics.accelerations(&self.q, &self.nu, &self.u)?.0),
        }
    }

    /// `def` with its initial state at the state `x` of this operating point's coordinates
    /// (the rotation vectors applied exactly: `M₀ exp(θ̂)`, `exp(θ̂) R₀`; closed loops closed
    /// by the dependent coordinates), so that a run started from it starts at `x`.
    ///
    /// # Panics
    /// When `x` is not as long as [`Operating::x`], or the loops do not close near `x`.
    #[must_use]
    pub fn initial_def(&self, def: &ModelDef, x: &[f64]) -> ModelDef {
        assert_eq!(x.len(), self.x().len(), "initial_def: x length");
        let (q, nu) = self
            .tree_of(x)
            .unwrap_or_else(|e| panic!("initial_def: {e}"));
        let (q, nu) = (&q[..], &nu[..]);
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

    /// The names of the state `x`: [`Operating::tree_names`], of `I` only with closed loops.
    #[must_use]
    pub fn state_names(&self, model: &Model) -> Vec<String> {
        let all = self.tree_names(model);
        match &self.loops {
            Some(cl) => {
                let n = self.q.len();
                let rates: Vec<usize> = cl.indep.iter().map(|i| n + i).collect();
                cl.indep
                    .iter()
                    .chain(&rates)
                    .map(|&i| all[i].clone())
                    .collect()
            }
            None => all
                .into_iter()
                .chain(self.dynamics.sticking().names(model))
                .collect(),
        }
    }

    /// The names of the tree's coordinates then of its rates (`joint.J.q`, `joint.J.q[k]`,
    /// `joint.J.theta[k]`, `body.B.r[i]`, `body.B.theta[i]`; `joint.J.qd`, `joint.J.qd[k]`,
    /// `joint.J.w[k]`, `body.B.v[i]`, `body.B.w[i]`; indices 1-based).
    #[must_use]
    pub fn tree_names(&self, model: &Model) -> Vec<String> {
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
