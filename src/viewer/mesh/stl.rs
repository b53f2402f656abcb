//! STL files (ASCII or binary) through `stl_io`, which also merges repeated vertices.

use std::path::Path;

use super::trimesh::{MeshPart, TriMesh};

/// Reads an STL file.
pub(super) fn load(path: &Path) -> Result<TriMesh, String> {
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    let mut reader = std::io::BufReader::new(file);
    let stl = stl_io::read_stl(&mut reader).map_err(|e| format!("not a readable STL file: {e}"))?;
    let indices = stl
        .faces
        .iter()
        .flat_map(|f| f.vertices)
        .map(|i| u32::try_from(i).map_err(|_| "too many vertices".to_string()))
        .collect::<Result<_, _>>()?;
    Ok(TriMesh {
        parts: vec![MeshPart {
            positions: stl.vertices.iter().map(|v| v.0).collect(),
            indices,
            rgba: None,
        }],
    })
}
