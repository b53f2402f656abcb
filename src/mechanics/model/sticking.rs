//! Sticking contacts and joint friction in the minimal-coordinate dynamics (`tree_dynamics`):
//! the continuous-time limit of the step's laws (`contact_law`, `joint_friction`) at the
//! ground points that touch at an operating point and the joint coordinates with friction,
//! their bristles added to the state.
//!
//! Ground point `X` (body axes, from the centre of mass `c`) of radius `r`, ground `n·x = h₀`:
//!
//! ```text
//! P = o + R (c + X),   Ṗ = v + ω × R (c + X)                 (the point; a sphere's centre)
//! x = h₀ + r − n·P > 0,   ẋ = −n·Ṗ                            (penetration, its rate)
//! f = k x (1 + ψ(d ẋ))          normal force at P along n  (ψ of `contact_law`: the step's
//!                                 e(1 + ψ(d Δx/h)) as h → 0, e → k x)
//! C = P − r n,  v_C = v + ω × (R (c + X) − r n),  u̇ = v_C − n (n·v_C)   (the contact point)
//! s = σ₁ t₁ + σ₂ t₂              the bristle (t₁, t₂: the ground's tangent axes), a state
//! F = −k s − k d x u̇            friction at C (the step's F* = −k s* − c_t u/h, c_t = k d p̄)
//! σ̇ᵢ = tᵢ·v_C                   (sticking: the step's s₁ = s₀ + u)
//! ```
//!
//! Joint coordinate `q` with friction limit `C` (`k = C/δ`, `c = k τ`): bristle `s` (a state),
//! load `F = −k s − c q̇` on the coordinate, `ṡ = q̇`.
//!
//! Both hold while the bristle sticks, `|F| ≤ 0.9 C` (`C = μ f` for a contact): there the step
//! keeps `λ = 1` and nothing slides, so the laws are smooth. Where a bristle slides, the step's
//! anchor jumps by `2(1 − λ) s*` per step, which has no limit as `h → 0`: no continuous-time
//! model, refused. Points that do not touch (`x < 0`) carry no load, and their bristles are
//! reset by the step: not states. Body–body contacts are refused where they touch.
//! The active set and the tangent axes are those of the operating point.
//!
//! `t₁` is the world x axis projected on the ground (y if the normal is along x), `t₂ = n × t₁`:
//! for the default ground (`n = +z`), `σ₁`, `σ₂` are the bristle's x and y deflections (m).

use super::def::ContactLaw;
use super::joint_friction::{JointFriction, TIME_CONSTANT};
use super::motion::Motion;
use super::runtime::Model;
use super::scalar::{c, cv, mv, Real};
use crate::math::Vec3;
use nalgebra::Vector3;

/// A ground point touching at the operating point.
#[derive(Clone, Debug)]
pub(super) struct Touch {
    /// Its index among the ground points (`GroundRt::points`).
    pub(super) ground: usize,
    /// The shape's name and the point's index among the shape's points (0-based).
    pub(super) shape: String,
    /// Its index among the collision shapes.
    pub(super) shape_index: usize,
    pub(super) point: usize,
    pub(super) body: usize,
    /// Body axes, from the centre of mass, m.
    pub(super) x: Vec3,
    pub(super) radius: f64,
    pub(super) law: ContactLaw,
    /// Offset of its two bristle states in `σ` (`None`: no friction, μ = 0).
    pub(super) at: Option<usize>,
}

/// A joint coordinate with friction.
#[derive(Clone, Debug)]
pub(super) struct Stuck {
    /// Its bristle's index among the joint friction bristles (`JointRt::fric0`).
    pub(super) fric: usize,
    pub(super) joint: String,
    /// Its index in `q`, and among the joint's coordinates.
    pub(super) coord: usize,
    pub(super) k: usize,
    pub(super) dofs: usize,
    pub(super) friction: JointFriction,
    /// Offset of its bristle state in `σ`.
    pub(super) at: usize,
}

/// The sticking bristles and touching points of an operating point (module formulas).
#[derive(Clone, Debug, Default)]
pub struct Sticking {
    pub(super) normal: Vec3,
    pub(super) height: f64,
    pub(super) tangents: [Vec3; 2],
    pub(super) touches: Vec<Touch>,
    pub(super) joints: Vec<Stuck>,
    /// `σ` at the operating point: contact bristles (2 per point with friction), then joint
    /// bristles (1 per coordinate), m or rad.
    pub(super) sigma0: Vec<f64>,
}

