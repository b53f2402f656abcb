//! A recorded motion: the time of every kept row and, for every body of the model, the pose of
//! its frame (position and rotation world ← body), the contact force through every collision
//! shape whose outputs were recorded, and the signals the page plots. Built from a result CSV
//! ([`Recording::from_table`]) or directly (the FMU's initial pose).

use std::collections::BTreeSet;

use super::csv::ResultTable;
use super::error::ViewerError;
use crate::math::{Mat3, Vec3};
use crate::spec::{JointKind, Spec};

/// The pose of one body over the recording.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyTrack {
    /// The body's name (as in the spec).
    pub name: String,
    /// Origin of the body frame, world frame, m; one per recorded time.
    pub r: Vec<Vec3>,
    /// Rotation world ← body (columns are the body axes in world coordinates); one per time.
    pub rot: Vec<Mat3>,
}

/// The contact force through one collision shape over the recording (`contact.C.f[1..3]`).
#[derive(Clone, Debug, PartialEq)]
pub struct ContactTrack {
    /// The shape's name (as `Spec::collision_names` gives it).
    pub name: String,
    /// Index of the shape among the spec's `[[collision]]` entries.
    pub shape: usize,
    /// Total contact force on the shape's body through the shape, world frame, N; one per
    /// recorded time (non-finite values are kept: the page draws no arrow for them).
    pub f: Vec<Vec3>,
    /// The shape's gap to the ground (`contact.C.gap`), m, one per time, if recorded: it tells
    /// the height of the ground the run had (`ground.height` is a tunable parameter).
    pub gap: Option<Vec<f64>>,
}

/// What a plotted signal measures.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SignalKind {
    /// A joint coordinate (`joint.J.q`, `joint.J.q[k]`), rad or m.
    Coordinate,
    /// `system.energy − system.work` minus its initial value, J (constant for the scheme).
    Balance,
}

/// A signal plotted in the page's panel, one value per recorded time.
#[derive(Clone, Debug, PartialEq)]
pub struct Signal {
    /// The label (the CSV column, or `energy - work` for the balance).
    pub name: String,
    /// Its unit (`rad`, `m`, `J`).
    pub unit: &'static str,
    /// What it measures.
    pub kind: SignalKind,
    /// The values.
    pub values: Vec<f64>,
    /// For the balance: the largest |system.energy| of the run, J (sets the plot's least
    /// range, so that round-off shows as a flat line); 0 otherwise.
    pub scale: f64,
}

/// A recorded motion of a model's bodies.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Recording {
    /// Times of the rows, s, non-decreasing.
    pub time: Vec<f64>,
    /// One track per body of the model, in the spec's order.
    pub bodies: Vec<BodyTrack>,
    /// One track per collision shape whose three force columns are in the result, in the
    /// spec's order (none for a result without them: the page then has no force arrows).
    pub contacts: Vec<ContactTrack>,
    /// Plotted signals (joint coordinates, energy balance), in CSV order.
    pub signals: Vec<Signal>,
}

/// The body named by a pose column (`body.B.r[i]` or `body.B.R[i,j]`), if it is one.
fn pose_body(column: &str) -> Option<&str> {
    let rest = column.strip_prefix("body.")?;
    let (body, var) = rest.rsplit_once('.')?;
    (var.starts_with("r[") || var.starts_with("R[")).then_some(body)
}

/// The joint and coordinate index (1-based, 0 for a scalar `q`) of `joint.J.q` / `joint.J.q[k]`.
fn coordinate(column: &str) -> Option<(&str, usize)> {
    let rest = column.strip_prefix("joint.")?;
    let (joint, var) = rest.rsplit_once('.')?;
    if var == "q" {
        return Some((joint, 0));
    }
    let k = var.strip_prefix("q[")?.strip_suffix(']')?.parse().ok()?;
    Some((joint, k))
}

/// The shape and component (1-based; 0 for the gap) of a contact column `contact.C.f[i]` or
/// `contact.C.gap`.
fn contact_column(column: &str) -> Option<(&str, usize)> {
    let rest = column.strip_prefix("contact.")?;
    let (shape, var) = rest.rsplit_once('.')?;
    if var == "gap" {
        return Some((shape, 0));
    }
    let i = var.strip_prefix("f[")?.strip_suffix(']')?.parse().ok()?;
    (1..=3).contains(&i).then_some((shape, i))
}

