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

use super::contact::{pair_nodes, ContactRt};
use super::contact_law::YIELD;
use super::def::{ContactLaw, ModelDef};
use super::joint_friction::{JointFriction, TIME_CONSTANT};
use super::runtime::Model;
use super::tree_dynamics::{c, mv, Motion, Real, TreeDynamics, Unsupported};
use crate::math::Vec3;
use nalgebra::Vector3;

/// A ground point touching at the operating point.
#[derive(Clone, Debug)]
struct Touch {
    /// The shape's name and the point's index among the shape's points (0-based).
    shape: String,
    point: usize,
    body: usize,
    /// Body axes, from the centre of mass, m.
    x: Vec3,
    radius: f64,
    law: ContactLaw,
    /// Offset of its two bristle states in `σ` (`None`: no friction, μ = 0).
    at: Option<usize>,
}

/// A joint coordinate with friction.
#[derive(Clone, Debug)]
struct Stuck {
    joint: String,
    /// Its index in `q`, and among the joint's coordinates.
    coord: usize,
    k: usize,
    dofs: usize,
    friction: JointFriction,
    /// Offset of its bristle state in `σ`.
    at: usize,
}

/// The sticking bristles and touching points of an operating point (module formulas).
#[derive(Clone, Debug, Default)]
pub struct Sticking {
    normal: Vec3,
    height: f64,
    tangents: [Vec3; 2],
    touches: Vec<Touch>,
    joints: Vec<Stuck>,
    /// `σ` at the operating point: contact bristles (2 per point with friction), then joint
    /// bristles (1 per coordinate), m or rad.
    sigma0: Vec<f64>,
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
fn tangent_axes(n: &Vec3) -> [Vec3; 2] {
    let pick = if n.x.abs() < 0.9 {
        Vec3::x()
    } else {
        Vec3::y()
    };
    let t1 = (pick - n * n.dot(&pick)).normalize();
    [t1, n.cross(&t1)]
}

fn cv<T: Real>(v: &Vec3) -> Vector3<T> {
    v.map(c)
}

impl Sticking {
    /// The touching points and bristles of `model` at `(q, ν)` (`td`'s coordinates), with the
    /// state's contact bristles `bristle` (3 per ground point, world) and joint bristles `fric`
    /// (`JointRt::fric0`). Friction is not yet checked ([`Sticking::check`]).
    ///
    /// # Errors
    /// [`Unsupported::Touching`] when two bodies' shapes touch at `q`.
    pub(crate) fn at(
        td: &TreeDynamics,
        model: &Model,
        q: &[f64],
        bristle: &[f64],
        fric: &[f64],
    ) -> Result<Self, Unsupported> {
        let def: &ModelDef = model.def();
        let ct: &ContactRt = &model.contact;
        let mo = td.motion(q, &vec![0.0; q.len()], None);
        let mut out = Self::default();
        if !ct.features.is_empty() {
            // the nodes of every body at q: centre of mass and directors
            let mut nodes = vec![0.0; 12 * td.n_bodies()];
            for b in 0..td.n_bodies() {
                let (pg, _) = td.com_of(&mo, b);
                for i in 0..3 {
                    nodes[12 * b + i] = pg[i];
                    for k in 0..3 {
                        nodes[12 * b + 3 * (k + 1) + i] = mo.r[b][(i, k)];
                    }
                }
            }
            for f in &ct.features {
                let (qa, qb) = pair_nodes(&nodes, f);
                if f.gap(&f.invariants(&qa, &qb)) < 0.0 {
                    return Err(Unsupported::Touching(
                        def.contact.shapes[f.shapes.0].name.clone(),
                        def.contact.shapes[f.shapes.1].name.clone(),
                    ));
                }
            }
        }
        let mut at = 0;
        if let Some(g) = &ct.ground {
            out.normal = g.normal;
            out.height = g.height;
            out.tangents = tangent_axes(&g.normal);
            let mut seen = vec![0; def.contact.shapes.len()];
            for (k, p) in g.points.iter().enumerate() {
                let point = seen[p.shape];
                seen[p.shape] += 1;
                let arm = mo.r[p.body] * (td.body_com(p.body) + p.x);
                let x = g.height + p.radius - g.normal.dot(&(mo.o[p.body] + arm));
                if x <= 0.0 {
                    continue;
                }
                let friction = p.law.friction > 0.0;
                if friction {
                    let s = Vec3::new(bristle[3 * k], bristle[3 * k + 1], bristle[3 * k + 2]);
                    out.sigma0.extend(out.tangents.iter().map(|t| t.dot(&s)));
                }
                out.touches.push(Touch {
                    shape: def.contact.shapes[p.shape].name.clone(),
                    point,
                    body: p.body,
                    x: p.x,
                    radius: p.radius,
                    law: p.law,
                    at: friction.then_some(at),
                });
                if friction {
                    at += 2;
                }
            }
        }
        for (j, jt) in model.joints.iter().enumerate() {
            let (Some(fr), Some(coord)) = (jt.friction, td.joint_at(j)) else {
                continue;
            };
            if td.is_spherical(j) {
                continue;
            }
            let dofs = def.joints[j].kind.dof();
            for k in 0..dofs {
                out.sigma0.push(fric[jt.fric0 + k]);
                out.joints.push(Stuck {
                    joint: def.joints[j].name.clone(),
                    coord: coord + k,
                    k,
                    dofs,
                    friction: fr,
                    at,
                });
                at += 1;
            }
        }
        Ok(out)
    }

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
            let single = def
                .contact
                .shapes
                .iter()
                .find(|s| s.name == t.shape)
                .is_some_and(|s| matches!(s.kind, super::def::ShapeKind::Sphere { .. }));
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

