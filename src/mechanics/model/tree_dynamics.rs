//! The continuous-time dynamics of a tree model in minimal coordinates, generic over the
//! scalar (`f64`, or a dual number for exact derivatives: `linear`).
//!
//! State `x = (q, ν)`, `n` coordinates and `n` rates. Per tree joint J (model order, fixed
//! joints have none) its coordinates and rates as `joint.J.q`, `joint.J.qd`, except a
//! spherical joint: `θ` (3, a rotation vector of the child joint frame about the operating
//! orientation, child frame: `M = M₀ exp(θ̂)`) and `w` (3, the relative angular velocity in the
//! child frame). Per free body B (before the joints): `r` (3, its frame origin, world), `θ` (3,
//! `R = exp(θ̂) R₀`, world) and `v`, `ω` (frame origin velocity and angular velocity, world).
//! The rotation vectors are perturbations: the functions hold at `θ = 0` with their first
//! derivatives (`exp(θ̂) ≈ I + θ̂ + ½θ̂²`), which is where `linear` evaluates them.
//!
//! ```text
//! kinematics (kinematics.rs, parent before child; J = parent joint frame, c = child joint frame)
//!   R_J = R_p R_pf,  o_J = o_p + R_p t_pf,  R_c = R_J M(q),  o_c = o_J + R_J τ(q)
//!   ω_rel = Σ a_k ν_k,  τ̇ = Σ b_k ν_k                        (a_k, b_k in J)
//!   ω_b = ω_p + R_J ω_rel,   v_c = v_J + ω_p × R_J τ + R_J τ̇
//!   α_b = α_p + ω_p × R_J ω_rel + R_J (Σ a_k ν̇_k + β_ω),       β_ω = e₁α̇ × a_β β̇ (universal)
//!   a_c = a_J + α_p × R_Jτ + ω_p × (ω_p × R_Jτ) + 2 ω_p × R_J τ̇ + R_J Σ b_k ν̇_k
//! inverse dynamics (RNEA, moments about the world origin)
//!   F_b = m (a_G − g) − f_ext,   N_b = I α + ω × I ω − n_ext + p_G × F_b    (per body)
//!   Q_k = ω_k · (N − p × F) + u_k · F    (subtree totals; dof k moves the subtree by the
//!                                          twist ω_k about the point p with velocity u_k there)
//!   res = Q + a ν̇ − (act − k q − c q̇ + stop(q, q̇) + Σ τ_A(u_A, q, q̇))
//!                       (actuators clamped to ±effort; a: the rotor inertia, armature;
//!                        τ_A: the joint actuators of `joint_actuator`)
//!   stop(q, q̇) = −k⟨q − upper⟩ + k⟨lower − q⟩ − c (⟨q − upper⟩ + ⟨lower − q⟩) q̇
//! coordinate rates  q̇ = ν, except  θ̇ = w + ½ θ × w  (spherical),  θ̇ = ω − ½ θ × ω  (free)
//! energy  E = Σ ½ m|v_G|² + ½ ω·Iω − m g·p_G + Σ (½ k q² + ½ a q̇²) + stops   (as `outputs.rs`)
//! mass matrix  M(q) by composite inertias, plus a on the diagonal of each rotor's coordinate
//! ```
//!
//! The loads are those of the step (`step/joint_loads.rs`): actuator torques `±τ n` and slide
//! forces, springs and dampers per coordinate, a spherical joint's damper `−c(ω_B − ω_A)` and
//! torques about its parent joint-frame axes, body torques and forces (world frame, at the
//! centre of mass), gravity. Loop-closing joints are not tree edges: their rows constrain the
//! tree's coordinates (`loop_closure`, `loop_linear`). Ground contacts touching at the
//! operating point and joint friction load the bodies and coordinates through their sticking
//! bristles (`sticking`, states beside `(q, ν)`).
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use super::def::{JointType, ModelDef};
use super::joint::joint_frame;
use super::joint_actuator::JointActuators;
pub use super::motion::Motion;
use super::runtime::Model;
pub use super::scalar::{c, Real};
use super::scalar::{cm, cv, hat, mm, mv};
use super::sticking::{lift_sigma, Sticking};
use super::stops::Stops;
pub use super::unsupported::Unsupported;
use crate::math::{Mat3, Vec3};
use nalgebra::{Matrix3, Vector3};

/// Rotation by `t` about the unit axis `n`.
fn rot<T: Real>(n: &Vector3<T>, t: T) -> Matrix3<T> {
    let (s, co) = (t.sin(), t.cos());
    let k = T::one() - co;
    Matrix3::from_fn(|i, j| {
        let d = if i == j { co } else { T::zero() };
        d + n[i] * n[j] * k
    }) + hat(n) * s
}

