//! Joint geometry: the constraint rows, the invariants of the joint coordinates and the
//! coordinates/rates of one lower pair (theory.md §3.2–§3.3), built from [`DotRow`]s.
//!
//! Frames. The user's joint frame sits at `parent_frame` in the parent body frame (or the world)
//! and at `child_frame` in the child body frame; at q = 0 they coincide (URDF). Internally the
//! joint frame is rotated by an orthonormal `S` (the [`JointGeom::frame`]) so that its third
//! axis is the joint axis (`S e₃ = axis`); universal: `S = [axis, axis2, axis × axis2]`;
//! spherical and fixed: `S = I`. The parent's rotated joint-frame axes (world frame) are
//! `a_k = Σ_i (R_pf S)_{ik} dᴬ_i`, the child's `b_k = Σ_i (R_cf S)_{ik} dᴮ_i`; the joint
//! points are `p_A = φᴬ + Σ Xᴬ_i dᴬ_i` (`Xᴬ = parent_frame.translation − comᴬ`; world:
//! the constant `parent_frame.translation`) and `p_B` likewise; `r = p_B − p_A`.
//! Then `[a]ᵀ[b] = Sᵀ M S` where `M` is the joint motion in the user's joint frame.

use super::constraint::{DotRow, LinVec, Nodes, NODES};
use super::def::{BodyDef, JointDef, JointType};
use super::error::ModelError;
use crate::math::{matrix_to_quat, skew, Mat3, Vec3};

/// How one joint coordinate acts: the handle for actuators, springs and dampers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Dof {
    /// A translational coordinate (m) as its invariant `s = r·a_k`; a force `F` along it acts
    /// through `F ∇s` (midpoint gradient: exact discrete gradient).
    Slide(DotRow),
    /// A rotational coordinate (rad) about the world axis `n` (linear in the nodes); its torque
    /// `τ` acts as `+τ n` on the child and `−τ n` on the parent.
    Turn(LinVec),
}

/// Geometry of one joint between a parent (body or world) and a child body.
#[derive(Clone, Debug, PartialEq)]
pub struct JointGeom {
    /// Parent body index, `None` for the world.
    pub parent: Option<usize>,
    /// Child body index.
    pub child: usize,
    /// Pair type.
    pub kind: JointType,
    /// `S`: rotation user joint frame ← internal joint frame (columns in the user's joint frame).
    pub frame: Mat3,
    /// Constraint rows `g = 0` (order of the table in ARCHITECTURE.md), node order `[A…, B…]`.
    pub rows: Vec<DotRow>,
    /// One handle per degree of freedom, in the order of [`JointType::dof`]; spherical: turns
    /// about the parent joint-frame axes `a1, a2, a3`.
    pub dofs: Vec<Dof>,
    /// `r = p_B − p_A`, world frame, m.
    pub r: LinVec,
    /// Parent joint-frame axes `a1, a2, a3`, world frame.
    pub a: [LinVec; 3],
    /// Child joint-frame axes `b1, b2, b3`, world frame.
    pub b: [LinVec; 3],
}

/// The constant nodes of the world: `[0, e1, e2, e3]`.
#[must_use]
pub fn world_nodes() -> Nodes {
    [Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::z()]
}

/// Nodes of `body` in the system coordinates `q` (12 per body); the world's for `None`.
#[must_use]
pub fn body_nodes(q: &[f64], body: Option<usize>) -> Nodes {
    match body {
        Some(k) => super::constraint::nodes(&q[12 * k..12 * k + 12]),
        None => world_nodes(),
    }
}

/// Node velocities of `body` in the system velocities `v` (12 per body); zeros for the world.
#[must_use]
pub fn body_rates(v: &[f64], body: Option<usize>) -> Nodes {
    match body {
        Some(k) => super::constraint::nodes(&v[12 * k..12 * k + 12]),
        None => [Vec3::zeros(); NODES],
    }
}

