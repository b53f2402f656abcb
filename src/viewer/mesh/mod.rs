//! Mesh files for the viewer: finding them (`package://`, relative, absolute, `file://`) and
//! reading STL (ASCII and binary), Wavefront OBJ (with its MTL colours) and COLLADA (`.dae`:
//! triangles, polylists and polygons, node transforms, `<unit>` and `<up_axis>`, diffuse
//! colours) into triangle lists.

mod dae;
mod dae_tree;
mod load;
mod obj;
mod resolve;
mod stl;
mod trimesh;

pub use load::load;
pub use resolve::MeshPaths;
pub use trimesh::{MeshPart, TriMesh};