/// `exp(θ̂)` to second order: exact with its first derivative at `θ = 0`.
fn exp_small<T: Real>(th: &Vector3<T>) -> Matrix3<T> {
    let h = hat(th);
    Matrix3::identity() + h + mm(&h, &h) * c::<T>(0.5)
}

/// What one coordinate is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coord {
    /// Coordinate `k` of joint `joint` (a spherical joint's: the rotation vector component).
    Joint {
        /// Joint index.
        joint: usize,
        /// Component.
        k: usize,
    },
    /// Component `i` of a free body's position (`i < 3`) or rotation vector (`i ≥ 3`).
    Free {
        /// Body index.
        body: usize,
        /// Component 0..6.
        i: usize,
    },
}

#[derive(Clone, Debug)]
struct JointData {
    kind: JointType,
    parent: Option<usize>,
    child: usize,
    pf_t: Vec3,
    pf_r: Mat3,
    cf_t: Vec3,
    cf_r: Mat3,
    /// The internal joint frame `S` (columns e₁, e₂, n in the user's joint frame).
    s: Mat3,
    /// Offset of the joint's coordinates in `q` (and rates in `ν`).
    at: usize,
    damping: f64,
    stiffness: f64,
    armature: f64,
    stops: Option<Stops>,
    effort: f64,
    input: Option<usize>,
    acts: JointActuators,
}

/// A tree model prepared for the minimal-coordinate dynamics, at given damping and stiffness
/// values and operating orientations.
#[derive(Clone, Debug)]
pub struct TreeDynamics {
    gravity: Vec3,
    mass: Vec<f64>,
    com: Vec<Vec3>,
    inertia: Vec<Mat3>,
    order: Vec<usize>,
    /// Per body: its tree joint, or its free-body offset in `q`.
    parent_of: Vec<Parent>,
    joints: Vec<Option<JointData>>,
    torques: Vec<(usize, usize)>,
    forces: Vec<(usize, usize)>,
    /// Operating orientation of each spherical joint (`M₀`) and free body (`R₀`), by joint or
    /// body index.
    joint_rot0: Vec<Mat3>,
    body_rot0: Vec<Mat3>,
    sites: Vec<(usize, Vec3, Mat3)>,
    coords: Vec<Coord>,
    nu: usize,
    /// The touching ground points and the joints' friction bristles of the operating point
    /// (`sticking`; empty until [`TreeDynamics::set_sticking`]).
    sticking: Sticking,
    /// The actuators' gains `[kp, kv]`, two per actuator of the model.
    gains: Vec<f64>,
}

/// A joint's relative motion in its parent joint frame: `M`, `τ`, the rate columns `(a_k, b_k)`
/// and the angular bias `β_ω`.
type Local<T> = (
    Matrix3<T>,
    Vector3<T>,
    Vec<(Vector3<T>, Vector3<T>)>,
    Vector3<T>,
);

/// The mass matrix's LU factors.
pub type MassLu = nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>;

#[derive(Clone, Copy, Debug)]
enum Parent {
    Joint(usize),
    Free(usize),
}

/// Whether `def` has a minimal-coordinate dynamics in tree coordinates alone: a tree (no
/// loop-closing joint, no coupling) that [`linearizable`] admits.
///
/// # Errors
/// [`Unsupported`] naming the first obstacle.
pub fn supported(def: &ModelDef) -> Result<(), Unsupported> {
    if let Some(j) = def.joints.iter().find(|j| j.loop_closing) {
        return Err(Unsupported::Loop(j.name.clone()));
    }
    if let Some(c) = def.couplings.first() {
        return Err(Unsupported::Coupling(def.joints[c.b].name.clone()));
    }
    linearizable(def)
}

/// Whether `def`'s FMU has linear models (directional derivatives over its declared joint
/// states, and the `joint.J.qdd` outputs): no collision shapes, no joint friction, whose
/// bristles would be states the FMU has no variables for; closed loops and couplings in their
/// independent coordinates. (`triad linearize` takes contact and friction too: `sticking`.)
///
/// # Errors
/// [`Unsupported`] naming the first obstacle.
pub fn linearizable(def: &ModelDef) -> Result<(), Unsupported> {
    if !def.contact.shapes.is_empty() {
        return Err(Unsupported::Contact);
    }
    if let Some(j) = def.joints.iter().find(|j| j.friction > 0.0) {
        return Err(Unsupported::Friction(j.name.clone()));
    }
    Ok(())
}