/// Orthonormal `S` with `S e₃ = n` (n unit): the cyclic permutation for a coordinate axis
/// (`±e1 → [e2, ±e3, ±e1]`, `±e2 → [e3, ±e1, ±e2]`, `e3 → I`), else the least rotation
/// taking `e₃` to `n` (via `−n` when `n_z < 0`).
///
/// A coordinate axis is one whose other two components are exactly zero: an axis tilted by
/// t < 1.5e-8 rad normalises to a component of exactly ±1 while its others are ≈ t, and the
/// permutation frame beside it would be off by t (non-orthonormal bodies below the joint).
#[must_use]
pub fn axis_frame(n: &Vec3) -> Mat3 {
    for k in 0..3 {
        if n[k].abs() == 1.0 && n[(k + 1) % 3] == 0.0 && n[(k + 2) % 3] == 0.0 {
            let s = n[k];
            let (e1, e2) = (Vec3::ith((k + 1) % 3, 1.0), Vec3::ith((k + 2) % 3, s));
            return Mat3::from_columns(&[e1, e2, *n]);
        }
    }
    let least = |m: &Vec3| -> Mat3 {
        let k = skew(&Vec3::z().cross(m));
        Mat3::identity() + k + k * k / (1.0 + m.z)
    };
    if n.z >= 0.0 {
        least(n)
    } else {
        least(&-n) * Mat3::from_diagonal(&Vec3::new(1.0, -1.0, -1.0))
    }
}

/// The internal joint frame `S` of `def` (see the module docs).
///
/// # Errors
/// [`ModelError::Invalid`] for a zero or non-finite axis, or a universal `axis2` not
/// perpendicular to `axis` (|cos| > 1e-6).
pub fn joint_frame(def: &JointDef) -> Result<Mat3, ModelError> {
    let bad = |what: &str| ModelError::Invalid(format!("joint '{}': {what}", def.name));
    let unit = |v: &Vec3, what: &str| -> Result<Vec3, ModelError> {
        let n = v.norm();
        if n.is_finite() && n > 1e-12 {
            Ok(v / n)
        } else {
            Err(bad(&format!("{what} must be a non-zero finite vector")))
        }
    };
    match def.kind {
        JointType::Spherical | JointType::Fixed => Ok(Mat3::identity()),
        JointType::Universal => {
            let u1 = unit(&def.axis, "axis")?;
            let u2 = unit(&def.axis2, "axis2")?;
            if u1.dot(&u2).abs() > 1e-6 {
                return Err(bad("axis2 must be perpendicular to axis"));
            }
            let u2 = (u2 - u1 * u1.dot(&u2)).normalize();
            Ok(Mat3::from_columns(&[u1, u2, u1.cross(&u2)]))
        }
        _ => Ok(axis_frame(&unit(&def.axis, "axis")?)),
    }
}

/// Checks that a frame rotation is finite, orthonormal and right-handed (to 1e-9).
///
/// # Errors
/// [`ModelError::Invalid`] naming `what` otherwise.
pub fn check_rotation(r: &Mat3, what: &str) -> Result<(), ModelError> {
    if r.iter().all(|x| x.is_finite())
        && (r.transpose() * r - Mat3::identity()).amax() < 1e-9
        && r.determinant() > 0.0
    {
        Ok(())
    } else {
        Err(ModelError::Invalid(format!(
            "{what}: rotation is not orthonormal and right-handed"
        )))
    }
}

