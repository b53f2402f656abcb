//! Reading a mesh file by its extension, with the checks every format shares.

use std::path::Path;

use super::trimesh::{MeshPart, TriMesh};
use super::{dae, obj, stl};

/// Reads the mesh file `path` by its extension (`.stl`, `.obj`, `.dae`, any case).
///
/// # Errors
/// A message saying why the file cannot be read (missing, unknown format, malformed, empty).
pub fn load(path: &Path) -> Result<TriMesh, String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or_default()
        .to_ascii_lowercase();
    let mesh = match ext.as_str() {
        "stl" => stl::load(path)?,
        "obj" => obj::load(path)?,
        "dae" => {
            let text = std::fs::read_to_string(path).map_err(|e| e.to_string())?;
            dae::parse(&text)?
        }
        _ => {
            return Err(format!(
                "unknown mesh format .{ext} (triad reads .stl, .obj and .dae)"
            ))
        }
    };
    let mut mesh = mesh;
    mesh.parts.retain(|p| !p.indices.is_empty());
    if mesh.parts.is_empty() {
        return Err("the file holds no triangles".into());
    }
    let n = |p: &MeshPart| p.positions.len();
    if mesh
        .parts
        .iter()
        .any(|p| p.indices.iter().any(|&i| i as usize >= n(p)))
    {
        return Err("a triangle refers to a vertex the file does not have".into());
    }
    if mesh
        .parts
        .iter()
        .any(|p| p.positions.iter().flatten().any(|x| !x.is_finite()))
    {
        return Err("a vertex is not finite".into());
    }
    Ok(mesh)
}