/// Unit of coordinate `k` (1-based, 0 for the only one) of a joint of type `kind`.
fn coordinate_unit(kind: JointKind, k: usize) -> &'static str {
    match (kind, k) {
        (JointKind::Prismatic, _) | (JointKind::Cylindrical, 1) | (JointKind::Planar, 1 | 2) => "m",
        _ => "rad",
    }
}

impl Recording {
    /// True for the columns a recording reads: poses, contact forces and gaps, joint
    /// coordinates, energy and work.
    #[must_use]
    pub fn reads(column: &str) -> bool {
        pose_body(column).is_some()
            || contact_column(column).is_some()
            || coordinate(column).is_some()
            || column == "system.energy"
            || column == "system.work"
    }

    /// The recording of `spec`'s bodies in `table` (read with [`Recording::reads`]).
    ///
    /// # Errors
    /// [`ViewerError::NoPoses`] without any pose column; [`ViewerError::OtherModel`] when the
    /// bodies of the CSV are not the model's, or a joint's child is not where its parent places
    /// it in the first row; [`ViewerError::Csv`] for a missing rotation entry, a non-finite pose,
    /// a rotation that is not one, or times that go backwards.
    pub fn from_table(table: &ResultTable, spec: &Spec) -> Result<Self, ViewerError> {
        let origin = &table.origin;
        let csv_err = |message: String| ViewerError::Csv {
            origin: origin.clone(),
            message,
        };
        let in_csv: BTreeSet<&str> = table.header.iter().filter_map(|h| pose_body(h)).collect();
        if in_csv.is_empty() {
            return Err(ViewerError::NoPoses {
                origin: origin.clone(),
            });
        }
        let in_model: BTreeSet<&str> = spec.body.iter().map(|b| b.name.as_str()).collect();
        let missing: Vec<&str> = in_model.difference(&in_csv).copied().collect();
        let extra: Vec<&str> = in_csv.difference(&in_model).copied().collect();
        if !missing.is_empty() || !extra.is_empty() {
            let mut reason = Vec::new();
            if !missing.is_empty() {
                reason.push(format!("no poses of its bodies {}", missing.join(", ")));
            }
            if !extra.is_empty() {
                reason.push(format!(
                    "poses of bodies it does not have: {}",
                    extra.join(", ")
                ));
            }
            return Err(ViewerError::OtherModel {
                origin: origin.clone(),
                model: spec.name.clone(),
                reason: reason.join("; "),
            });
        }
        let time = table.column("time").unwrap_or_default().to_vec();
        if let Some(k) = (1..time.len()).find(|&k| time[k] < time[k - 1]) {
            return Err(csv_err(format!(
                "line {}: time goes back from {} to {}",
                k + 2,
                time[k - 1],
                time[k]
            )));
        }
        let mut bodies = Vec::with_capacity(spec.body.len());
        for b in &spec.body {
            let col = |var: String| {
                let name = format!("body.{}.{var}", b.name);
                table.column(&name).ok_or_else(|| {
                    csv_err(format!(
                        "no column {name} (body {} has other pose columns)",
                        b.name
                    ))
                })
            };
            let r_cols: Vec<&[f64]> = (1..=3)
                .map(|i| col(format!("r[{i}]")))
                .collect::<Result<_, _>>()?;
            let rot_cols: Vec<&[f64]> = (1..=3)
                .flat_map(|i| (1..=3).map(move |j| (i, j)))
                .map(|(i, j)| col(format!("R[{i},{j}]")))
                .collect::<Result<_, _>>()?;
            let mut track = BodyTrack {
                name: b.name.clone(),
                r: Vec::with_capacity(time.len()),
                rot: Vec::with_capacity(time.len()),
            };
            for k in 0..time.len() {
                let r = Vec3::new(r_cols[0][k], r_cols[1][k], r_cols[2][k]);
                let rot = Mat3::from_fn(|i, j| rot_cols[3 * i + j][k]);
                if !(r.iter().chain(rot.iter()).all(|x| x.is_finite())) {
                    return Err(csv_err(format!(
                        "line {}: body {}: the pose is not finite (t = {})",
                        k + 2,
                        b.name,
                        time[k]
                    )));
                }
                let defect = (rot.transpose() * rot - Mat3::identity()).amax();
                if defect > 1e-3 || rot.determinant() < 0.0 {
                    return Err(csv_err(format!(
                        "line {}: body {}: body.{}.R is not a rotation (|RᵀR − I| = {defect:.1e})",
                        k + 2,
                        b.name,
                        b.name
                    )));
                }
                track.r.push(r);
                track.rot.push(rot);
            }
            bodies.push(track);
        }
        let rec = Self {
            signals: signals(table, spec),
            contacts: contacts(table, spec),
            time,
            bodies,
        };
        rec.check_joints(spec, origin)?;
        Ok(rec)
    }

