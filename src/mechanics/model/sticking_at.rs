//! The sticking bristles of an operating point (`sticking`'s module formulas): which ground
//! points touch at `q` (penetration `x > 0`), their bristles and the joints' read from the
//! state on the ground's tangent axes, and whether each sticks (`|F| ≤ 0.9 C`).
//!
//! ```text
//! touching:  x = h₀ + r − n·P(q) > 0        (P of `sticking`; x ≤ 0: no load, no state)
//! bristles:  σ = (t₁·s, t₂·s) per touching point with μ > 0, then the joints' s
//! sticking:  |F| ≤ 0.9 μ f  (contacts),  |F| ≤ 0.9 C  (joints)
//! ```

use super::contact::{pair_nodes, ContactRt};
use super::contact_law::YIELD;
use super::def::ModelDef;
use super::runtime::Model;
use super::sticking::{percent, tangent_axes, Sticking, Stuck, Touch};
use super::tree_dynamics::{TreeDynamics, Unsupported};
use crate::math::Vec3;

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
        let mut out = Sticking::default();
        if !ct.features.is_empty() {
            let (nodes, _) = td.nodal(q, &vec![0.0; q.len()]);
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
                let arm = mo.r[p.body] * (td.body_coms()[p.body] + p.x);
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
                    ground: k,
                    shape: def.contact.shapes[p.shape].name.clone(),
                    shape_index: p.shape,
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
                return Err(Unsupported::SphericalFriction(def.joints[j].name.clone()));
            }
            let dofs = def.joints[j].kind.dof();
            for k in 0..dofs {
                out.sigma0.push(fric[jt.fric0 + k]);
                out.joints.push(Stuck {
                    fric: jt.fric0 + k,
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
        let coms = td.body_coms();
        for t in &self.touches {
            let (_, f, fr, _) = self.point_loads(coms, &m, &self.sigma0, t);
            let name = || format!("contact.{} (point {})", t.shape, t.point + 1);
            if t.at.is_some() && !(f > 0.0 && fr.norm() <= YIELD * t.law.friction * f) {
                return Err(Unsupported::Sliding(
                    name(),
                    percent(fr.norm() / (t.law.friction * f)),
                ));
            }
        }
        // the loads, as the residual's negated terms
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
