//! What the page draws: every body's shapes in its body frame, the shapes fixed in the world,
//! the sites, and the meshes they use. Shapes come from the spec's `[[visual]]` entries (a
//! URDF's `<visual>` elements); a body without any, or whose mesh cannot be read, gets its
//! default shape ([`super::defaults`]), whose inertia box gives way to the body's collision
//! shapes if it has any. The ground, the collision shapes and the force arrows' scale come
//! from [`super::contact`].

use std::collections::HashMap;
use std::path::PathBuf;

use super::contact::{self, CollisionShape, ForceScale, GroundPlane};
use super::defaults;
use super::mesh::{self, MeshPaths, TriMesh};
use super::recording::Recording;
use super::shape::{Geometry, Shape};
use crate::math::{rpy_to_matrix, Mat3, Vec3};
use crate::spec::{Spec, VisualSpec};

/// A body's shapes.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyShapes {
    /// The body's name.
    pub name: String,
    /// Its shapes, in its body frame.
    pub shapes: Vec<Shape>,
}

/// A site: a frame fixed on a body.
#[derive(Clone, Debug, PartialEq)]
pub struct SiteFrame {
    /// The site's name.
    pub name: String,
    /// Index of its body in [`Scene::bodies`].
    pub body: usize,
    /// Its origin in the body frame, m.
    pub xyz: Vec3,
    /// Rotation body ← site.
    pub rot: Mat3,
}

/// Everything drawn, in body frames; the recording places the bodies.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scene {
    /// One entry per body of the model, in the spec's order.
    pub bodies: Vec<BodyShapes>,
    /// Shapes fixed in the world frame (a URDF's welded base).
    pub world: Vec<Shape>,
    /// The sites.
    pub sites: Vec<SiteFrame>,
    /// The meshes the shapes use.
    pub meshes: Vec<TriMesh>,
    /// The model's size, m: the diagonal of the box holding the body origins over the
    /// recording and the joints and centres of mass at its start (at least 0.1 m); sizes
    /// the default shapes, the frames drawn and the camera.
    pub length: f64,
    /// What could not be drawn as asked (missing or unreadable meshes), one line each.
    pub warnings: Vec<String>,
    /// The ground plane (`[ground]`).
    pub ground: Option<GroundPlane>,
    /// The collision shapes (`[[collision]]`), drawn on demand.
    pub collisions: Vec<CollisionShape>,
    /// The scale of the contact-force arrows.
    pub forces: ForceScale,
}

impl Scene {
    /// The scene of `spec` for `recording` (which gives the model's size), meshes looked up
    /// in `paths`.
    #[must_use]
    pub fn new(spec: &Spec, recording: &Recording, paths: &MeshPaths) -> Self {
        let length = defaults::model_length(spec, recording);
        let collisions = contact::collision_shapes(spec);
        let (ground, warning) = contact::ground(spec, recording, &collisions);
        let mut scene = Self {
            length,
            ground,
            collisions,
            forces: contact::force_scale(spec, recording, length),
            warnings: warning.into_iter().collect(),
            ..Self::default()
        };
        let mut loaded: HashMap<PathBuf, Result<usize, String>> = HashMap::new();
        let mut fallback = vec![false; spec.body.len()];
        let mut shapes: Vec<Vec<Shape>> = vec![Vec::new(); spec.body.len()];
        for (i, v) in spec.visual.iter().enumerate() {
            let host = spec.body.iter().position(|b| b.name == v.body);
            let geometry = match scene.geometry(v, paths, &mut loaded) {
                Ok(g) => g,
                Err(why) => {
                    let whose = host.map_or("the world".to_string(), |b| {
                        format!("body {}", spec.body[b].name)
                    });
                    let instead = if host.is_some() {
                        "its default shape is drawn instead"
                    } else {
                        "left out"
                    };
                    scene.warnings.push(format!(
                        "visual[{i}] of {whose}: mesh {}: {why}; {instead}",
                        v.mesh.as_deref().unwrap_or("")
                    ));
                    if let Some(b) = host {
                        fallback[b] = true;
                    }
                    continue;
                }
            };
            let shape = Shape {
                geometry,
                xyz: Vec3::from(v.origin.xyz),
                rot: rpy_to_matrix(&Vec3::from(v.origin.rpy)),
                rgba: v.rgba,
                default: false,
                faceted: false,
            };
            match host {
                Some(b) => shapes[b].push(shape),
                None => scene.world.push(shape),
            }
        }
        for (b, body) in spec.body.iter().enumerate() {
            let mut own = std::mem::take(&mut shapes[b]);
            if own.is_empty() || fallback[b] {
                let collision: Vec<Shape> = scene
                    .collisions
                    .iter()
                    .filter(|c| c.body == b)
                    .map(|c| Shape {
                        faceted: true,
                        ..c.shape.clone()
                    })
                    .collect();
                own.extend(defaults::shapes(spec, b, length, collision.is_empty()));
                own.extend(collision);
            }
            scene.bodies.push(BodyShapes {
                name: body.name.clone(),
                shapes: own,
            });
        }
        scene.sites = spec
            .site
            .iter()
            .filter_map(|s| {
                Some(SiteFrame {
                    name: s.name.clone(),
                    body: spec.body.iter().position(|b| b.name == s.body)?,
                    xyz: Vec3::from(s.origin.xyz),
                    rot: rpy_to_matrix(&Vec3::from(s.origin.rpy)),
                })
            })
            .collect();
        scene
    }

    /// The geometry of a `[[visual]]`, loading its mesh (once per file).
    fn geometry(
        &mut self,
        v: &VisualSpec,
        paths: &MeshPaths,
        loaded: &mut HashMap<PathBuf, Result<usize, String>>,
    ) -> Result<Geometry, String> {
        if let Some(s) = v.cuboid {
            return Ok(Geometry::Cuboid(s));
        }
        if let Some([radius, length]) = v.cylinder {
            return Ok(Geometry::Cylinder { radius, length });
        }
        if let Some(r) = v.sphere {
            return Ok(Geometry::Sphere(r));
        }
        let uri = v.mesh.as_deref().unwrap_or_default();
        let path = paths.resolve(uri)?;
        let index = loaded
            .entry(path.clone())
            .or_insert_with(|| {
                mesh::load(&path)
                    .map(|m| {
                        self.meshes.push(m);
                        self.meshes.len() - 1
                    })
                    .map_err(|e| format!("{}: {e}", path.display()))
            })
            .clone()?;
        Ok(Geometry::Mesh {
            index,
            scale: v.scale.unwrap_or([1.0; 3]),
        })
    }
}