/// `ψ(z)` of `contact_law`, in any scalar.
fn psi<T: Real>(z: T) -> T {
    if z >= c::<T>(-0.5) {
        z
    } else {
        (z * c::<T>(2.0) + T::one()).exp() * c::<T>(0.5) - T::one()
    }
}

/// The ground's tangent axes (module docs).
pub(super) fn tangent_axes(n: &Vec3) -> [Vec3; 2] {
    let pick = if n.x.abs() < 0.9 {
        Vec3::x()
    } else {
        Vec3::y()
    };
    let t1 = (pick - n * n.dot(&pick)).normalize();
    [t1, n.cross(&t1)]
}

impl Sticking {
    /// Number of bristle states `σ`.
    #[must_use]
    pub fn n(&self) -> usize {
        self.sigma0.len()
    }

    /// Whether nothing touches and no joint has friction.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.touches.is_empty() && self.joints.is_empty()
    }

    /// `σ` at the operating point.
    #[must_use]
    pub fn sigma0(&self) -> &[f64] {
        &self.sigma0
    }

    /// Moves the operating point's bristles to `sigma` (len [`Sticking::n`]).
    pub fn set_sigma0(&mut self, sigma: &[f64]) {
        self.sigma0.copy_from_slice(sigma);
    }

    /// The contact bristles' states in `σ` order: the ground point (`GroundRt::points`) and
    /// the tangent axis its component lies along (world, unit).
    #[must_use]
    pub fn contact_axes(&self) -> Vec<(usize, Vec3)> {
        self.touches
            .iter()
            .filter(|t| t.at.is_some())
            .flat_map(|t| self.tangents.iter().map(move |a| (t.ground, *a)))
            .collect()
    }

    /// The joint friction bristles' states in `σ` order (after the contacts'): their indices
    /// among the joint friction bristles (`State::joint_bristles`).
    #[must_use]
    pub fn joint_bristles(&self) -> Vec<usize> {
        self.joints.iter().map(|s| s.fric).collect()
    }

    /// The ground points (`GroundRt::points`) that touch, with friction or without.
    #[must_use]
    pub fn touching(&self) -> Vec<usize> {
        self.touches.iter().map(|t| t.ground).collect()
    }

    /// The names of `σ`: `contact.C.s[i]` (a shape with one point) or `contact.C.s[k,i]` (point
    /// k of C), then `joint.J.s` or `joint.J.s[k]`; 1-based.
    #[must_use]
    pub fn names(&self, model: &Model) -> Vec<String> {
        let def = model.def();
        let mut out = Vec::with_capacity(self.n());
        for t in &self.touches {
            if t.at.is_none() {
                continue;
            }
            let single = matches!(
                def.contact.shapes[t.shape_index].kind,
                super::def::ShapeKind::Sphere { .. }
            );
            for i in 1..=2 {
                out.push(if single {
                    format!("contact.{}.s[{i}]", t.shape)
                } else {
                    format!("contact.{}.s[{},{i}]", t.shape, t.point + 1)
                });
            }
        }
        for s in &self.joints {
            out.push(if s.dofs == 1 {
                format!("joint.{}.s", s.joint)
            } else {
                format!("joint.{}.s[{}]", s.joint, s.k + 1)
            });
        }
        out
    }

    /// Per touching point (bodies' centres of mass `coms`, body frames): the arm `R (c + X)`, the normal force `f` and the friction `F` (world)
    /// at `m` with bristles `sigma`, and the contact point's arm `R (c + X) − r n`.
    pub(super) fn point_loads<T: Real>(
        &self,
        coms: &[Vec3],
        m: &Motion<T>,
        sigma: &[T],
        t: &Touch,
    ) -> (Vector3<T>, T, Vector3<T>, Vector3<T>) {
        let n = cv::<T>(&self.normal);
        let (k, d) = (c::<T>(t.law.stiffness), c::<T>(t.law.damping));
        let arm = mv(&m.r[t.body], &cv::<T>(&(coms[t.body] + t.x)));
        let p = m.o[t.body] + arm;
        let pdot = m.v[t.body] + m.w[t.body].cross(&arm);
        let x = c::<T>(self.height + t.radius) - n.dot(&p);
        let xdot = T::zero() - n.dot(&pdot);
        let f = k * x * (T::one() + psi(d * xdot));
        let carm = arm - n * c::<T>(t.radius);
        let Some(at) = t.at else {
            return (arm, f, Vector3::zeros(), carm);
        };
        let vc = m.v[t.body] + m.w[t.body].cross(&carm);
        let ut = vc - n * n.dot(&vc);
        let s = cv::<T>(&self.tangents[0]) * sigma[at] + cv::<T>(&self.tangents[1]) * sigma[at + 1];
        let fr = (s * k + ut * (k * d * x)) * (T::zero() - T::one());
        (arm, f, fr, carm)
    }

    /// Adds the contact loads at `m` with bristles `sigma` to the applied forces `fe` (at the
    /// centres of mass) and moments `ne` (about them), world frame, per body.
    pub(crate) fn body_loads<T: Real>(
        &self,
        coms: &[Vec3],
        m: &Motion<T>,
        sigma: &[T],
        fe: &mut [Vector3<T>],
        ne: &mut [Vector3<T>],
    ) {
        let n = cv::<T>(&self.normal);
        for t in &self.touches {
            let (arm, f, fr, carm) = self.point_loads(coms, m, sigma, t);
            let b = t.body;
            // arms from the frame origin less the centre of mass's: R X, R X − r n
            let rc = mv(&m.r[b], &cv::<T>(&coms[b]));
            fe[b] += n * f + fr;
            ne[b] += (arm - rc).cross(&(n * f)) + (carm - rc).cross(&fr);
        }
    }

    /// The ground's force on collision shape `shape`'s body through it: its touching points'
    /// `f n + F` at `m` with bristles `sigma` (world, N; zero where it does not touch).
    pub(crate) fn shape_force<T: Real>(
        &self,
        coms: &[Vec3],
        m: &Motion<T>,
        sigma: &[T],
        shape: usize,
    ) -> Vector3<T> {
        let n = cv::<T>(&self.normal);
        self.touches
            .iter()
            .filter(|t| t.shape_index == shape)
            .fold(Vector3::zeros(), |acc, t| {
                let (_, f, fr, _) = self.point_loads(coms, m, sigma, t);
                acc + n * f + fr
            })
    }

    /// Subtracts the joint friction loads `−k s − c q̇` from the residual `res` (len `n`, one
    /// per coordinate), at rates `nu`.
    pub(crate) fn joint_loads<T: Real>(&self, nu: &[T], sigma: &[T], res: &mut [T]) {
        for s in &self.joints {
            let k = s.friction.stiffness();
            res[s.coord] += sigma[s.at] * c::<T>(k) + nu[s.coord] * c::<T>(k * TIME_CONSTANT);
        }
    }

    /// The bristles' rates `σ̇` at `m` (module formulas).
    pub(crate) fn rates<T: Real>(&self, coms: &[Vec3], m: &Motion<T>, nu: &[T]) -> Vec<T> {
        let mut out = vec![T::zero(); self.n()];
        let n = cv::<T>(&self.normal);
        for t in &self.touches {
            let Some(at) = t.at else { continue };
            let carm = mv(&m.r[t.body], &cv::<T>(&(coms[t.body] + t.x))) - n * c::<T>(t.radius);
            let vc = m.v[t.body] + m.w[t.body].cross(&carm);
            for i in 0..2 {
                out[at + i] = cv::<T>(&self.tangents[i]).dot(&vc);
            }
        }
        for s in &self.joints {
            out[s.at] = nu[s.coord];
        }
        out
    }
}

/// `r` in percent, for messages (a pulling contact, `r` not finite: 100 %+).
#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
pub(super) fn percent(r: f64) -> u32 {
    if r.is_finite() {
        (100.0 * r).round().clamp(0.0, 1e6) as u32
    } else {
        1_000_000
    }
}

/// `x` as a scalar `T`, for the bristles at the operating point.
pub(crate) fn lift_sigma<T: Real>(s: &Sticking) -> Vec<T> {
    s.sigma0.iter().map(|&x| c::<T>(x)).collect()
}
