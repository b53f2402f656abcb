//! Placements and inertials: a link's inertial placed in a body frame, several merged into one,
//! and the rule for links whose own inertial is impossible (one rule for merged and kept fixed
//! links).
//!
//! ```text
//! c         = p + R · xyz_inertial                 (centre of mass in the host frame)
//! J_c       = (R · R_rpy) J_urdf (R · R_rpy)ᵀ      (inertia about c, host axes)
//! merged:     m = Σ mᵢ,  c = Σ mᵢ cᵢ / m,  J = Σ [J_cᵢ + mᵢ (|cᵢ − c|² I − (cᵢ − c)(cᵢ − c)ᵀ)]
//! possible:   E = ½ tr(J) I − J ⪰ 0                (the second moments of a mass distribution:
//!                                                   J ⪰ 0 and the triangle inequality)
//! ```
//!
//! A *rigid cluster* is a set of links welded together by fixed joints (merged into one body, or
//! kept as bodies on fixed joints). Since `E` is linear in `J` and the parallel-axis term is
//! itself possible, a cluster of possible inertials is possible, and a cluster is impossible only
//! through its impossible links: those are the ones a refusal names.

use super::robot::{at, Inertial, Pose, Robot};
pub(super) use crate::import::frame::Iso;
pub(super) use crate::import::inertia::{clean, merge, Part};
use crate::math::{rpy_to_matrix, Mat3, Vec3};
use crate::mechanics::ranges;
use crate::spec::{OriginSpec, Problem};

impl Iso {
    /// The placement a URDF `origin xyz rpy` describes.
    pub(super) fn of(pose: &Pose) -> Self {
        Self {
            r: rpy_to_matrix(&Vec3::from(pose.rpy)),
            p: Vec3::from(pose.xyz),
        }
    }

    /// The spec's `origin` of this placement (the URDF's own numbers where nothing was
    /// composed).
    pub(super) fn origin(&self, written: Option<&Pose>) -> OriginSpec {
        match written {
            Some(w) => OriginSpec {
                xyz: w.xyz,
                rpy: w.rpy,
            },
            None => self.origin_spec(),
        }
    }
}

/// The inertial contributions merged into one body, in the body frame.
pub(super) type Parts = Vec<Part>;

pub(super) fn inertia_matrix(i: &[f64; 6]) -> Mat3 {
    let [xx, yy, zz, xy, xz, yz] = *i;
    Mat3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz)
}

/// An inertial placed in a host frame: `(m, c, J_c)`; `j` replaces the written tensor.
fn placed_as(inertial: &Inertial, j: Mat3, frame: &Iso) -> Part {
    let io = Iso::of(&inertial.origin);
    let total = frame.then(&io);
    let jc = if total.r == Mat3::identity() {
        j
    } else {
        total.r * j * total.r.transpose()
    };
    (inertial.mass, total.p, jc)
}

/// An inertial placed in a host frame: `(m, c, J_c)`.
pub(super) fn placed(inertial: &Inertial, frame: &Iso) -> Part {
    placed_as(inertial, inertia_matrix(&inertial.inertia), frame)
}

/// `E = ½ tr(J) I − J`: the second moments of the mass about the centre of mass.
fn second_moments(j: &Mat3) -> Mat3 {
    Mat3::identity() * (0.5 * j.trace()) - j
}

/// How far `j` is from a possible inertia: `max(0, −λ_min(E))`, kg·m².
fn violation(j: &Mat3) -> f64 {
    (-second_moments(j).symmetric_eigen().eigenvalues.min()).max(0.0)
}

/// The possible inertia nearest `j` in its second moments: the negative eigenvalues of `E` set
/// to zero, `J = tr(E) I − E`.
fn made_possible(j: &Mat3) -> Mat3 {
    let eig = second_moments(j).symmetric_eigen();
    let d = Mat3::from_diagonal(&eig.eigenvalues.map(|x| x.max(0.0)));
    let e = eig.eigenvectors * d * eig.eigenvectors.transpose();
    let e = (e + e.transpose()) * 0.5;
    Mat3::identity() * e.trace() - e
}