impl TreeDynamics {
    /// Prepares `model` with the joints' current `damping` and `stiffness` (per joint), the
    /// actuators' current `gains` (`[kp, kv]` per actuator, as `State::gains`) and the
    /// operating orientations `joint_rot0` (spherical joints: relative rotation child joint
    /// frame → parent joint frame; others unused) and `body_rot0` (free bodies; others unused).
    ///
    /// Touching contacts and joint friction come later, at an operating point
    /// ([`TreeDynamics::set_sticking`]).
    ///
    /// # Errors
    /// None today (every model has this dynamics); kept for obstacles a model may bring.
    pub fn new(
        model: &Model,
        damping: &[f64],
        stiffness: &[f64],
        gains: &[f64],
        joint_rot0: Vec<Mat3>,
        body_rot0: Vec<Mat3>,
    ) -> Result<Self, Unsupported> {
        let def: &ModelDef = model.def();
        let nb = def.bodies.len();
        let mut coords = Vec::new();
        let mut parent_of = vec![Parent::Free(0); nb];
        for f in &def.free_bodies {
            parent_of[f.body] = Parent::Free(coords.len());
            coords.extend((0..6).map(|i| Coord::Free { body: f.body, i }));
        }
        let mut joints = Vec::with_capacity(def.joints.len());
        for (j, jd) in def.joints.iter().enumerate() {
            if jd.loop_closing {
                // its rows are the loop-closure constraints (`loop_closure`), not a tree edge
                joints.push(None);
                continue;
            }
            parent_of[jd.child] = Parent::Joint(j);
            let at = coords.len();
            coords.extend((0..jd.kind.dof()).map(|k| Coord::Joint { joint: j, k }));
            let jt = &model.joints[j];
            joints.push(Some(JointData {
                kind: jd.kind,
                parent: jd.parent,
                child: jd.child,
                pf_t: jd.parent_frame.translation,
                pf_r: jd.parent_frame.rotation,
                cf_t: jd.child_frame.translation,
                cf_r: jd.child_frame.rotation,
                s: joint_frame(jd).unwrap_or_else(|_| Mat3::identity()),
                at,
                damping: damping[j],
                stiffness: stiffness[j],
                armature: jt.armature,
                stops: jt.stops,
                effort: jt.effort,
                input: jt.input,
                acts: jt.acts.clone(),
            }));
        }
        Ok(Self {
            gravity: def.gravity,
            mass: def.bodies.iter().map(|b| b.mass).collect(),
            com: def.bodies.iter().map(|b| b.com).collect(),
            inertia: def.bodies.iter().map(|b| b.inertia).collect(),
            order: model.order.clone(),
            parent_of,
            joints,
            torques: model.body_torques.clone(),
            forces: model.body_forces.clone(),
            joint_rot0,
            body_rot0,
            sites: def
                .sites
                .iter()
                .map(|s| (s.body, s.frame.translation, s.frame.rotation))
                .collect(),
            nu: model.inputs.len(),
            gains: gains.to_vec(),
            coords,
            sticking: Sticking::default(),
        })
    }

    /// The coordinates, in order (`n` of them; the rates follow the same order).
    #[must_use]
    pub fn coords(&self) -> &[Coord] {
        &self.coords
    }

    /// Number of coordinates `n`.
    #[must_use]
    pub fn n(&self) -> usize {
        self.coords.len()
    }

    /// Number of inputs.
    #[must_use]
    pub fn n_inputs(&self) -> usize {
        self.nu
    }

    /// Number of bodies.
    #[must_use]
    pub fn n_bodies(&self) -> usize {
        self.mass.len()
    }

    /// Number of sites.
    #[must_use]
    pub fn n_sites(&self) -> usize {
        self.sites.len()
    }

    /// Offset of joint `j`'s coordinates in `q`.
    #[must_use]
    pub fn joint_at(&self, j: usize) -> Option<usize> {
        self.joints.get(j)?.as_ref().map(|d| d.at)
    }

    /// Offset of free body `b`'s coordinates in `q`.
    #[must_use]
    pub fn free_at(&self, b: usize) -> Option<usize> {
        match self.parent_of.get(b)? {
            Parent::Free(at) => Some(*at),
            Parent::Joint(_) => None,
        }
    }

    /// Relative motion of joint `jd` in its parent joint frame: `M`, `τ`, the rate columns
    /// `(a_k, b_k)` and the rate-quadratic angular bias `β_ω`.
    fn local<T: Real>(&self, j: usize, jd: &JointData, q: &[T], nu: &[T]) -> Local<T> {
        let s = cm::<T>(&jd.s);
        let (e1, e2, n) = (
            s.column(0).into_owned(),
            s.column(1).into_owned(),
            s.column(2).into_owned(),
        );
        let z = Vector3::zeros();
        let q = &q[jd.at..];
        let nu = &nu[jd.at..];
        match jd.kind {
            JointType::Revolute => (rot(&n, q[0]), z, vec![(n, z)], z),
            JointType::Prismatic => (Matrix3::identity(), n * q[0], vec![(z, n)], z),
            JointType::Cylindrical => (rot(&n, q[1]), n * q[0], vec![(z, n), (n, z)], z),
            JointType::Universal => {
                let ra = rot(&e1, q[0]);
                let ab = mv(&ra, &e2);
                let bias = (e1 * nu[0]).cross(&(ab * nu[1]));
                (mm(&ra, &rot(&e2, q[1])), z, vec![(e1, z), (ab, z)], bias)
            }
            JointType::Planar => (
                rot(&n, q[2]),
                e1 * q[0] + e2 * q[1],
                vec![(z, e1), (z, e2), (n, z)],
                z,
            ),
            JointType::Spherical => {
                let th = Vector3::new(q[0], q[1], q[2]);
                let m = mm(&cm::<T>(&self.joint_rot0[j]), &exp_small(&th));
                let cols = (0..3)
                    .map(|k| (m.column(k).into_owned(), z))
                    .collect::<Vec<_>>();
                (m, z, cols, z)
            }
            JointType::Fixed => (Matrix3::identity(), z, Vec::new(), z),
        }
    }

