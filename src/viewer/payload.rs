//! The data embedded in the page: one JSON object whose bulk arrays are base64 strings of
//! little-endian numbers. Body positions are `f64` (exact); orientations are unit quaternions
//! `[x, y, z, w]` in `f32`, sign-continuous over time (≤ 2e-7 rad from the recorded rotation);
//! signals and contact forces are `f32` (a force's components within 6e-8 of their own size);
//! mesh vertices are quantised to `u16` over each part's bounding box (a step of 1/65535 of
//! the box) with `u16` or `u32` indices. [`decode`] reads the poses and forces back.

use base64::engine::general_purpose::STANDARD;
use base64::Engine as _;
use serde::Serialize;
use serde_json::Value;

use super::contact::ForceBasis;
use super::mesh::MeshPart;
use super::recording::{Recording, SignalKind};
use super::scene::Scene;
use super::shape::{Geometry, Shape};
use crate::math::{matrix_to_quat, quat_to_matrix, Mat3, Vec3};

/// Version of the payload's layout, read by `viewer.js`.
pub const FORMAT: u32 = 1;

#[derive(Serialize)]
struct Payload<'a> {
    format: u32,
    name: &'a str,
    length: f64,
    frames: usize,
    time: String,
    bodies: Vec<BodyOut<'a>>,
    world: Vec<ShapeOut>,
    sites: Vec<SiteOut<'a>>,
    signals: Vec<SignalOut<'a>>,
    meshes: Vec<Vec<PartOut>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    ground: Option<GroundOut>,
    contacts: Vec<ContactOut<'a>>,
    forces: ForcesOut,
}

#[derive(Serialize)]
struct GroundOut {
    normal: [f64; 3],
    height: f64,
}

#[derive(Serialize)]
struct ContactOut<'a> {
    name: &'a str,
    body: usize,
    shape: ShapeOut,
    /// `contact.C.f` per frame (3 `f32` each), if recorded.
    #[serde(skip_serializing_if = "Option::is_none")]
    f: Option<String>,
}

#[derive(Serialize)]
struct ForcesOut {
    /// N per m of arrow.
    scale: f64,
    /// The force the scale was chosen from, N.
    reference: f64,
    /// `weight`, `largest` or `unit`.
    basis: &'static str,
}

#[derive(Serialize)]
struct BodyOut<'a> {
    name: &'a str,
    r: String,
    q: String,
    shapes: Vec<ShapeOut>,
}

#[derive(Serialize)]
struct ShapeOut {
    kind: &'static str,
    size: Vec<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    mesh: Option<usize>,
    xyz: [f64; 3],
    q: [f64; 4],
    #[serde(skip_serializing_if = "Option::is_none")]
    rgba: Option<[f64; 4]>,
    default: bool,
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    faceted: bool,
}

#[derive(Serialize)]
struct SiteOut<'a> {
    name: &'a str,
    body: usize,
    xyz: [f64; 3],
    q: [f64; 4],
}

#[derive(Serialize)]
struct SignalOut<'a> {
    name: &'a str,
    unit: &'a str,
    kind: &'static str,
    scale: f64,
    values: String,
}

#[derive(Serialize)]
struct PartOut {
    min: [f32; 3],
    max: [f32; 3],
    positions: String,
    indices: String,
    wide: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    rgba: Option<[f32; 4]>,
}

fn b64_f64(x: impl Iterator<Item = f64>) -> String {
    STANDARD.encode(x.flat_map(f64::to_le_bytes).collect::<Vec<u8>>())
}

#[allow(clippy::cast_possible_truncation)]
fn b64_f32(x: impl Iterator<Item = f64>) -> String {
    STANDARD.encode(
        x.flat_map(|v| (v as f32).to_le_bytes())
            .collect::<Vec<u8>>(),
    )
}

/// `[x, y, z, w]` of a rotation (three.js order).
fn xyzw(rot: &Mat3) -> [f64; 4] {
    let [w, x, y, z] = matrix_to_quat(rot);
    [x, y, z, w]
}

