//! Reading and writing `.ptfilm` files (the byte format is the engine's, `film/file.rs`), and
//! the scene half of a film's key: a hash of the scene's source, the same for the CLI and the
//! Python module, so parts rendered by either merge.

use crate::image_io::{write_atomically, ImageIoError};
use pathtrace::film::{FilmFileError, Fnv64, RangedFilm};
use std::io::Write;
use std::path::Path;

/// Writes `film` to `path` atomically (a complete file or the old one, never a partial one).
pub fn write_film(path: &Path, film: &RangedFilm) -> Result<(), ImageIoError> {
    let bytes = film.to_bytes();
    write_atomically(path, |out| out.write_all(&bytes).map_err(|e| ImageIoError::io(path, "write", e)))
}

/// Why a film file cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum ReadFilmError {
    #[error("{}: cannot read: {source}", path.display())]
    Io { path: std::path::PathBuf, source: std::io::Error },
    #[error("{}: {source}", path.display())]
    Format { path: std::path::PathBuf, source: FilmFileError },
}

/// Reads a film file; the error names the file and what is wrong with it.
pub fn read_film(path: &Path) -> Result<RangedFilm, ReadFilmError> {
    let bytes = std::fs::read(path).map_err(|source| ReadFilmError::Io { path: path.to_path_buf(), source })?;
    RangedFilm::from_bytes(&bytes).map_err(|source| ReadFilmError::Format { path: path.to_path_buf(), source })
}

/// What a scene was built from.
pub enum SceneSource<'a> {
    /// A scene file's bytes and the `-D` defines it was loaded with. Files it refers to (meshes,
    /// textures) are not hashed: a farm must give every machine the same copies.
    File { bytes: &'a [u8], defines: &'a [(String, String)] },
    /// Native JSON text.
    Text(&'a str),
    /// A built-in scene's name.
    Builtin(&'a str),
}

/// The hash of a scene's source ([`pathtrace::film::render_key`] adds the settings).
pub fn scene_source_key(source: &SceneSource) -> u64 {
    let mut h = Fnv64::default();
    match source {
        SceneSource::File { bytes, defines } => {
            h.field(b"file").field(bytes);
            for (name, value) in defines.iter() {
                h.field(name.as_bytes()).field(value.as_bytes());
            }
        }
        SceneSource::Text(text) => {
            h.field(b"text").field(text.as_bytes());
        }
        SceneSource::Builtin(name) => {
            h.field(b"builtin").field(name.as_bytes());
        }
    }
    h.finish()
}