impl JointGeom {
    /// Builds the rows and dof handles of `def` over `bodies`.
    ///
    /// # Errors
    /// [`ModelError::Invalid`] for body indices out of range, parent = child, a frame that is
    /// not a rigid placement, or a degenerate axis (see [`joint_frame`]).
    pub fn new(def: &JointDef, bodies: &[BodyDef]) -> Result<Self, ModelError> {
        let bad = |what: &str| ModelError::Invalid(format!("joint '{}': {what}", def.name));
        let child = bodies
            .get(def.child)
            .ok_or_else(|| bad("child body index out of range"))?;
        if def.parent == Some(def.child) {
            return Err(bad("parent and child are the same body"));
        }
        for (frame, side) in [(&def.parent_frame, "parent"), (&def.child_frame, "child")] {
            check_rotation(
                &frame.rotation,
                &format!("joint '{}' {side} frame", def.name),
            )?;
            if !frame.translation.iter().all(|x| x.is_finite()) {
                return Err(bad(&format!("{side} frame translation must be finite")));
            }
        }
        let s = joint_frame(def)?;
        let ca = def.parent_frame.rotation * s;
        let cb = def.child_frame.rotation * s;
        let (a, p_a) = match def.parent {
            Some(k) => {
                let parent = bodies
                    .get(k)
                    .ok_or_else(|| bad("parent body index out of range"))?;
                let x = def.parent_frame.translation - parent.com;
                (
                    std::array::from_fn(|k| LinVec::axis_a(&ca.column(k).into_owned())),
                    LinVec::point_a(&x),
                )
            }
            None => (
                std::array::from_fn(|k| LinVec::constant(ca.column(k).into_owned())),
                LinVec::constant(def.parent_frame.translation),
            ),
        };
        let b: [LinVec; 3] = std::array::from_fn(|k| LinVec::axis_b(&cb.column(k).into_owned()));
        let r = LinVec::point_b(&(def.child_frame.translation - child.com)).sub(&p_a);
        let dot = |u: LinVec, w: LinVec| DotRow::new(u, w, 0.0);
        let point: Vec<DotRow> = (0..3)
            .map(|k| DotRow::component(r, Vec3::ith(k, 1.0)))
            .collect();
        let axial = [dot(a[2], b[0]), dot(a[2], b[1])];
        let mut rows = Vec::new();
        let mut dofs = Vec::new();
        match def.kind {
            JointType::Spherical => {
                rows.extend(&point);
                dofs.extend(a.iter().map(|n| Dof::Turn(*n)));
            }
            JointType::Revolute => {
                rows.extend(point.iter().chain(&axial));
                dofs.push(Dof::Turn(a[2]));
            }
            JointType::Cylindrical | JointType::Prismatic => {
                rows.extend([dot(r, a[0]), dot(r, a[1])].iter().chain(&axial));
                dofs.push(Dof::Slide(dot(r, a[2])));
                if def.kind == JointType::Prismatic {
                    rows.push(dot(a[0], b[1]));
                } else {
                    dofs.push(Dof::Turn(a[2]));
                }
            }
            JointType::Universal => {
                rows.extend(&point);
                rows.push(dot(a[0], b[1]));
                dofs.extend([Dof::Turn(a[0]), Dof::Turn(b[1])]);
            }
            JointType::Planar => {
                rows.push(dot(r, a[2]));
                rows.extend(&axial);
                dofs.extend([
                    Dof::Slide(dot(r, a[0])),
                    Dof::Slide(dot(r, a[1])),
                    Dof::Turn(a[2]),
                ]);
            }
            JointType::Fixed => {
                rows.extend(&point);
                rows.extend([dot(a[0], b[1]), dot(a[1], b[2]), dot(a[2], b[0])]);
            }
        }
        Ok(Self {
            parent: def.parent,
            child: def.child,
            kind: def.kind,
            frame: s,
            rows,
            dofs,
            r,
            a,
            b,
        })
    }

    /// The invariants `(s, c)` with `atan2(s, c)` = the `k`-th coordinate, for rotational
    /// coordinates (the angles of [`JointGeom::coords`]: `s`, `c` are entries of `[a]ᵀ[b]`);
    /// `None` for slides and spherical joints.
    #[must_use]
    pub fn angle_rows(&self, k: usize) -> Option<(DotRow, DotRow)> {
        let ab = |i: usize, j: usize| DotRow::new(self.a[i], self.b[j], 0.0);
        match (self.kind, k) {
            (JointType::Revolute, 0) | (JointType::Cylindrical, 1) | (JointType::Planar, 2) => {
                Some((ab(1, 0), ab(0, 0)))
            }
            (JointType::Universal, 0) => Some((ab(2, 1), ab(1, 1))),
            (JointType::Universal, 1) => Some((ab(0, 2), ab(0, 0))),
            _ => None,
        }
    }

