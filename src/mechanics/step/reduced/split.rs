//! Which revolute joints the reduced iteration loads in joint space (`joint_space`): their
//! turn rows `s = p_s·k_s`, `c = p_c·k_c` split into a factor fixed in the parent (a
//! combination of its directors, or a constant for the world) and one fixed in the child,
//! and the axis `n` fixed in the parent. Increments as `turn::row_increment` sums them:
//!
//! ```text
//! Δ(p·k) = Δp·k̄ + p̄·Δk      (Δ from the node increments, bars at the midpoint)
//! ```

use crate::math::Vec3;
use crate::mechanics::model::constraint::{LinVec, Nodes};
use crate::mechanics::model::def::JointType;
use crate::mechanics::model::runtime::{DofRt, Model};

/// A factor of a turn row: a combination of the parent's or the child's directors, or a
/// constant (the world's axes).
#[derive(Clone, Copy, Debug)]
pub(crate) enum Factor {
    /// `Σᵢ cᵢ dᵢ` over the parent's directors (`c[0] = 0`: no position node).
    Parent([f64; 4]),
    /// `Σᵢ cᵢ dᵢ` over the child's directors.
    Child([f64; 4]),
    /// A constant, world frame.
    Fixed(Vec3),
}

impl Factor {
    /// The value at the parent's and the child's nodes, as `LinVec::eval` sums it.
    #[inline]
    pub(crate) fn at(&self, qa: &Nodes, qb: &Nodes) -> Vec3 {
        match self {
            Self::Parent(c) => comb(c, qa),
            Self::Child(c) => comb(c, qb),
            Self::Fixed(v) => *v,
        }
    }

    /// The increment from the node increments (a constant's is zero), as
    /// `turn::row_increment` sums it.
    #[inline]
    pub(crate) fn increment(&self, da: &Nodes, db: &Nodes) -> Vec3 {
        match self {
            Self::Parent(c) => comb(c, da),
            Self::Child(c) => comb(c, db),
            Self::Fixed(_) => Vec3::zeros(),
        }
    }
}

/// `Σₙ xₙ cₙ` in the order of `LinVec::eval` (a zero position coefficient adds an exact 0).
#[inline]
fn comb(c: &[f64; 4], x: &Nodes) -> Vec3 {
    let mut v = x[0] * c[0];
    v += x[1] * c[1];
    v += x[2] * c[2];
    v += x[3] * c[3];
    v
}

/// A revolute joint's turn rows split into their parent and child factors, and its axis.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Split {
    /// `[p, k]` of `s`, and whether `p` is the row's first factor.
    pub(crate) s: ([Factor; 2], bool),
    /// `[p, k]` of `c`, and whether `p` is the row's first factor.
    pub(crate) c: ([Factor; 2], bool),
    /// The axis `n` (parent-fixed).
    pub(crate) n: Factor,
}

const ZERO4: [f64; 4] = [0.0; 4];

/// `v` as a parent factor: a combination of the parent's directors (no position node, no
/// constant), or a constant where the parent is the world.
fn parent_factor(v: &LinVec, world: bool) -> Option<Factor> {
    if v.b != ZERO4 {
        None
    } else if world {
        (v.a == ZERO4).then_some(Factor::Fixed(v.c))
    } else {
        (v.a[0] == 0.0 && v.c == Vec3::zeros()).then_some(Factor::Parent(v.a))
    }
}

/// `v` as a child factor: a combination of the child's directors.
fn child_factor(v: &LinVec) -> Option<Factor> {
    (v.a == ZERO4 && v.b[0] == 0.0 && v.c == Vec3::zeros()).then_some(Factor::Child(v.b))
}

impl Split {
    /// `[Δs, Δc]` from the midpoint nodes and the node increments, the same sums as
    /// `turn::row_increment` (`Δ(u·w) = Δu·w̄ + ū·Δw`).
    pub(crate) fn increments(&self, bar: (&Nodes, &Nodes), d: (&Nodes, &Nodes)) -> [f64; 2] {
        let (qa_bar, qb_bar) = bar;
        let inc = |row: &([Factor; 2], bool)| {
            let f = &row.0;
            let at = (f[0].at(qa_bar, qb_bar), f[1].at(qa_bar, qb_bar));
            row_increment(row, at, d)
        };
        [inc(&self.s), inc(&self.c)]
    }
}

/// The increment of the row `(p, k)` (`p_first`: `p` is the row's first factor) from its
/// factors at the midpoint `(p̄, k̄)` and the node increments, as `turn::row_increment` sums
/// it (`Δu·w̄ + ū·Δw` in the row's order).
pub(crate) fn row_increment(
    (f, p_first): &([Factor; 2], bool),
    (pb, kb): (Vec3, Vec3),
    (da, db): (&Nodes, &Nodes),
) -> f64 {
    let (dp, dk) = (f[0].increment(da, db), f[1].increment(da, db));
    if *p_first {
        dp.dot(&kb) + pb.dot(&dk)
    } else {
        dk.dot(&pb) + kb.dot(&dp)
    }
}

/// The split of joint `j`, if it is a revolute joint whose rows have one.
pub(crate) fn split(model: &Model, j: usize) -> Option<Split> {
    let jt = &model.joints[j];
    if jt.geom.kind != JointType::Revolute || jt.dofs.len() != 1 {
        return None;
    }
    let DofRt::Turn(tr) = &jt.dofs[0] else {
        return None;
    };
    let world = jt.parent.is_none();
    let pk = |u: &LinVec, w: &LinVec| {
        if let (Some(p), Some(k)) = (parent_factor(u, world), child_factor(w)) {
            Some(([p, k], true))
        } else if let (Some(p), Some(k)) = (parent_factor(w, world), child_factor(u)) {
            Some(([p, k], false))
        } else {
            None
        }
    };
    Some(Split {
        s: pk(&tr.sin.u, &tr.sin.w)?,
        c: pk(&tr.cos.u, &tr.cos.w)?,
        n: parent_factor(&jt.geom.a[2], world)?,
    })
}

/// What one joint adds in joint space: its residual and (`jac`) rotational rows on the child's
/// and the parent's twists.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct JointRow {
    /// Added to the joint's reduced residual.
    pub r: f64,
    /// Row on the child's rotation.
    pub xc: Vec3,
    /// Row on the parent's rotation.
    pub xp: Vec3,
}