    /// Per touching point: the arm `R (c + X)`, the normal force `f` and the friction `F` (world)
    /// at `m` with bristles `sigma`, and the contact point's arm `R (c + X) − r n`.
    fn point_loads<T: Real>(
        &self,
        td: &TreeDynamics,
        m: &Motion<T>,
        sigma: &[T],
        t: &Touch,
    ) -> (Vector3<T>, T, Vector3<T>, Vector3<T>) {
        let n = cv::<T>(&self.normal);
        let (k, d) = (c::<T>(t.law.stiffness), c::<T>(t.law.damping));
        let arm = mv(&m.r[t.body], &cv::<T>(&(td.body_com(t.body) + t.x)));
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
        td: &TreeDynamics,
        m: &Motion<T>,
        sigma: &[T],
        fe: &mut [Vector3<T>],
        ne: &mut [Vector3<T>],
    ) {
        let n = cv::<T>(&self.normal);
        for t in &self.touches {
            let (arm, f, fr, carm) = self.point_loads(td, m, sigma, t);
            let b = t.body;
            // arms from the frame origin less the centre of mass's: R X, R X − r n
            let rc = mv(&m.r[b], &cv::<T>(&td.body_com(b)));
            fe[b] += n * f + fr;
            ne[b] += (arm - rc).cross(&(n * f)) + (carm - rc).cross(&fr);
        }
    }

    /// The joint friction loads `−k s − c q̇` per coordinate of `q` (len `n`), at rates `nu`.
    pub(crate) fn joint_loads<T: Real>(&self, nu: &[T], sigma: &[T], out: &mut [T]) {
        for s in &self.joints {
            let k = s.friction.stiffness();
            out[s.coord] -= sigma[s.at] * c::<T>(k) + nu[s.coord] * c::<T>(k * TIME_CONSTANT);
        }
    }

    /// The bristles' rates `σ̇` at `m` (module formulas).
    pub(crate) fn rates<T: Real>(&self, td: &TreeDynamics, m: &Motion<T>, nu: &[T]) -> Vec<T> {
        let mut out = vec![T::zero(); self.n()];
        let n = cv::<T>(&self.normal);
        for t in &self.touches {
            let Some(at) = t.at else { continue };
            let carm =
                mv(&m.r[t.body], &cv::<T>(&(td.body_com(t.body) + t.x))) - n * c::<T>(t.radius);
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

    /// Whether every bristle sticks at `(q, ν)` with `σ₀` (module docs).
    ///
    /// # Errors
    /// [`Unsupported::Sliding`] naming the first that slides (or a contact pulling apart).
    pub(crate) fn check(
        &self,
        td: &TreeDynamics,
        q: &[f64],
        nu: &[f64],
    ) -> Result<(), Unsupported> {
        let m = td.motion(q, nu, None);
        for t in &self.touches {
            let (_, f, fr, _) = self.point_loads(td, &m, &self.sigma0, t);
            let name = || format!("contact.{} (point {})", t.shape, t.point + 1);
            if t.at.is_some() && !(f > 0.0 && fr.norm() <= YIELD * t.law.friction * f) {
                return Err(Unsupported::Sliding(
                    name(),
                    percent(fr.norm() / (t.law.friction * f)),
                ));
            }
        }
        let mut gen = vec![0.0; q.len()];
        self.joint_loads(nu, &self.sigma0, &mut gen);
        for s in &self.joints {
            let r = gen[s.coord].abs() / s.friction.limit;
            if r > YIELD {
                let name = if s.dofs == 1 {
                    format!("joint.{}", s.joint)
                } else {
                    format!("joint.{} (coordinate {})", s.joint, s.k + 1)
                };
                return Err(Unsupported::Sliding(name, percent(r)));
            }
        }
        Ok(())
    }
}

/// `r` in percent, for messages (a pulling contact, `r` not finite: 100 %+).
#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
fn percent(r: f64) -> u32 {
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
