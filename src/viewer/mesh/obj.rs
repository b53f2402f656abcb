//! Wavefront OBJ files through `tobj` (polygons triangulated; the diffuse colour of each
//! object's MTL material, when the MTL file is there).

use std::path::Path;

use super::trimesh::{MeshPart, TriMesh};

/// Reads an OBJ file (and its MTL file, if present; a missing MTL file only loses colours).
pub(super) fn load(path: &Path) -> Result<TriMesh, String> {
    let opts = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..tobj::LoadOptions::default()
    };
    let (models, materials) = tobj::load_obj(path, &opts).map_err(|e| match e {
        tobj::LoadError::OpenFileFailed => "cannot open the file".to_string(),
        e => format!("not a readable OBJ file: {e}"),
    })?;
    let materials = materials.unwrap_or_default();
    let parts = models
        .into_iter()
        .map(|m| {
            let rgba = m
                .mesh
                .material_id
                .and_then(|k| materials.get(k))
                .and_then(|mat| {
                    mat.diffuse
                        .map(|[r, g, b]| [r, g, b, mat.dissolve.unwrap_or(1.0)])
                });
            MeshPart {
                positions: m
                    .mesh
                    .positions
                    .chunks_exact(3)
                    .map(|p| [p[0], p[1], p[2]])
                    .collect(),
                indices: m.mesh.indices,
                rgba,
            }
        })
        .collect();
    Ok(TriMesh { parts })
}