    /// Checks, in the first row, that the child of every joint that keeps a point in common
    /// (revolute, spherical, universal, fixed) is where its parent places it.
    fn check_joints(&self, spec: &Spec, origin: &str) -> Result<(), ViewerError> {
        let pose = |name: &str| -> Option<(Vec3, Mat3)> {
            self.bodies
                .iter()
                .find(|t| t.name == name)
                .map(|t| (t.r[0], t.rot[0]))
        };
        let scale = self
            .bodies
            .iter()
            .map(|t| t.r[0].norm())
            .fold(1.0, f64::max);
        for j in &spec.joint {
            if !matches!(
                j.kind,
                JointKind::Revolute
                    | JointKind::Spherical
                    | JointKind::Universal
                    | JointKind::Fixed
            ) {
                continue;
            }
            let at = |p: Option<(Vec3, Mat3)>, xyz: [f64; 3]| {
                let x = Vec3::from(xyz);
                p.map_or(x, |(r, rot)| r + rot * x)
            };
            let parent = at(pose(&j.parent), j.origin.xyz);
            let child = at(pose(&j.child), j.child_origin.map_or([0.0; 3], |o| o.xyz));
            let gap = (parent - child).norm();
            if gap > 1e-4 * scale || gap.is_nan() {
                return Err(ViewerError::OtherModel {
                    origin: origin.to_string(),
                    model: spec.name.clone(),
                    reason: format!(
                        "at t = {}, joint {} of the model joins {} and {} at points {gap:.3e} m apart \
                         (a result of another model, or of another version of it?)",
                        self.time[0], j.name, j.parent, j.child
                    ),
                });
            }
        }
        Ok(())
    }

    /// The rows kept for a replay at most `rate` frames per second of recorded time: the first,
    /// then each row at least `1/rate` after the last kept one, and the last. Rows at a repeated
    /// time keep the first. `rate <= 0` or non-finite keeps every row of increasing time.
    #[must_use]
    pub fn decimated(&self, rate: f64) -> Self {
        let gap = if rate > 0.0 && rate.is_finite() {
            (1.0 - 1e-9) / rate
        } else {
            0.0
        };
        let n = self.time.len();
        let mut keep: Vec<usize> = Vec::new();
        for k in 0..n {
            match keep.last() {
                None => keep.push(k),
                Some(&l) if self.time[k] > self.time[l] && self.time[k] - self.time[l] >= gap => {
                    keep.push(k);
                }
                _ => {}
            }
        }
        if let (Some(&l), Some(last)) = (keep.last(), n.checked_sub(1)) {
            if self.time[last] > self.time[l] {
                keep.push(last);
            }
        }
        let pick = |v: &[f64]| keep.iter().map(|&k| v[k]).collect::<Vec<_>>();
        Self {
            time: pick(&self.time),
            bodies: self
                .bodies
                .iter()
                .map(|b| BodyTrack {
                    name: b.name.clone(),
                    r: keep.iter().map(|&k| b.r[k]).collect(),
                    rot: keep.iter().map(|&k| b.rot[k]).collect(),
                })
                .collect(),
            contacts: self
                .contacts
                .iter()
                .map(|c| ContactTrack {
                    f: keep.iter().map(|&k| c.f[k]).collect(),
                    gap: c.gap.as_deref().map(&pick),
                    ..c.clone()
                })
                .collect(),
            signals: self
                .signals
                .iter()
                .map(|s| Signal {
                    values: pick(&s.values),
                    ..s.clone()
                })
                .collect(),
        }
    }
}

