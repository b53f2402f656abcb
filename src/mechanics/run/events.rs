//! Joint-stop and body contacts as step ends under error control (`solver.rtol > 0`): a trial
//! step across which a limited coordinate reaches one of its limits (enters contact) or leaves
//! it, or a contact point or feature touches or leaves (its gap changes sign), is replaced by a
//! step that ends where it does, so that no step straddles the kink of a contact force.
//!
//! With the coordinate `t` (rad or m; `t₀` at the step start, `t₁` at the trial's end) and a
//! limit `ℓ`, the signed penetration is `x = t − upper` or `x = lower − t`; a step crosses
//! when `x₀ ≤ 0 < x₁` (entering) or `x₀ > 0 ≥ x₁` (leaving), and the crossing lies at the
//! fraction (secant, linear in time)
//!
//! ```text
//! θ = x₀ / (x₀ − x₁) ∈ [0, 1)
//! ```
//!
//! of the step (for a contact, `x = −gap`). The earliest `θ` of all limits and contacts in `(LANDED, 1 − LANDED)` gives the landing step
//! `θh`; a crossing within `LANDED` of either end counts as landed already (the secant retry
//! converges to it: each retry ends closer, and no step is shortened to a sliver).

use crate::math::Vec3;
use crate::mechanics::model::constraint::body_nodes;
use crate::mechanics::model::contact::pair_nodes;
use crate::mechanics::model::runtime::{DofRt, JointRt, Model};

/// Fractions of a step within this of its start or end count as landed.
pub const LANDED: f64 = 1e-3;

/// The coordinate of joint `jt` (its first, the only one a joint with stops has) at the
/// coordinates `q` and unwrapped angles `ang`.
fn coordinate(jt: &JointRt, q: &[f64], ang: &[f64]) -> Option<f64> {
    match jt.dofs.first()? {
        DofRt::Slide(row) => {
            let qb = body_nodes(q, jt.child);
            let qa = jt.parent.map_or([Vec3::zeros(); 4], |a| body_nodes(q, a));
            Some(row.eval(&qa, &qb))
        }
        DofRt::Turn(_) => Some(ang[jt.turn0]),
    }
}

/// The fraction of a step from `x0` to `x1` (signed penetrations) at which it enters or
/// leaves contact, if it does.
fn crossing(x0: f64, x1: f64) -> Option<f64> {
    ((x0 <= 0.0) != (x1 <= 0.0)).then(|| x0 / (x0 - x1))
}

/// The earliest fraction `θ ∈ (LANDED, 1 − LANDED)` of the step from `(q0, ang0)` to
/// `(q1, ang1)` at which a joint coordinate with stops reaches one of its limits, entering or
/// leaving contact (module docs); `None` when no limit is crossed away from the step's ends.
#[must_use]
pub fn stop_crossing(
    model: &Model,
    q0: &[f64],
    ang0: &[f64],
    q1: &[f64],
    ang1: &[f64],
) -> Option<f64> {
    crossing_within(model, q0, ang0, q1, ang1, 1.0 - LANDED)
}

/// The earliest fraction `θ ∈ (LANDED, hi)` of the step at which a limit or contact is
/// crossed (`stop_crossing` with the upper bound `hi`; `hi > 1` also reports crossings at
/// the step's end, for an early return there).
#[must_use]
pub fn crossing_within(
    model: &Model,
    q0: &[f64],
    ang0: &[f64],
    q1: &[f64],
    ang1: &[f64],
    hi: f64,
) -> Option<f64> {
    first_event(model, q0, ang0, q1, ang1, LANDED, hi).map(|(theta, _)| theta)
}

/// One event of a step: a joint coordinate reaching or leaving a limit, or a contact point or
/// feature touching or leaving.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Event {
    /// Joint `joint`'s upper (`true`) or lower limit.
    Stop {
        /// The joint.
        joint: usize,
        /// The upper limit (else the lower).
        upper: bool,
    },
    /// Ground contact point `k`.
    Ground(usize),
    /// Body–body contact feature `k`.
    Feature(usize),
}

/// The signed penetration of `ev` at the coordinates `q` and unwrapped angles `ang` (module
/// docs: `t − upper`, `lower − t`, `−gap`; positive in contact), rad or m.
#[must_use]
pub fn penetration(model: &Model, ev: Event, q: &[f64], ang: &[f64]) -> f64 {
    match ev {
        Event::Stop { joint, upper } => {
            let jt = &model.joints[joint];
            let (Some(st), Some(t)) = (jt.stops, coordinate(jt, q, ang)) else {
                return f64::NAN;
            };
            if upper {
                t - st.upper
            } else {
                st.lower - t
            }
        }
        Event::Ground(k) => {
            let Some(g) = &model.contact.ground else {
                return f64::NAN;
            };
            let p = &g.points[k];
            let n = body_nodes(q, p.body);
            let x = n[0] + n[1] * p.x.x + n[2] * p.x.y + n[3] * p.x.z;
            -(g.normal.dot(&x) - g.height - p.radius)
        }
        Event::Feature(k) => {
            let f = &model.contact.features[k];
            let (qa, qb) = pair_nodes(q, f);
            -f.gap(&f.invariants(&qa, &qb))
        }
    }
}

/// The earliest event crossed at a fraction `θ ∈ (lo, hi)` of the step from `(q0, ang0)`
/// to `(q1, ang1)`, with that fraction (`crossing_within` names only the fraction, with
/// `lo = LANDED`).
#[must_use]
pub fn first_event(
    model: &Model,
    q0: &[f64],
    ang0: &[f64],
    q1: &[f64],
    ang1: &[f64],
    lo: f64,
    hi: f64,
) -> Option<(f64, Event)> {
    let mut first: Option<(f64, Event)> = None;
    let mut consider = |ev: Event| {
        let (x0, x1) = (
            penetration(model, ev, q0, ang0),
            penetration(model, ev, q1, ang1),
        );
        if let Some(theta) = crossing(x0, x1) {
            if theta > lo && theta < hi && first.is_none_or(|(f, _)| theta < f) {
                first = Some((theta, ev));
            }
        }
    };
    for (j, jt) in model.joints.iter().enumerate() {
        let Some(st) = jt.stops else {
            continue;
        };
        if st.upper.is_finite() {
            consider(Event::Stop {
                joint: j,
                upper: true,
            });
        }
        if st.lower.is_finite() {
            consider(Event::Stop {
                joint: j,
                upper: false,
            });
        }
    }
    if let Some(g) = &model.contact.ground {
        for k in 0..g.points.len() {
            consider(Event::Ground(k));
        }
    }
    for k in 0..model.contact.features.len() {
        consider(Event::Feature(k));
    }
    first
}

#[cfg(test)]
mod tests {
    use super::crossing;

    #[test]
    fn crossing_fraction_is_the_secant() {
        assert_eq!(crossing(-1.0, 1.0), Some(0.5));
        assert_eq!(crossing(3.0, -1.0), Some(0.75));
        assert_eq!(crossing(0.0, 2.0), Some(0.0));
        assert_eq!(crossing(-1.0, -0.5), None);
        assert_eq!(crossing(1.0, 0.5), None);
    }
}
