//! Checks of `[[coupling]]`: the two joints exist, differ, are both revolute or both prismatic
//! tree joints; the ratio is finite and non-zero, the offset finite; a joint follows at most one
//! other and no joint follows itself through a cycle; the follower takes no input and its
//! initial state, if given, is the leader's mapped (`q_b = r q_a + o`, `q̇_b = r q̇_a`).

use std::collections::HashMap;

use crate::spec::error::{did_you_mean, Report};
use crate::spec::schema::{JointKind, JointSpec, Spec};
use crate::spec::values::Coords;

/// Largest difference between a follower's given initial `q` or `qd` and the leader's mapped.
const INITIAL_TOL: f64 = 1e-9;

/// Reports every problem of the spec's couplings.
pub(super) fn check(spec: &Spec, report: &mut Report) {
    let index: HashMap<&str, usize> = spec
        .joint
        .iter()
        .enumerate()
        .map(|(i, j)| (j.name.as_str(), i))
        .collect();
    let names = || spec.joint.iter().map(|j| j.name.as_str());
    let mut follows: HashMap<usize, usize> = HashMap::new();
    for (i, c) in spec.coupling.iter().enumerate() {
        let p = format!("coupling[{i}]");
        let find = |report: &mut Report, field: &str, name: &str| {
            let j = index.get(name).copied();
            if j.is_none() {
                report.push(
                    format!("{p}.{field}"),
                    format!("no joint \"{name}\"{}", did_you_mean(name, names())),
                );
            }
            j
        };
        let (a, b) = (find(report, "a", &c.a), find(report, "b", &c.b));
        if !(c.ratio.is_finite() && c.ratio != 0.0) {
            report.push(
                format!("{p}.ratio"),
                format!("must be finite and non-zero (got {})", c.ratio),
            );
        }
        if !c.offset.is_finite() {
            report.push(
                format!("{p}.offset"),
                format!("must be finite (got {})", c.offset),
            );
        }
        let (Some(a), Some(b)) = (a, b) else { continue };
        if a == b {
            report.push(&p, format!("joint \"{}\" cannot follow itself", c.a));
            continue;
        }
        let (ja, jb) = (&spec.joint[a], &spec.joint[b]);
        let one = |j: &JointSpec| matches!(j.kind, JointKind::Revolute | JointKind::Prismatic);
        if ja.kind != jb.kind || !one(ja) {
            report.push(
                &p,
                format!(
                    "joints \"{}\" and \"{}\" must both be revolute or both prismatic (got {} and {})",
                    ja.name,
                    jb.name,
                    super::joints::kind_name(ja.kind),
                    super::joints::kind_name(jb.kind)
                ),
            );
            continue;
        }
        for j in [ja, jb] {
            if j.is_loop_closing() {
                report.push(
                    &p,
                    format!(
                        "joint \"{}\" closes a loop: only tree joints can be coupled",
                        j.name
                    ),
                );
            }
        }
        if jb.actuated {
            report.push(
                &p,
                format!(
                    "joint \"{}\" follows \"{}\" and has no input of its own: set actuated = false on it and drive \"{}\"",
                    jb.name, ja.name, ja.name
                ),
            );
        }
        if let Some(first) = follows.insert(b, a) {
            report.push(
                format!("{p}.b"),
                format!(
                    "joint \"{}\" already follows \"{}\": a joint follows at most one other",
                    jb.name, spec.joint[first].name
                ),
            );
        }
        initial(report, &p, c.ratio, c.offset, ja, jb);
    }
    // a cycle a → b → … → a makes the rows dependent
    for &start in follows.keys() {
        let (mut j, mut n) = (start, 0);
        while let Some(&a) = follows.get(&j) {
            j = a;
            n += 1;
            if j == start || n > follows.len() {
                report.push(
                    "coupling",
                    format!(
                        "joint \"{}\" follows itself through a cycle of couplings",
                        spec.joint[start].name
                    ),
                );
                return;
            }
        }
    }
}

/// A follower's given initial `q`, `qd` must be the leader's mapped (they are derived when
/// left out).
fn initial(report: &mut Report, p: &str, r: f64, o: f64, ja: &JointSpec, jb: &JointSpec) {
    let first = |c: Option<&Coords>| c.map(|c| c.values().first().copied().unwrap_or(0.0));
    let ia = ja.initial.as_ref();
    let ib = jb.initial.as_ref();
    let (qa, qda) = (
        first(ia.and_then(|i| i.q.as_ref())).unwrap_or(0.0),
        first(ia.and_then(|i| i.qd.as_ref())).unwrap_or(0.0),
    );
    let checks = [
        ("q", first(ib.and_then(|i| i.q.as_ref())), r * qa + o),
        ("qd", first(ib.and_then(|i| i.qd.as_ref())), r * qda),
    ];
    for (what, given, want) in checks {
        if let Some(g) = given {
            if (g - want).abs() > INITIAL_TOL * (1.0 + want.abs()) {
                report.push(
                    p,
                    format!(
                        "joint \"{}\" follows \"{}\": its initial {what} = {g} is not ratio · {what}_a{} = {want}; leave it out (it is derived)",
                        jb.name,
                        ja.name,
                        if what == "q" { " + offset" } else { "" }
                    ),
                );
            }
        }
    }
}