/// Why a body's (cleaned) inertia is impossible, if it is.
fn impossible(part: &Part) -> Option<String> {
    ranges::inertia(&clean(part.2, part.0)).err()
}

/// A link on the way of the inertials: where the import put it.
#[derive(Clone, Copy)]
pub(super) struct Placement {
    /// The body that carries the link (None: the world).
    pub body: Option<usize>,
    /// The link frame in that body's frame.
    pub frame: Iso,
    /// The first link of its rigid cluster (None: welded to the world).
    pub cluster: Option<usize>,
    /// The link frame in the cluster's first link's frame.
    pub in_cluster: Iso,
}

/// The link names of `members`, each between `quote`s, joined; past four, how many more.
fn names(robot: &Robot, members: &[usize], quote: char) -> String {
    const SHOWN: usize = 4;
    let q: Vec<String> = members
        .iter()
        .take(SHOWN)
        .map(|&l| format!("{quote}{}{quote}", robot.links[l].name))
        .collect();
    match members.len().saturating_sub(SHOWN) {
        0 => q.join(", "),
        more => format!(
            "{} and {more} more link{}",
            q.join(", "),
            if more == 1 { "" } else { "s" }
        ),
    }
}

/// Gives every body its parts: each link's inertial in the frame of the body that carries it.
///
/// The rule (the same merged and kept): a link whose own inertial is impossible but which is
/// welded by fixed joints into a rigid cluster that is possible is accepted with a note; a
/// cluster that is impossible is refused, naming its impossible links at the line of their
/// `<inertia>`. A link welded to the world does not move: merged, its inertial goes nowhere;
/// kept, its body is massless when the inertial is impossible (with a note).
///
/// Kept links (`keep_fixed`): a violation at round-off, `max(0, −λ_min(E)) ≤ 1e-12` of the
/// cluster's scale (the largest entry of its merged tensor or of a member's), is read as zero
/// (`E`'s negative eigenvalues set to zero) and the link keeps its inertial; a larger one is
/// carried by the cluster's first body (the one on the cluster's moving joint, or the free
/// base), the link staying a massless body on its fixed joint; if that body is still
/// impossible, it carries every inertial of the cluster. The cluster's mass, centre of mass
/// and inertia are unchanged, so is the motion.
#[allow(clippy::too_many_lines)]
pub(super) fn distribute(
    robot: &Robot,
    placement: &[Option<Placement>],
    keep_fixed: bool,
    parts: &mut [Parts],
    notes: &mut Vec<String>,
    problems: &mut Vec<Problem>,
) {
    let with_inertial = |l: usize| placement[l].zip(robot.links[l].inertial.as_ref());
    // the world's cluster: nothing moves
    for l in 0..robot.links.len() {
        let Some((p, inertial)) = with_inertial(l) else {
            continue;
        };
        if p.cluster.is_some() {
            continue;
        }
        // a kept body on a fixed joint to the world (merged: the world takes the inertial)
        let Some(b) = p.body else { continue };
        let own = placed(inertial, &p.frame);
        match impossible(&own) {
            None => parts[b].push(own),
            Some(why) => notes.push(format!(
                "link '{}': its inertia {why}; it is welded to the world and does not move: its body is kept massless",
                robot.links[l].name
            )),
        }
    }
    let mut firsts: Vec<usize> = placement
        .iter()
        .filter_map(|p| p.and_then(|p| p.cluster))
        .collect();
    firsts.sort_unstable();
    firsts.dedup();
    for first in firsts {
        let members: Vec<usize> = (0..robot.links.len())
            .filter(|&l| placement[l].is_some_and(|p| p.cluster == Some(first)))
            .collect();
        let massive: Vec<(usize, Placement, &Inertial)> = members
            .iter()
            .filter_map(|&l| with_inertial(l).map(|(p, i)| (l, p, i)))
            .collect();
        let in_cluster: Parts = massive
            .iter()
            .map(|(_, p, i)| placed(i, &p.in_cluster))
            .collect();
        let whole = merge(&in_cluster);
        let bad: Vec<(usize, String)> = massive
            .iter()
            .filter_map(|&(l, _, i)| {
                let own = (i.mass, Vec3::zeros(), inertia_matrix(&i.inertia));
                impossible(&own).map(|why| (l, why))
            })
            .collect();
        let others = |l: usize, quote: char| {
            let rest: Vec<usize> = members.iter().copied().filter(|&k| k != l).collect();
            names(robot, &rest, quote)
        };
        if let Some(why) = impossible(&whole) {
            if bad.is_empty() {
                problems.push(Problem::new(
                    at(robot.links[first].line, &format!("link \"{}\"", robot.links[first].name)),
                    format!(
                        "the rigid body of links {} (welded by fixed joints) has an inertia that {why}",
                        names(robot, &members, '"')
                    ),
                ));
            }
            for (l, own) in &bad {
                let link = &robot.links[*l];
                let line = link.inertial.as_ref().map_or(link.line, |i| i.line);
                let tail = if members.len() > 1 {
                    format!(
                        "; welded by fixed joints to {}, the rigid body they form is impossible too (its inertia {why})",
                        others(*l, '"')
                    )
                } else {
                    String::new()
                };
                problems.push(Problem::new(
                    at(line, &format!("link \"{}\"", link.name)),
                    format!("<inertia> {own}{tail}"),
                ));
            }
            continue;
        }
        let scale = massive
            .iter()
            .map(|(_, _, i)| inertia_matrix(&i.inertia).amax())
            .fold(whole.2.amax(), f64::max);
        let round_off = |i: &Inertial| violation(&inertia_matrix(&i.inertia)) <= 1e-12 * scale;
        let is_bad = |l: usize| bad.iter().any(|(k, _)| *k == l);
        // what each body gets: merged, every part to its body; kept, see above
        let mut given: Vec<(usize, Part)> = Vec::new();
        let mut carry_all = false;
        let first_body = placement[first].and_then(|p| p.body);
        for (l, p, i) in &massive {
            let Some(b) = p.body else { continue };
            if !keep_fixed || !is_bad(*l) {
                given.push((b, placed(i, &p.frame)));
            } else if round_off(i) {
                let j = made_possible(&inertia_matrix(&i.inertia));
                given.push((b, placed_as(i, j, &p.frame)));
            } else if let Some(fb) = first_body {
                given.push((fb, placed(i, &p.in_cluster)));
            }
        }
        if let (true, Some(fb)) = (keep_fixed && !bad.is_empty(), first_body) {
            let on_first: Parts = given
                .iter()
                .filter(|(b, _)| *b == fb)
                .map(|(_, part)| *part)
                .collect();
            if impossible(&merge(&on_first)).is_some() {
                carry_all = true;
                given = in_cluster.iter().map(|part| (fb, *part)).collect();
            }
        }
        for (b, part) in given {
            parts[b].push(part);
        }
        let first_name = &robot.links[first].name;
        for (l, why) in &bad {
            let tiny = robot.links[*l].inertial.as_ref().is_some_and(round_off);
            let what = if keep_fixed && carry_all {
                format!(" ('{first_name}' carries the inertials of the whole cluster; the other bodies are massless)")
            } else if tiny {
                " (a violation at round-off of that body's scale, read as zero)".to_string()
            } else if keep_fixed {
                format!(" (kept as a massless body on its fixed joint; '{first_name}' carries its inertial)")
            } else {
                String::new()
            };
            notes.push(format!(
                "link '{}': its own inertia {why}; accepted: it is welded by fixed joints to {}, and the rigid body they form is possible{what}",
                robot.links[*l].name,
                others(*l, '\'')
            ));
        }
    }
}
