//! The 3-D replay (`triad animate`, `simulate --animate`, the FMU's `documentation/scene.html`):
//! one self-contained HTML page that places the model's bodies from recorded poses only
//! (`body.B.r[i]`, `body.B.R[i,j]` of a result CSV) and draws them with three.js, inlined.
//!
//! The viewer reads results and geometry; it knows nothing of the integrator. Its parts:
//! `csv` (the result CSV), `recording` (the poses and plotted signals, checked against the
//! model), `scene` and `defaults` (what each body looks like: its `[[visual]]` shapes, or a
//! default drawn from its joints and inertia), `contact` (the ground, the collision shapes and
//! the scale of the contact-force arrows), `mesh` (finding and reading STL, OBJ and DAE
//! files), `payload` (the data embedded in the page), `html` (the page).
//!
//! Sizes: a frame costs 8 bytes of time plus, per body, 24 bytes of position (`f64`) and 16 of
//! orientation (`f32` quaternion), base64-encoded (×4/3); [`Options::max_rate`] (default
//! 100 frames per second of recorded time) decimates longer or denser recordings. Mesh
//! vertices are quantised to 16 bits over their bounding box (6 bytes a vertex) and each mesh
//! file is stored once however many shapes use it. Contact forces (`contact.C.f[1..3]`) cost
//! 12 bytes a frame per collision shape (`f32`).

mod contact;
mod csv;
mod defaults;
mod error;
mod html;
mod mesh;
mod payload;
mod recording;
mod replay;
mod scene;
mod shape;

pub use contact::{ground_normal, CollisionShape, ForceBasis, ForceScale, GroundPlane};
pub use csv::ResultTable;
pub use error::ViewerError;
pub use html::{page, payload_of};
pub use mesh::{load as load_mesh, MeshPart, MeshPaths, TriMesh};
pub use payload::{decode, encode, DecodedPoses, FORMAT};
pub use recording::{BodyTrack, ContactTrack, Recording, Signal, SignalKind};
pub use replay::{replay, replay_csv, Options, Page};
pub use scene::{BodyShapes, Scene, SiteFrame};
pub use shape::{Geometry, Shape};