/// The contact forces of `spec`'s collision shapes whose three columns `table` has.
fn contacts(table: &ResultTable, spec: &Spec) -> Vec<ContactTrack> {
    spec.collision_names()
        .into_iter()
        .enumerate()
        .filter_map(|(shape, name)| {
            let cols: Vec<&[f64]> = (1..=3)
                .map(|i| table.column(&format!("contact.{name}.f[{i}]")))
                .collect::<Option<_>>()?;
            let f = (0..cols[0].len())
                .map(|k| Vec3::new(cols[0][k], cols[1][k], cols[2][k]))
                .collect();
            let gap = table
                .column(&format!("contact.{name}.gap"))
                .map(<[f64]>::to_vec);
            Some(ContactTrack {
                name,
                shape,
                f,
                gap,
            })
        })
        .collect()
}

/// The joint coordinates of `spec`'s joints found in `table`, then the energy balance.
fn signals(table: &ResultTable, spec: &Spec) -> Vec<Signal> {
    let mut out = Vec::new();
    for name in &table.header {
        let Some((joint, k)) = coordinate(name) else {
            continue;
        };
        let (Some(j), Some(values)) = (
            spec.joint.iter().find(|j| j.name == joint),
            table.column(name),
        ) else {
            continue;
        };
        out.push(Signal {
            name: name.clone(),
            unit: coordinate_unit(j.kind, k),
            kind: SignalKind::Coordinate,
            values: values.to_vec(),
            scale: 0.0,
        });
    }
    if let (Some(e), Some(w)) = (table.column("system.energy"), table.column("system.work")) {
        let base = e[0] - w[0];
        out.push(Signal {
            name: "energy - work".into(),
            unit: "J",
            kind: SignalKind::Balance,
            values: e.iter().zip(w).map(|(e, w)| (e - w) - base).collect(),
            scale: e.iter().fold(0.0, |m: f64, x| m.max(x.abs())),
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn column_names() {
        assert_eq!(pose_body("body.link_1.R[1,2]"), Some("link_1"));
        assert_eq!(pose_body("body.a.r[3]"), Some("a"));
        assert_eq!(pose_body("body.a.v[3]"), None);
        assert_eq!(coordinate("joint.elbow.q"), Some(("elbow", 0)));
        assert_eq!(coordinate("joint.hip.q[2]"), Some(("hip", 2)));
        assert_eq!(coordinate("joint.hip.qd[2]"), None);
        assert_eq!(contact_column("contact.FL_foot.f[3]"), Some(("FL_foot", 3)));
        assert_eq!(contact_column("contact.FL_foot.f[4]"), None);
        assert_eq!(contact_column("contact.FL_foot.gap"), Some(("FL_foot", 0)));
        assert_eq!(contact_column("contact.FL_foot.v"), None);
        assert!(Recording::reads("contact.shell.f[1]"));
    }

    #[test]
    fn decimation_keeps_first_and_last() {
        let rec = Recording {
            time: (0..=10).map(|k| f64::from(k) * 0.01).collect(),
            contacts: vec![ContactTrack {
                name: "foot".into(),
                shape: 0,
                f: (0..=10)
                    .map(|k| Vec3::new(0.0, 0.0, f64::from(k)))
                    .collect(),
                gap: Some((0..=10).map(f64::from).collect()),
            }],
            ..Recording::default()
        };
        let d = rec.decimated(30.0);
        assert_eq!(d.time, [0.0, 0.04, 0.08, 0.1]);
        // the forces and gaps of the kept rows
        let f: Vec<f64> = d.contacts[0].f.iter().map(|f| f.z).collect();
        assert_eq!(f, [0.0, 4.0, 8.0, 10.0]);
        assert_eq!(
            d.contacts[0].gap.as_deref(),
            Some(&[0.0, 4.0, 8.0, 10.0][..])
        );
        assert_eq!(d.time[0], 0.0);
        assert_eq!(*d.time.last().unwrap(), 0.1);
        assert_eq!(rec.decimated(0.0).time.len(), 11);
    }
}
