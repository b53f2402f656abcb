//! Files that appear only on success: written under a temporary name beside the target and
//! renamed into place when complete; removed if dropped before.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// A file being written; becomes `target` on [`AtomicFile::commit`], vanishes otherwise.
pub struct AtomicFile {
    temp: PathBuf,
    target: PathBuf,
    committed: bool,
}

impl AtomicFile {
    /// Reserves a temporary path beside `target` (same extension, so format-sniffing writers
    /// such as the PNG encoder still work).
    pub fn new(target: &Path) -> Self {
        let name = target
            .file_name()
            .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
        let ext = target
            .extension()
            .map_or_else(String::new, |e| format!(".{}", e.to_string_lossy()));
        let temp = target.with_file_name(format!(".{name}.{}.tmp{ext}", std::process::id()));
        Self {
            temp,
            target: target.to_path_buf(),
            committed: false,
        }
    }

    /// The temporary path to write to.
    pub fn path(&self) -> &Path {
        &self.temp
    }

    /// Opens the temporary file for buffered writing.
    pub fn create(&self) -> Result<BufWriter<File>, String> {
        File::create(&self.temp)
            .map(BufWriter::new)
            .map_err(|e| format!("cannot write {}: {e}", self.target.display()))
    }

    /// Moves the finished file into place.
    pub fn commit(mut self) -> Result<(), String> {
        std::fs::rename(&self.temp, &self.target)
            .map_err(|e| format!("cannot write {}: {e}", self.target.display()))?;
        self.committed = true;
        Ok(())
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_file(&self.temp);
        }
    }
}

/// Flushes a buffered writer, naming the file on error.
pub fn finish(mut w: impl Write, what: &Path) -> Result<(), String> {
    w.flush()
        .map_err(|e| format!("cannot write {}: {e}", what.display()))
}