fn shape(s: &Shape) -> ShapeOut {
    let (kind, size, mesh) = match &s.geometry {
        Geometry::Cuboid(d) => ("box", d.to_vec(), None),
        Geometry::Cylinder { radius, length } => ("cylinder", vec![*radius, *length], None),
        Geometry::Sphere(r) => ("sphere", vec![*r], None),
        Geometry::Capsule { radius, length } => ("capsule", vec![*radius, *length], None),
        Geometry::Mesh { index, scale } => ("mesh", scale.to_vec(), Some(*index)),
    };
    ShapeOut {
        kind,
        size,
        mesh,
        xyz: s.xyz.into(),
        q: xyzw(&s.rot),
        rgba: s.rgba,
        default: s.default,
        faceted: s.faceted,
    }
}

/// A mesh part with its vertices quantised over its bounding box.
#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
fn part(p: &MeshPart) -> PartOut {
    let mut min = [f32::INFINITY; 3];
    let mut max = [f32::NEG_INFINITY; 3];
    for v in &p.positions {
        for k in 0..3 {
            min[k] = min[k].min(v[k]);
            max[k] = max[k].max(v[k]);
        }
    }
    let mut bytes = Vec::with_capacity(p.positions.len() * 6);
    for v in &p.positions {
        for k in 0..3 {
            let span = max[k] - min[k];
            let u = if span > 0.0 {
                ((v[k] - min[k]) / span * 65535.0).round()
            } else {
                0.0
            };
            bytes.extend_from_slice(&(u.clamp(0.0, 65535.0) as u16).to_le_bytes());
        }
    }
    let wide = p.positions.len() > 65536;
    let indices: Vec<u8> = if wide {
        p.indices.iter().flat_map(|i| i.to_le_bytes()).collect()
    } else {
        p.indices
            .iter()
            .flat_map(|&i| (i as u16).to_le_bytes())
            .collect()
    };
    PartOut {
        min,
        max,
        positions: STANDARD.encode(bytes),
        indices: STANDARD.encode(indices),
        wide,
        rgba: p.rgba,
    }
}

/// The payload JSON of `scene` replaying `recording` (whose bodies are the scene's, in order).
#[must_use]
pub fn encode(name: &str, scene: &Scene, recording: &Recording) -> String {
    let bodies = scene
        .bodies
        .iter()
        .zip(&recording.bodies)
        .map(|(s, t)| {
            // sign-continuous quaternions, so that the page can interpolate between frames
            let mut prev = [0.0, 0.0, 0.0, 1.0];
            let q: Vec<f64> = t
                .rot
                .iter()
                .flat_map(|rot| {
                    let mut q = xyzw(rot);
                    if q.iter().zip(&prev).map(|(a, b)| a * b).sum::<f64>() < 0.0 {
                        q = q.map(|x| -x);
                    }
                    prev = q;
                    q
                })
                .collect();
            BodyOut {
                name: &s.name,
                r: b64_f64(t.r.iter().flat_map(|r| [r.x, r.y, r.z])),
                q: b64_f32(q.into_iter()),
                shapes: s.shapes.iter().map(shape).collect(),
            }
        })
        .collect();
    let payload = Payload {
        format: FORMAT,
        name,
        length: scene.length,
        frames: recording.time.len(),
        time: b64_f64(recording.time.iter().copied()),
        bodies,
        world: scene.world.iter().map(shape).collect(),
        sites: scene
            .sites
            .iter()
            .map(|s| SiteOut {
                name: &s.name,
                body: s.body,
                xyz: s.xyz.into(),
                q: xyzw(&s.rot),
            })
            .collect(),
        signals: recording
            .signals
            .iter()
            .map(|s| SignalOut {
                name: &s.name,
                unit: s.unit,
                kind: match s.kind {
                    SignalKind::Coordinate => "coordinate",
                    SignalKind::Balance => "balance",
                },
                scale: s.scale,
                values: b64_f32(s.values.iter().copied()),
            })
            .collect(),
        meshes: scene
            .meshes
            .iter()
            .map(|m| m.parts.iter().map(part).collect())
            .collect(),
        ground: scene.ground.map(|g| GroundOut {
            normal: g.normal.into(),
            height: g.height,
        }),
        contacts: scene
            .collisions
            .iter()
            .map(|c| ContactOut {
                name: &c.name,
                body: c.body,
                shape: shape(&c.shape),
                f: recording
                    .contacts
                    .iter()
                    .find(|t| t.name == c.name)
                    .map(|t| b64_f32(t.f.iter().flat_map(|f| [f.x, f.y, f.z]))),
            })
            .collect(),
        forces: ForcesOut {
            scale: scene.forces.newtons_per_metre,
            reference: scene.forces.reference,
            basis: match scene.forces.basis {
                ForceBasis::Weight => "weight",
                ForceBasis::Largest => "largest",
                ForceBasis::Unit => "unit",
            },
        },
    };
    serde_json::to_string(&payload).unwrap_or_default()
}

