//! Where a mesh named in a model is: `package://PKG/REL` looked up in package folders,
//! `file://` and absolute paths as they are, anything else relative to the model file.

use std::path::{Path, PathBuf};

/// Environment variables whose folders hold packages (`DIR/PKG`), in the order searched.
pub const PACKAGE_PATH_VARIABLES: [&str; 4] = [
    "ROS_PACKAGE_PATH",
    "GAZEBO_MODEL_PATH",
    "GZ_SIM_RESOURCE_PATH",
    "IGN_GAZEBO_RESOURCE_PATH",
];

/// Environment variables whose folders are install prefixes (`PREFIX/share/PKG`).
pub const PREFIX_PATH_VARIABLES: [&str; 2] = ["AMENT_PREFIX_PATH", "COLCON_PREFIX_PATH"];

/// The places a mesh of a model is looked for.
#[derive(Clone, Debug, Default)]
pub struct MeshPaths {
    /// The model file's folder: relative paths start there, and `package://PKG` also matches
    /// a folder named PKG above it (or beside one of those), as in a source checkout.
    pub base: Option<PathBuf>,
    /// Folders that hold packages (`DIR/PKG/...`) or are one (`DIR` named PKG), searched first
    /// (`--package-path`), then those of `PACKAGE_PATH_VARIABLES`.
    pub package_dirs: Vec<PathBuf>,
    /// Install prefixes (`PREFIX/share/PKG/...`), from `PREFIX_PATH_VARIABLES`.
    pub prefixes: Vec<PathBuf>,
}

impl MeshPaths {
    /// The places for a model file in `base`: `package_dirs` (from the command line) first,
    /// then the folders named by the usual environment variables.
    #[must_use]
    pub fn new(base: Option<&Path>, package_dirs: &[PathBuf]) -> Self {
        let split = |var: &str| -> Vec<PathBuf> {
            std::env::var_os(var)
                .map(|v| {
                    std::env::split_paths(&v)
                        .filter(|p| !p.as_os_str().is_empty())
                        .collect()
                })
                .unwrap_or_default()
        };
        let mut dirs = package_dirs.to_vec();
        dirs.extend(PACKAGE_PATH_VARIABLES.iter().flat_map(|v| split(v)));
        Self {
            base: base.map(Path::to_path_buf),
            package_dirs: dirs,
            prefixes: PREFIX_PATH_VARIABLES
                .iter()
                .flat_map(|v| split(v))
                .collect(),
        }
    }

    /// The file that `uri` names, if it exists.
    ///
    /// # Errors
    /// A message naming the places tried (or why the URI cannot be resolved).
    pub fn resolve(&self, uri: &str) -> Result<PathBuf, String> {
        let tried = self.candidates(uri)?;
        tried.iter().find(|p| p.is_file()).cloned().ok_or_else(|| {
            let list: Vec<String> = tried.iter().map(|p| p.display().to_string()).collect();
            if let Some(pkg) = package_of(uri) {
                format!(
                    "not found (tried {}); give the folder of package '{pkg}' (or the folder \
                     holding it) with --package-path, or set ROS_PACKAGE_PATH",
                    list.join(", ")
                )
            } else {
                format!("not found (tried {})", list.join(", "))
            }
        })
    }

    /// The paths `uri` may stand for, most likely first.
    fn candidates(&self, uri: &str) -> Result<Vec<PathBuf>, String> {
        if let Some(rest) = uri.strip_prefix("package://") {
            let (pkg, rel) = rest.split_once('/').unwrap_or((rest, ""));
            if pkg.is_empty() || rel.is_empty() {
                return Err(format!("{uri}: a package URI is package://PACKAGE/PATH"));
            }
            let mut out = Vec::new();
            for d in &self.package_dirs {
                out.push(d.join(pkg).join(rel));
                if d.file_name().is_some_and(|n| n == pkg) {
                    out.push(d.join(rel));
                }
            }
            out.extend(
                self.prefixes
                    .iter()
                    .map(|p| p.join("share").join(pkg).join(rel)),
            );
            if let Some(base) = &self.base {
                for a in base.ancestors() {
                    if a.file_name().is_some_and(|n| n == pkg) {
                        out.push(a.join(rel));
                    }
                    out.push(a.join(pkg).join(rel));
                }
            }
            return Ok(out);
        }
        let path = uri.strip_prefix("file://").unwrap_or(uri);
        let path = Path::new(path);
        if path.is_absolute() {
            return Ok(vec![path.to_path_buf()]);
        }
        Ok(vec![self
            .base
            .as_ref()
            .map_or_else(|| path.to_path_buf(), |b| b.join(path))])
    }
}

/// The package of a `package://` URI.
fn package_of(uri: &str) -> Option<&str> {
    uri.strip_prefix("package://")
        .map(|r| r.split_once('/').map_or(r, |(p, _)| p))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn package_uri_in_a_package_dir_and_above_the_model() {
        let tmp = std::env::temp_dir().join(format!("triad_resolve_{}", std::process::id()));
        let mesh = tmp.join("src/my_robot/meshes/link.stl");
        std::fs::create_dir_all(mesh.parent().unwrap()).unwrap();
        std::fs::write(&mesh, "solid x\nendsolid x\n").unwrap();
        let urdf_dir = tmp.join("src/my_robot/urdf");
        std::fs::create_dir_all(&urdf_dir).unwrap();
        let uri = "package://my_robot/meshes/link.stl";
        // above the model file
        let paths = MeshPaths {
            base: Some(urdf_dir.clone()),
            ..MeshPaths::default()
        };
        assert_eq!(paths.resolve(uri).unwrap(), mesh);
        // a folder holding the package, and the package folder itself
        for dir in [tmp.join("src"), tmp.join("src/my_robot")] {
            let paths = MeshPaths {
                package_dirs: vec![dir],
                ..MeshPaths::default()
            };
            assert_eq!(paths.resolve(uri).unwrap(), mesh);
        }
        // relative to the model, and a miss that names what it tried
        let rel = MeshPaths {
            base: Some(urdf_dir),
            ..MeshPaths::default()
        };
        assert_eq!(
            rel.resolve("../meshes/link.stl").unwrap(),
            tmp.join("src/my_robot/urdf/../meshes/link.stl")
        );
        let e = MeshPaths::default()
            .resolve("package://other/x.stl")
            .unwrap_err();
        assert!(e.contains("--package-path"), "{e}");
        std::fs::remove_dir_all(&tmp).unwrap();
    }
}
