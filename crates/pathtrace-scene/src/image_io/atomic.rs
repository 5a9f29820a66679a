//! Writing a file through a temporary sibling and a rename, so the destination is
//! either left untouched or replaced by a complete file.

use std::ffi::OsString;
use std::fs::{self, File, OpenOptions};
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use super::ImageIoError;

/// Distinguishes temporary files made by concurrent writes within one process.
static NEXT_TEMP_ID: AtomicU64 = AtomicU64::new(0);

/// Calls `write` on a buffered temporary file in `path`'s directory, then flushes,
/// syncs and renames it onto `path`. On any failure (or a panic inside `write`) the
/// temporary file is removed and `path` is left as it was.
pub(crate) fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<File>) -> Result<(), ImageIoError>,
) -> Result<(), ImageIoError> {
    super::stale_temps::remove_stale_temps(path);
    let (temp, file) = TempFile::create(path)?;
    let mut writer = BufWriter::new(file);
    write(&mut writer)?;
    let file = writer.into_inner().map_err(|e| ImageIoError::io(path, "write", e.into_error()))?;
    file.sync_all().map_err(|e| ImageIoError::io(path, "write", e))?;
    drop(file);
    temp.persist(path)
}

/// A temporary file's path; the file is deleted on drop unless persisted.
struct TempFile {
    path: Option<PathBuf>,
}

impl TempFile {
    /// Creates `.<name>.<pid>.<n>.tmp` next to `target`, failing if it already exists.
    fn create(target: &Path) -> Result<(TempFile, File), ImageIoError> {
        let name = target.file_name().ok_or_else(|| ImageIoError::NotAFilePath { path: target.to_path_buf() })?;
        let mut temp_name = OsString::from(".");
        temp_name.push(name);
        temp_name.push(format!(".{}.{}.tmp", std::process::id(), NEXT_TEMP_ID.fetch_add(1, Ordering::Relaxed)));
        let path = target.with_file_name(temp_name);
        let file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&path)
            .map_err(|e| ImageIoError::io(target, "create a temporary file for", e))?;
        Ok((TempFile { path: Some(path) }, file))
    }

    /// Renames the temporary file onto `target`.
    fn persist(mut self, target: &Path) -> Result<(), ImageIoError> {
        if let Some(path) = &self.path {
            fs::rename(path, target).map_err(|e| ImageIoError::io(target, "rename into", e))?;
        }
        // Renamed away: nothing left to delete.
        self.path = None;
        Ok(())
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        if let Some(path) = self.path.take() {
            // Best effort: the error that got us here is the one worth reporting.
            let _ = fs::remove_file(path);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_io::scratch::ScratchDir;
    use std::io::Write as _;

    #[test]
    fn success_replaces_target_and_leaves_no_temp() {
        let dir = ScratchDir::new("atomic-ok");
        let target = dir.path().join("out.bin");
        fs::write(&target, b"old").unwrap();
        write_atomically(&target, |w| w.write_all(b"new contents").map_err(|e| ImageIoError::io(&target, "write", e)))
            .unwrap();
        assert_eq!(fs::read(&target).unwrap(), b"new contents");
        assert_eq!(dir.entries(), ["out.bin"]);
    }

    #[test]
    fn failure_keeps_old_target_and_removes_temp() {
        let dir = ScratchDir::new("atomic-fail");
        let target = dir.path().join("out.bin");
        fs::write(&target, b"old").unwrap();
        let result = write_atomically(&target, |w| {
            w.write_all(b"partial").unwrap();
            Err(ImageIoError::InvalidPfm { path: target.clone(), reason: "simulated".into() })
        });
        assert!(result.is_err());
        assert_eq!(fs::read(&target).unwrap(), b"old");
        assert_eq!(dir.entries(), ["out.bin"]);
    }

    #[test]
    fn rename_onto_a_directory_fails_cleanly() {
        let dir = ScratchDir::new("atomic-dir");
        let target = dir.path().join("sub");
        fs::create_dir(&target).unwrap();
        fs::write(target.join("keep"), b"x").unwrap();
        let err = write_atomically(&target, |_| Ok(())).unwrap_err();
        assert!(err.to_string().contains("sub"), "{err}");
        assert_eq!(dir.entries(), ["sub"]);
    }

    #[test]
    fn path_without_file_name_is_rejected() {
        let err = write_atomically(Path::new("/"), |_| Ok(())).unwrap_err();
        assert!(matches!(err, ImageIoError::NotAFilePath { .. }), "{err}");
    }
}
