//! Making a page: decimate the recording, build the scene, encode, assemble.

use std::path::{Path, PathBuf};

use super::csv::ResultTable;
use super::error::ViewerError;
use super::html::page;
use super::mesh::MeshPaths;
use super::payload::encode;
use super::recording::Recording;
use super::scene::Scene;
use crate::spec::Spec;

/// How a replay is made.
#[derive(Clone, Debug)]
pub struct Options {
    /// Most frames kept per second of recorded time (decimation of denser recordings).
    pub max_rate: f64,
    /// Folders holding ROS packages (or being one), searched first for `package://` meshes.
    pub package_dirs: Vec<PathBuf>,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            max_rate: 100.0,
            package_dirs: Vec::new(),
        }
    }
}

/// A finished page and what it says about itself.
#[derive(Clone, Debug)]
pub struct Page {
    /// The whole HTML document.
    pub html: String,
    /// Frames in the page (after decimation).
    pub frames: usize,
    /// Warnings (a mesh that could not be read and what is drawn instead), one line each.
    pub warnings: Vec<String>,
}

/// The page replaying `recording` of `spec`; meshes are looked up relative to `model_dir` (the
/// folder of the model file, if any), in `opts.package_dirs` and the usual environment
/// variables ([`MeshPaths::new`]).
#[must_use]
pub fn replay(
    spec: &Spec,
    model_dir: Option<&Path>,
    recording: &Recording,
    opts: &Options,
) -> Page {
    let recording = recording.decimated(opts.max_rate);
    let paths = MeshPaths::new(model_dir, &opts.package_dirs);
    let scene = Scene::new(spec, &recording, &paths);
    let json = encode(&spec.name, &scene, &recording);
    Page {
        html: page(&spec.name, &json),
        frames: recording.time.len(),
        warnings: scene.warnings,
    }
}

/// The page replaying the result CSV `csv` of `spec` (see [`replay`]).
///
/// # Errors
/// An unreadable or malformed CSV, a CSV without poses, or one of another model
/// ([`ViewerError`]).
pub fn replay_csv(
    spec: &Spec,
    model_dir: Option<&Path>,
    csv: &Path,
    opts: &Options,
) -> Result<Page, ViewerError> {
    let table = ResultTable::read(csv, &Recording::reads)?;
    let recording = Recording::from_table(&table, spec)?;
    Ok(replay(spec, model_dir, &recording, opts))
}