    /// Poses, twists and (with `nud`) accelerations of every body at `(q, ν, ν̇)`; without
    /// `nud` the accelerations are left at zero (not the velocity-product terms at `ν̇ = 0`).
    #[allow(clippy::too_many_lines)]
    pub fn motion<T: Real>(&self, q: &[T], nu: &[T], nud: Option<&[T]>) -> Motion<T> {
        let nb = self.mass.len();
        let z = Vector3::<T>::zeros();
        let mut m = Motion {
            o: vec![z; nb],
            r: vec![Matrix3::identity(); nb],
            v: vec![z; nb],
            w: vec![z; nb],
            a: vec![z; nb],
            al: vec![z; nb],
            cols: vec![(z, z, z); self.coords.len()],
        };
        let zeros = vec![T::zero(); self.coords.len()];
        // without accelerations their terms are left at zero (most passes: poses and twists)
        let acc = nud.is_some();
        let nud = nud.unwrap_or(&zeros);
        for &b in &self.order {
            match self.parent_of[b] {
                Parent::Free(at) => {
                    let th = Vector3::new(q[at + 3], q[at + 4], q[at + 5]);
                    m.o[b] = Vector3::new(q[at], q[at + 1], q[at + 2]);
                    m.r[b] = mm(&exp_small(&th), &cm::<T>(&self.body_rot0[b]));
                    m.v[b] = Vector3::new(nu[at], nu[at + 1], nu[at + 2]);
                    m.w[b] = Vector3::new(nu[at + 3], nu[at + 4], nu[at + 5]);
                    m.a[b] = Vector3::new(nud[at], nud[at + 1], nud[at + 2]);
                    m.al[b] = Vector3::new(nud[at + 3], nud[at + 4], nud[at + 5]);
                    for i in 0..3 {
                        let e = Vector3::ith(i, T::one());
                        m.cols[at + i] = (z, e, m.o[b]);
                        m.cols[at + 3 + i] = (e, z, m.o[b]);
                    }
                }
                Parent::Joint(j) => {
                    let jd = self.joints[j].as_ref().expect("tree joint");
                    let (o_p, r_p, v_p, w_p, a_p, al_p) = match jd.parent {
                        Some(p) => (m.o[p], m.r[p], m.v[p], m.w[p], m.a[p], m.al[p]),
                        None => (z, Matrix3::identity(), z, z, z, z),
                    };
                    let (mrel, tau, cols, bias_w) = self.local(j, jd, q, nu);
                    // frames aligned with their bodies (most URDF joints) need no product
                    let r_j = if jd.pf_r == Mat3::identity() {
                        r_p
                    } else {
                        mm(&r_p, &cm::<T>(&jd.pf_r))
                    };
                    let arm = mv(&r_p, &cv::<T>(&jd.pf_t));
                    let o_j = o_p + arm;
                    let v_j = v_p + w_p.cross(&arm);
                    let (mut w_rel, mut tau_d, mut w_acc, mut tau_acc) = (z, z, bias_w, z);
                    for (k, (ak, bk)) in cols.iter().enumerate() {
                        let nk = nu[jd.at + k];
                        w_rel += ak * nk;
                        tau_d += bk * nk;
                        if acc {
                            let ndk = nud[jd.at + k];
                            w_acc += ak * ndk;
                            tau_acc += bk * ndk;
                        }
                    }
                    let tau_w = mv(&r_j, &tau);
                    let tau_dw = mv(&r_j, &tau_d);
                    let r_c = mm(&r_j, &mrel);
                    let o_c = o_j + tau_w;
                    let w_rel_w = mv(&r_j, &w_rel);
                    let w_c = w_p + w_rel_w;
                    let v_c = v_j + w_p.cross(&tau_w) + tau_dw;
                    let r_b = if jd.cf_r == Mat3::identity() {
                        r_c
                    } else {
                        mm(&r_c, &cm::<T>(&jd.cf_r.transpose()))
                    };
                    let o_b = o_c - mv(&r_b, &cv::<T>(&jd.cf_t));
                    let arm2 = o_b - o_c;
                    m.o[b] = o_b;
                    m.r[b] = r_b;
                    m.w[b] = w_c;
                    m.v[b] = v_c + w_c.cross(&arm2);
                    if acc {
                        let a_j = a_p + al_p.cross(&arm) + w_p.cross(&w_p.cross(&arm));
                        let al_c = al_p + w_p.cross(&w_rel_w) + mv(&r_j, &w_acc);
                        let a_c = a_j
                            + al_p.cross(&tau_w)
                            + w_p.cross(&w_p.cross(&tau_w))
                            + w_p.cross(&tau_dw) * c::<T>(2.0)
                            + mv(&r_j, &tau_acc);
                        m.al[b] = al_c;
                        m.a[b] = a_c + al_c.cross(&arm2) + w_c.cross(&w_c.cross(&arm2));
                    }
                    for (k, (ak, bk)) in cols.iter().enumerate() {
                        m.cols[jd.at + k] = (mv(&r_j, ak), mv(&r_j, bk), o_c);
                    }
                }
            }
        }
        m
    }