    /// The axes `[a]` and `[b]` (columns, world frame) at nodes `qa`, `qb`.
    #[must_use]
    pub fn axes(&self, qa: &Nodes, qb: &Nodes) -> (Mat3, Mat3) {
        let ev = |v: &[LinVec; 3]| {
            Mat3::from_columns(&[v[0].eval(qa, qb), v[1].eval(qa, qb), v[2].eval(qa, qb)])
        };
        (ev(&self.a), ev(&self.b))
    }

    /// Joint coordinates at nodes `qa` (parent; [`world_nodes`] for the world) and `qb`,
    /// `out.len() == kind.nq()`: angles (rad) wrapped to (−π, π], slides (m); spherical: the
    /// quaternion `[w, x, y, z]` (w ≥ 0) of the child joint frame relative to the parent's.
    pub fn coords(&self, qa: &Nodes, qb: &Nodes, out: &mut [f64]) {
        let (a, b) = self.axes(qa, qb);
        let rel = a.transpose() * b;
        let r = self.r.eval(qa, qb);
        let wrap = |x: f64| {
            if x <= -std::f64::consts::PI {
                std::f64::consts::PI
            } else {
                x
            }
        };
        let theta = wrap(rel[(1, 0)].atan2(rel[(0, 0)]));
        let along = |k: usize| r.dot(&a.column(k));
        match self.kind {
            JointType::Revolute => out[0] = theta,
            JointType::Prismatic => out[0] = along(2),
            JointType::Cylindrical => {
                out[0] = along(2);
                out[1] = theta;
            }
            JointType::Universal => {
                out[0] = wrap(rel[(2, 1)].atan2(rel[(1, 1)]));
                out[1] = wrap(rel[(0, 2)].atan2(rel[(0, 0)]));
            }
            JointType::Planar => {
                out[0] = along(0);
                out[1] = along(1);
                out[2] = theta;
            }
            JointType::Spherical => out.copy_from_slice(&matrix_to_quat(
                &(self.frame * rel * self.frame.transpose()),
            )),
            JointType::Fixed => {}
        }
    }

    /// Joint rates at nodes `qa`, `qb` with node velocities `va`, `vb` (zeros for the world),
    /// `out.len() == kind.dof()`: rad/s and m/s in the order of [`JointType::dof`]; spherical:
    /// the relative angular velocity in the child joint frame, `[b]ᵀ(ω_B − ω_A)`.
    pub fn rates(&self, qa: &Nodes, qb: &Nodes, va: &Nodes, vb: &Nodes, out: &mut [f64]) {
        let omega =
            |q: &Nodes, v: &Nodes| (1..NODES).map(|i| q[i].cross(&v[i])).sum::<Vec3>() * 0.5;
        let w = omega(qb, vb) - omega(qa, va);
        if self.kind == JointType::Spherical {
            for (k, b) in self.b.iter().enumerate() {
                out[k] = b.eval(qa, qb).dot(&w);
            }
            return;
        }
        for (k, dof) in self.dofs.iter().enumerate() {
            out[k] = match dof {
                Dof::Turn(n) => n.eval(qa, qb).dot(&w),
                Dof::Slide(row) => {
                    let mut g = [Vec3::zeros(); 2 * NODES];
                    row.gradient(qa, qb, &mut g);
                    (0..NODES)
                        .map(|i| g[i].dot(&va[i]) + g[NODES + i].dot(&vb[i]))
                        .sum()
                }
            };
        }
    }

    /// Largest constraint violation `max_k |g_k|` at `qa`, `qb` (m or 1).
    #[must_use]
    pub fn residual(&self, qa: &Nodes, qb: &Nodes) -> f64 {
        self.rows
            .iter()
            .map(|row| row.eval(qa, qb).abs())
            .fold(0.0, f64::max)
    }
}

#[cfg(test)]
#[path = "joint_tests.rs"]
mod tests;
