//! Triangle meshes as read from files: parts of one colour each.

/// A triangle mesh in the frame of its file, m (the file's unit applied), in parts that each
/// have one colour.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriMesh {
    /// The parts.
    pub parts: Vec<MeshPart>,
}

/// Part of a [`TriMesh`]: vertices, triangles and the colour the file gives it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshPart {
    /// Vertex positions, m.
    pub positions: Vec<[f32; 3]>,
    /// Three vertex indices per triangle (counter-clockwise seen from outside).
    pub indices: Vec<u32>,
    /// Red, green, blue, alpha in [0, 1], if the file gives a colour.
    pub rgba: Option<[f32; 4]>,
}

impl TriMesh {
    /// Number of triangles over all parts.
    #[must_use]
    pub fn triangles(&self) -> usize {
        self.parts.iter().map(|p| p.indices.len() / 3).sum()
    }
}