    /// Centres of mass of every body, body frames, m.
    pub(crate) fn body_coms(&self) -> &[Vec3] {
        &self.com
    }

    /// The touching points and friction bristles of the operating point (`sticking`).
    #[must_use]
    pub fn sticking(&self) -> &Sticking {
        &self.sticking
    }

    /// Sets the touching points and friction bristles of the operating point.
    pub fn set_sticking(&mut self, s: Sticking) {
        self.sticking = s;
    }

    /// The bristles' rates `σ̇` at `(q, ν)` (`sticking`).
    pub fn bristle_rates<T: Real>(&self, q: &[T], nu: &[T]) -> Vec<T> {
        if self.sticking.n() == 0 {
            return Vec::new();
        }
        let m = self.motion(q, nu, None);
        self.sticking.rates(&self.com, &m, nu)
    }

    /// Mass of body `b`, kg.
    pub(crate) fn body_mass(&self, b: usize) -> f64 {
        self.mass[b]
    }

    /// Inertia of body `b` about its centre of mass, body axes, kg·m².
    pub(crate) fn body_inertia<T: Real>(&self, b: usize) -> Matrix3<T> {
        cm::<T>(&self.inertia[b])
    }

    /// Centre of mass of body `b` (world) and its velocity, at `m`.
    pub(crate) fn com_of<T: Real>(&self, m: &Motion<T>, b: usize) -> (Vector3<T>, Vector3<T>) {
        let rc = mv(&m.r[b], &cv::<T>(&self.com[b]));
        (m.o[b] + rc, m.v[b] + m.w[b].cross(&rc))
    }

    /// World-frame inertia about the centre of mass.
    pub(crate) fn inertia_world<T: Real>(&self, m: &Motion<T>, b: usize) -> Matrix3<T> {
        mm(
            &mm(&m.r[b], &cm::<T>(&self.inertia[b])),
            &m.r[b].transpose(),
        )
    }

    /// The inverse-dynamics residual `Q(q, ν, ν̇) − Q_applied(q, ν, u)` (len `n`). With
    /// `inertial_only`, gravity, inputs, springs, dampers and stops are left out (then the
    /// residual is `M(q) ν̇ + C(q, ν) ν`). Touching contacts and joint friction load it with
    /// their bristles at the operating point's values (`sticking`).
    pub fn residual<T: Real>(
        &self,
        q: &[T],
        nu: &[T],
        nud: &[T],
        u: &[T],
        inertial_only: bool,
    ) -> Vec<T> {
        self.residual_with(q, nu, nud, u, &lift_sigma(&self.sticking), inertial_only)
    }