/// The poses and contact forces of a payload, read back as the page reads them.
#[derive(Clone, Debug, PartialEq)]
pub struct DecodedPoses {
    /// Frame times, s.
    pub time: Vec<f64>,
    /// Per body: name, origins (world frame, m) and rotations world ← body, one per frame.
    pub bodies: Vec<(String, Vec<Vec3>, Vec<Mat3>)>,
    /// Per collision shape with recorded forces: name and `contact.C.f` (world frame, N), one
    /// per frame.
    pub forces: Vec<(String, Vec<Vec3>)>,
}

fn bytes(v: &Value, what: &str) -> Result<Vec<u8>, String> {
    STANDARD
        .decode(v.as_str().ok_or(format!("{what}: not a string"))?)
        .map_err(|e| format!("{what}: {e}"))
}

/// Reads the times and body poses of a payload made by [`encode`].
///
/// # Errors
/// A message if the JSON is not such a payload.
pub fn decode(json: &str) -> Result<DecodedPoses, String> {
    let v: Value = serde_json::from_str(json).map_err(|e| e.to_string())?;
    let f64s = |b: Vec<u8>| -> Vec<f64> {
        b.chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap_or_default()))
            .collect()
    };
    let time = f64s(bytes(&v["time"], "time")?);
    let mut bodies = Vec::new();
    for b in v["bodies"].as_array().ok_or("no bodies")? {
        let name = b["name"]
            .as_str()
            .ok_or("a body without a name")?
            .to_string();
        let r: Vec<Vec3> = f64s(bytes(&b["r"], "r")?)
            .chunks_exact(3)
            .map(Vec3::from_column_slice)
            .collect();
        let rot: Vec<Mat3> = bytes(&b["q"], "q")?
            .chunks_exact(16)
            .map(|c| {
                let x: Vec<f64> = c
                    .chunks_exact(4)
                    .map(|f| f64::from(f32::from_le_bytes(f.try_into().unwrap_or_default())))
                    .collect();
                quat_to_matrix(&[x[3], x[0], x[1], x[2]])
            })
            .collect();
        if r.len() != time.len() || rot.len() != time.len() {
            return Err(format!(
                "body {name}: {} positions, {} rotations for {} times",
                r.len(),
                rot.len(),
                time.len()
            ));
        }
        bodies.push((name, r, rot));
    }
    let mut forces = Vec::new();
    for c in v["contacts"].as_array().map_or(&[][..], Vec::as_slice) {
        let name = c["name"]
            .as_str()
            .ok_or("a contact without a name")?
            .to_string();
        if c["f"].is_null() {
            continue;
        }
        let f: Vec<Vec3> = bytes(&c["f"], "f")?
            .chunks_exact(12)
            .map(|c| {
                Vec3::from_fn(|i, _| {
                    let b = &c[4 * i..4 * i + 4];
                    f64::from(f32::from_le_bytes(b.try_into().unwrap_or_default()))
                })
            })
            .collect();
        if f.len() != time.len() {
            return Err(format!(
                "contact {name}: {} forces for {} times",
                f.len(),
                time.len()
            ));
        }
        forces.push((name, f));
    }
    Ok(DecodedPoses {
        time,
        bodies,
        forces,
    })
}
