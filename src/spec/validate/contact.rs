//! Checks of `[ground]`, `[[collision]]`, `[[contact_pair]]` and `self_collision`.

use std::collections::HashMap;

use crate::mechanics::ranges;
use crate::spec::error::{did_you_mean, Report};
use crate::spec::schema::{CollisionSpec, Spec};

use super::common::{check_finite, is_identifier};

/// Reports a law value outside its range.
fn law(
    report: &mut Report,
    path: &str,
    friction: Option<f64>,
    stiffness: Option<f64>,
    damping: Option<f64>,
) {
    let checks = [
        ("friction", friction.map(ranges::non_negative)),
        ("stiffness", stiffness.map(ranges::positive)),
        ("damping", damping.map(ranges::non_negative)),
    ];
    for (field, check) in checks {
        if let Some(Err(e)) = check {
            report.push(format!("{path}.{field}"), e);
        }
    }
}

/// The kinds a shape gives, as `(key, sizes)`.
fn kinds(c: &CollisionSpec) -> Vec<(&'static str, Vec<f64>)> {
    [
        ("sphere", c.sphere.map(|s| vec![s.radius])),
        ("capsule", c.capsule.map(|s| vec![s.radius, s.length])),
        ("box", c.cuboid.map(|s| s.size.to_vec())),
        ("cylinder", c.cylinder.map(|s| vec![s.radius, s.length])),
    ]
    .into_iter()
    .filter_map(|(k, s)| s.map(|s| (k, s)))
    .collect()
}

/// Every contact check that needs only the spec.
pub(super) fn check(spec: &Spec, report: &mut Report, body_index: &HashMap<&str, usize>) {
    if let Some(g) = &spec.ground {
        if let Err(e) = ranges::any_finite(g.height) {
            report.push("ground.height", e);
        }
        law(
            report,
            "ground",
            Some(g.friction),
            Some(g.stiffness),
            Some(g.damping),
        );
    }
    let names = spec.collision_names();
    let mut seen: HashMap<&str, usize> = HashMap::new();
    for (i, c) in spec.collision.iter().enumerate() {
        let p = format!("collision[{i}]");
        let name = names[i].as_str();
        if !is_identifier(name) {
            report.push(
                format!("{p}.name"),
                format!("\"{name}\" is not an identifier: use letters, digits and _ and do not start with a digit"),
            );
        }
        if let Some(first) = seen.insert(name, i) {
            report.push(
                format!("{p}.name"),
                format!("duplicate collision name \"{name}\" (also collision[{first}])"),
            );
        }
        if !body_index.contains_key(c.body.as_str()) {
            let why = if c.body == "world" {
                "a collision shape must be fixed on a body (the ground is [ground])".into()
            } else {
                let hint = did_you_mean(&c.body, body_index.keys().copied());
                format!("no body named \"{}\"{hint}", c.body)
            };
            report.push(format!("{p}.body"), why);
        }
        check_finite(
            report,
            &format!("{p}.origin"),
            &[c.origin.xyz, c.origin.rpy].concat(),
        );
        let k = kinds(c);
        if k.len() != 1 {
            report.push(
                p.clone(),
                "give exactly one of sphere, capsule, box, cylinder",
            );
        }
        for (key, sizes) in &k {
            let ok = match *key {
                "capsule" => sizes[0] > 0.0 && sizes[1] >= 0.0,
                _ => sizes.iter().all(|&x| x > 0.0),
            };
            if !ok || sizes.iter().any(|x| !x.is_finite()) {
                let what = if *key == "capsule" {
                    "radius must be > 0 and length >= 0 (finite)"
                } else {
                    "sizes must be finite and > 0"
                };
                report.push(format!("{p}.{key}"), what);
            }
        }
        law(report, &p, c.friction, c.stiffness, c.damping);
    }
    for (i, pair) in spec.contact_pair.iter().enumerate() {
        let p = format!("contact_pair[{i}]");
        let mut found = Vec::new();
        for (key, n) in [("a", &pair.a), ("b", &pair.b)] {
            match seen.get(n.as_str()) {
                Some(&s) => found.push(s),
                None => {
                    let hint = did_you_mean(n, seen.keys().copied());
                    report.push(
                        format!("{p}.{key}"),
                        format!("no collision shape named \"{n}\"{hint}"),
                    );
                }
            }
        }
        if let [a, b] = found[..] {
            let (ca, cb) = (&spec.collision[a], &spec.collision[b]);
            if ca.body == cb.body {
                report.push(p.clone(), format!("\"{}\" and \"{}\" are on the same body \"{}\": shapes of one body do not touch each other", pair.a, pair.b, ca.body));
            }
            if ca.cylinder.is_some() || cb.cylinder.is_some() {
                report.push(p.clone(), "a cylinder touches the ground only: use a capsule (or a box) for contact between bodies");
            }
            if spec.contact_pair[..i]
                .iter()
                .any(|q| (q.a == pair.a && q.b == pair.b) || (q.a == pair.b && q.b == pair.a))
            {
                report.push(
                    p,
                    format!("the pair \"{}\", \"{}\" is listed twice", pair.a, pair.b),
                );
            }
        }
    }
}