    /// [`TreeDynamics::residual`] with the bristles at `sigma` (`sticking`) instead of the
    /// operating point's.
    #[allow(clippy::too_many_lines)]
    pub fn residual_with<T: Real>(
        &self,
        q: &[T],
        nu: &[T],
        nud: &[T],
        u: &[T],
        sigma: &[T],
        inertial_only: bool,
    ) -> Vec<T> {
        let m = self.motion(q, nu, Some(nud));
        let nb = self.mass.len();
        let z = Vector3::<T>::zeros();
        let g = if inertial_only {
            z
        } else {
            cv::<T>(&self.gravity)
        };
        let (mut f, mut nn) = (vec![z; nb], vec![z; nb]);
        // applied external torques and forces (world), subtracted below
        let (mut fe, mut ne) = (vec![z; nb], vec![z; nb]);
        if !inertial_only {
            for &(b, i) in &self.torques {
                ne[b] += Vector3::new(u[i], u[i + 1], u[i + 2]);
            }
            for &(b, i) in &self.forces {
                fe[b] += Vector3::new(u[i], u[i + 1], u[i + 2]);
            }
            for jd in self.joints.iter().flatten() {
                if jd.kind != JointType::Spherical {
                    continue;
                }
                let r_j = mm(
                    &match jd.parent {
                        Some(p) => m.r[p],
                        None => Matrix3::identity(),
                    },
                    &cm::<T>(&jd.pf_r),
                );
                let w_a = jd.parent.map_or(z, |p| m.w[p]);
                let mut t = (m.w[jd.child] - w_a) * (-c::<T>(jd.damping));
                if let Some(i) = jd.input {
                    for k in 0..3 {
                        t += r_j.column(k).into_owned() * u[i + k];
                    }
                }
                ne[jd.child] += t;
                if let Some(p) = jd.parent {
                    ne[p] -= t;
                }
            }
            self.sticking
                .body_loads(&self.com, &m, sigma, &mut fe, &mut ne);
        }
        for b in 0..nb {
            let mass = c::<T>(self.mass[b]);
            let rc = mv(&m.r[b], &cv::<T>(&self.com[b]));
            let pg = m.o[b] + rc;
            let ag = m.a[b] + m.al[b].cross(&rc) + m.w[b].cross(&m.w[b].cross(&rc));
            let iw = self.inertia_world(&m, b);
            let fb = (ag - g) * mass - fe[b];
            let nb_ = mv(&iw, &m.al[b]) + m.w[b].cross(&mv(&iw, &m.w[b])) - ne[b];
            f[b] = fb;
            nn[b] = nb_ + pg.cross(&fb);
        }
        let mut res = self.generalized(&m, f, nn);
        // rotors: a ν̇ per coordinate
        for jd in self.joints.iter().flatten() {
            if jd.armature > 0.0 {
                for k in 0..jd.kind.dof() {
                    res[jd.at + k] += nud[jd.at + k] * c::<T>(jd.armature);
                }
            }
        }
        if !inertial_only {
            for jd in self.joints.iter().flatten() {
                if jd.kind == JointType::Spherical {
                    continue;
                }
                for k in 0..jd.kind.dof() {
                    res[jd.at + k] -= self.coord_load(jd, k, q[jd.at + k], nu[jd.at + k], u);
                }
            }
            self.sticking.joint_loads(nu, sigma, &mut res);
        }
        res
    }

    /// The applied generalized force on coordinate `k` of the non-spherical joint `jd` at its
    /// value `qk` (rad or m), rate `vk` (rad/s or m/s) and the inputs `u` (module formulas):
    /// `act − k q − c q̇ + stop(q, q̇) + Σ τ_A(u_A, q, q̇)`, N·m or N.
    fn coord_load<T: Real>(&self, jd: &JointData, k: usize, qk: T, vk: T, u: &[T]) -> T {
        let mut gen = -qk * c::<T>(jd.stiffness) - vk * c::<T>(jd.damping);
        if let Some(i) = jd.input {
            let (act, e) = (u[i + k], jd.effort);
            gen += if act > c::<T>(e) {
                c::<T>(e)
            } else if act < c::<T>(-e) {
                c::<T>(-e)
            } else {
                act
            };
        }
        if !jd.acts.is_empty() {
            gen += jd.acts.torque(&self.gains, u, qk, vk);
        }
        if let Some(st) = &jd.stops {
            let pu = qk - c::<T>(st.upper);
            let pw = c::<T>(st.lower) - qk;
            let pu = if pu > T::zero() { pu } else { T::zero() };
            let pw = if pw > T::zero() { pw } else { T::zero() };
            gen += (pw - pu) * c::<T>(st.stiffness) - (pu + pw) * vk * c::<T>(st.damping);
        }
        gen
    }

    /// The generalized forces `Q_k = ω_k · (N − p_k × F) + u_k · F` of body forces `f` and
    /// moments `n` about the world origin (per body, world frame), `F`, `N` the subtree totals
    /// (len `n`): `Σ_b J_bᵀ w_b` for the twist Jacobians `J_b` of the bodies.
    pub fn generalized<T: Real>(
        &self,
        m: &Motion<T>,
        mut f: Vec<Vector3<T>>,
        mut nn: Vec<Vector3<T>>,
    ) -> Vec<T> {
        for &b in self.order.iter().rev() {
            if let (_, Some(p)) = self.own_dofs(b) {
                let (fb, nb_) = (f[b], nn[b]);
                f[p] += fb;
                nn[p] += nb_;
            }
        }
        let mut res = vec![T::zero(); self.coords.len()];
        for k in 0..self.coords.len() {
            let b = self.body_of(k);
            let (wk, uk, pk) = &m.cols[k];
            res[k] = wk.dot(&(nn[b] - pk.cross(&f[b]))) + uk.dot(&f[b]);
        }
        res
    }

