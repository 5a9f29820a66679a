//! Where the Open Image Denoise library is looked for:
//! - with `OIDN_DIR` set, only in `$OIDN_DIR/lib/libOpenImageDenoise.so*` (the folder convention of
//!   the `oidn` crate): an explicit choice is never overridden by another install;
//! - otherwise in the system's library search path (`libOpenImageDenoise.so.2` by name, as
//!   `dlopen` finds it), then in an installed `pyoidn` wheel (`pyoidn/oidn/lib`) of the active
//!   virtual environment, the user's site-packages or the system's Python folders.

use crate::oidn::Api;
use crate::DenoiseError;
use std::path::{Path, PathBuf};

/// The file names tried in each folder (OIDN 2's soname first).
pub const LIBRARY_NAMES: [&str; 2] = ["libOpenImageDenoise.so.2", "libOpenImageDenoise.so"];

/// The library files that would be tried, in order: `OIDN_DIR`'s two names when it is set;
/// otherwise the bare soname (which the system's loader resolves) and the `pyoidn` copies that
/// exist.
pub fn candidates() -> Vec<PathBuf> {
    if let Some(d) = std::env::var_os("OIDN_DIR") {
        let lib = Path::new(&d).join("lib");
        return LIBRARY_NAMES.map(|n| lib.join(n)).into();
    }
    let mut out = vec![PathBuf::from(LIBRARY_NAMES[0])];
    for site in python_site_dirs() {
        let lib = site.join("pyoidn/oidn/lib");
        out.extend(LIBRARY_NAMES.map(|n| lib.join(n)).into_iter().filter(|p| p.is_file()));
    }
    out
}

/// Python package folders where `pip install pyoidn` may have put the wheel.
fn python_site_dirs() -> Vec<PathBuf> {
    let mut roots: Vec<PathBuf> = Vec::new();
    if let Some(v) = std::env::var_os("VIRTUAL_ENV") {
        roots.push(PathBuf::from(v).join("lib"));
    }
    if let Some(h) = std::env::var_os("HOME") {
        roots.push(PathBuf::from(h).join(".local/lib"));
    }
    roots.extend(["/usr/local/lib", "/usr/lib"].map(PathBuf::from));
    let mut out = Vec::new();
    for root in roots {
        let Ok(entries) = std::fs::read_dir(&root) else { continue };
        let mut pythons: Vec<PathBuf> = entries
            .flatten()
            .map(|e| e.path())
            .filter(|p| p.file_name().and_then(|n| n.to_str()).is_some_and(|n| n.starts_with("python3")))
            .collect();
        pythons.sort();
        for p in pythons {
            out.push(p.join("site-packages"));
            out.push(p.join("dist-packages"));
        }
    }
    out
}

/// Loads the first candidate that opens. A file that exists but fails to load is reported as
/// such (a broken install), not skipped.
pub(crate) fn load() -> Result<(PathBuf, Api), DenoiseError> {
    let mut searched = Vec::new();
    for path in candidates() {
        match Api::load(&path) {
            Ok(api) => return Ok((path, api)),
            Err(message) if path.is_file() => return Err(DenoiseError::Load { path, message }),
            Err(_) => searched.push(path),
        }
    }
    Err(DenoiseError::NotFound { searched })
}