    /// The coordinate rates `q̇ = N(q) ν` (module formulas).
    pub fn qdot<T: Real>(&self, q: &[T], nu: &[T]) -> Vec<T> {
        let mut out = nu.to_vec();
        let half = c::<T>(0.5);
        let mut fix = |at: usize, sign: T| {
            let th = Vector3::new(q[at], q[at + 1], q[at + 2]);
            let w = Vector3::new(nu[at], nu[at + 1], nu[at + 2]);
            let d = th.cross(&w) * (half * sign);
            for i in 0..3 {
                out[at + i] += d[i];
            }
        };
        for jd in self.joints.iter().flatten() {
            if jd.kind == JointType::Spherical {
                fix(jd.at, T::one());
            }
        }
        for p in &self.parent_of {
            if let Parent::Free(at) = p {
                fix(at + 3, -T::one());
            }
        }
        out
    }

    /// The mechanical energy (module formula) at `(q, ν)`.
    pub fn energy<T: Real>(&self, q: &[T], nu: &[T]) -> T {
        let m = self.motion(q, nu, None);
        let g = cv::<T>(&self.gravity);
        let mut e = T::zero();
        for b in 0..self.mass.len() {
            let mass = c::<T>(self.mass[b]);
            let (pg, vg) = self.com_of(&m, b);
            let iw = self.inertia_world(&m, b);
            e += (vg.dot(&vg) * mass + m.w[b].dot(&mv(&iw, &m.w[b]))) * c::<T>(0.5)
                - pg.dot(&g) * mass;
        }
        for jd in self.joints.iter().flatten() {
            if jd.kind == JointType::Spherical {
                continue;
            }
            for k in 0..jd.kind.dof() {
                let qk = q[jd.at + k];
                let vk = nu[jd.at + k];
                e += qk * qk * c::<T>(0.5 * jd.stiffness) + vk * vk * c::<T>(0.5 * jd.armature);
                if let Some(st) = &jd.stops {
                    for p in [qk - c::<T>(st.upper), c::<T>(st.lower) - qk] {
                        if p > T::zero() {
                            e += p * p * c::<T>(0.5 * st.stiffness);
                        }
                    }
                }
            }
        }
        e
    }

    /// Linear momentum and angular momentum about the world origin at `(q, ν)`.
    pub fn momentum<T: Real>(&self, q: &[T], nu: &[T]) -> (Vector3<T>, Vector3<T>) {
        let m = self.motion(q, nu, None);
        let (mut p, mut l) = (Vector3::zeros(), Vector3::zeros());
        for b in 0..self.mass.len() {
            let mass = c::<T>(self.mass[b]);
            let (pg, vg) = self.com_of(&m, b);
            let iw = self.inertia_world(&m, b);
            p += vg * mass;
            l += pg.cross(&(vg * mass)) + mv(&iw, &m.w[b]);
        }
        (p, l)
    }

    /// Pose and twist of site `s` (world) at `m`: origin, rotation, velocity, angular velocity.
    pub fn site<T: Real>(
        &self,
        m: &Motion<T>,
        s: usize,
    ) -> (Vector3<T>, Matrix3<T>, Vector3<T>, Vector3<T>) {
        let (b, t, r) = &self.sites[s];
        let arm = mv(&m.r[*b], &cv::<T>(t));
        (
            m.o[*b] + arm,
            mm(&m.r[*b], &cm::<T>(r)),
            m.v[*b] + m.w[*b].cross(&arm),
            m.w[*b],
        )
    }

    /// Sets the operating orientation of spherical joint `j` (child joint frame → parent joint
    /// frame).
    pub fn set_joint_rot0(&mut self, j: usize, m: Mat3) {
        self.joint_rot0[j] = m;
    }

    /// Sets the operating orientation of free body `b` (world ← body).
    pub fn set_body_rot0(&mut self, b: usize, r: Mat3) {
        self.body_rot0[b] = r;
    }

    /// Whether joint `j` is spherical.
    #[must_use]
    pub fn is_spherical(&self, j: usize) -> bool {
        self.joints
            .get(j)
            .and_then(Option::as_ref)
            .is_some_and(|d| d.kind == JointType::Spherical)
    }

    /// The operating orientation of free body `b` (`R₀`, world ← body).
    #[must_use]
    pub fn body_rot0(&self, b: usize) -> Mat3 {
        self.body_rot0[b]
    }

    /// The operating orientation of spherical joint `j` (`M₀`).
    #[must_use]
    pub fn joint_rot0(&self, j: usize) -> Mat3 {
        self.joint_rot0[j]
    }

    /// The body that rate `k` moves (a joint's child, or the free body itself).
    fn body_of(&self, k: usize) -> usize {
        match self.coords[k] {
            Coord::Joint { joint, .. } => self.joints[joint].as_ref().expect("joint").child,
            Coord::Free { body, .. } => body,
        }
    }

    /// The rates of body `b`'s own joint (or free-body six), and the body its joint hangs on.
    fn own_dofs(&self, b: usize) -> (std::ops::Range<usize>, Option<usize>) {
        match self.parent_of[b] {
            Parent::Free(o) => (o..o + 6, None),
            Parent::Joint(j) => {
                let jd = self.joints[j].as_ref().expect("tree joint");
                (jd.at..jd.at + jd.kind.dof(), jd.parent)
            }
        }
    }

    /// The joint-space mass matrix by the composite-rigid-body algorithm in world coordinates
    /// (spatial vectors about the world origin: motion `S_k = (ω_k, u_k − ω_k × p_k)`, body
    /// inertia `[I_G + m ĉĉᵀ, m ĉ; m ĉᵀ, m I]` for the centre of mass `c`): composite inertias
    /// `I^c_b = I_b + Σ_children I^c`, then `M_ij = S_jᵀ I^c_{b(i)} S_i` for every rate `j` of
    /// `b(i)` and its ancestors. O(N·depth).
    #[must_use]
    pub fn mass_matrix(&self, q: &[f64]) -> nalgebra::DMatrix<f64> {
        self.mass_matrix_of(q)
    }

    /// [`TreeDynamics::mass_matrix`] in any scalar (dual numbers: its derivative).
    #[must_use]
    pub fn mass_matrix_of<T: Real>(&self, q: &[T]) -> nalgebra::DMatrix<T> {
        let mut mm = self.bodies_mass_matrix_of(q);
        for jd in self.joints.iter().flatten() {
            if jd.armature > 0.0 {
                for k in jd.at..jd.at + jd.kind.dof() {
                    mm[(k, k)] += c::<T>(jd.armature);
                }
            }
        }
        mm
    }

    /// The bodies' share of the mass matrix (without the rotors' armature): the metric of the
    /// outputs' M-orthogonal projection of the nodal velocities, whose kinetic energy is the
    /// bodies' (`minimal`'s read-off).
    #[must_use]
    pub fn bodies_mass_matrix_of<T: Real>(&self, q: &[T]) -> nalgebra::DMatrix<T> {
        type S6<T> = nalgebra::SMatrix<T, 6, 6>;
        type V6<T> = nalgebra::SVector<T, 6>;
        let n = self.coords.len();
        let zero = vec![T::zero(); n];
        let m = self.motion(q, &zero, None);
        let nb = self.mass.len();
        let mut ic = vec![S6::<T>::zeros(); nb];
        for b in 0..nb {
            let (cg, _) = self.com_of(&m, b);
            let iw = self.inertia_world(&m, b);
            ic[b] = super::spatial::inertia(c::<T>(self.mass[b]), &cg, &iw);
        }
        for &b in self.order.iter().rev() {
            if let (_, Some(p)) = self.own_dofs(b) {
                let child = ic[b];
                ic[p] += child;
            }
        }
        let col = |k: usize| -> V6<T> {
            let (w, u, p) = m.cols[k];
            let v = u - w.cross(&p);
            V6::<T>::new(w[0], w[1], w[2], v[0], v[1], v[2])
        };
        let mut mm = nalgebra::DMatrix::<T>::zeros(n, n);
        for b in 0..nb {
            let (own, _) = self.own_dofs(b);
            for i in own {
                let f = ic[b] * col(i);
                let mut at = Some(b);
                while let Some(k) = at {
                    let (dofs, parent) = self.own_dofs(k);
                    for j in dofs {
                        let v = col(j).dot(&f);
                        mm[(i, j)] = v;
                        mm[(j, i)] = v;
                    }
                    at = parent;
                }
            }
        }
        mm
    }

    /// The accelerations `ν̇` at `(q, ν, u)` (f64), with the mass matrix's LU.
    ///
    /// # Errors
    /// A message when the mass matrix is singular (a body without mass at the end of a chain).
    pub fn accelerations(
        &self,
        q: &[f64],
        nu: &[f64],
        u: &[f64],
    ) -> Result<(Vec<f64>, MassLu), String> {
        let n = self.coords.len();
        let zero = vec![0.0; n];
        let bias = self.residual(q, nu, &zero, u, false);
        let lu = self.mass_matrix(q).lu();
        let rhs = nalgebra::DVector::from_iterator(n, bias.iter().map(|x| -x));
        let acc = lu
            .solve(&rhs)
            .ok_or_else(|| "the joint-space mass matrix is singular".to_string())?;
        Ok((acc.iter().copied().collect(), lu))
    }
}

#[path = "tree_partials.rs"]
pub(crate) mod tree_partials;

#[path = "tree_tangent.rs"]
pub(crate) mod tree_tangent;

#[cfg(test)]
#[path = "tree_dynamics_tests.rs"]
mod tests;
