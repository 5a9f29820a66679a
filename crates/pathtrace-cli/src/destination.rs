//! Checking every output destination before any work starts: a render of minutes must not end in
//! "cannot write". Each output option (`-o`, `--spp-image`, `--stats-json`, `compare --diff`) goes
//! through [`check_destination`]; image outputs also through [`check_image_destination`].

use std::fs::{self, OpenOptions};
use std::io::Write;
use std::path::Path;

use crate::CliError;
use pathtrace_scene::image_io::ImageFormat;

/// Refuses `path` as the destination of `what` (e.g. "--stats-json") unless a file can be written
/// there: its folder exists, it is not a folder, and a probe write succeeds.
pub fn check_destination(path: &Path, what: &str) -> Result<(), CliError> {
    let refuse = |why: String| Err(CliError::usage(format!("{what}: cannot write {}: {why}", path.display())));
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    if !dir.is_dir() {
        return refuse(format!("folder {} does not exist", dir.display()));
    }
    match fs::metadata(path) {
        Ok(meta) if meta.is_dir() => refuse("it is a folder".to_owned()),
        Ok(meta) if meta.is_file() => match OpenOptions::new().append(true).open(path) {
            Ok(_) => Ok(()),
            Err(e) => refuse(e.to_string()),
        },
        Ok(_) => probe_device(path).or_else(|e| refuse(e.to_string())),
        Err(_) => probe_new_file(dir).or_else(|e| refuse(e.to_string())),
    }
}

/// [`check_destination`] for an image, whose format its extension names.
pub fn check_image_destination(path: &Path, what: &str) -> Result<(), CliError> {
    ImageFormat::from_path(path).map_err(|e| CliError::usage(format!("{what}: {e}")))?;
    check_destination(path, what)
}

/// A device such as `/dev/full` opens fine and fails on write: write one newline, which JSON and
/// text readers of `/dev/stdout` skip. (Files and folders never get here.)
fn probe_device(path: &Path) -> std::io::Result<()> {
    let mut device = OpenOptions::new().append(true).open(path)?;
    device.write_all(b"\n")?;
    device.flush()
}

/// Creates and removes a probe file in `dir`, as the real write will create its file there.
fn probe_new_file(dir: &Path) -> std::io::Result<()> {
    let probe = dir.join(format!(".pathtrace-probe.{}", std::process::id()));
    OpenOptions::new().write(true).create_new(true).open(&probe)?;
    fs::remove_file(probe)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_folders_folders_and_full_devices_are_refused() {
        let missing = check_destination(Path::new("/nonexistent-pathtrace/x.json"), "--stats-json").unwrap_err();
        assert!(missing.message.contains("does not exist") && missing.message.contains("--stats-json"), "{missing:?}");
        assert!(check_destination(Path::new("/"), "-o").is_err());
        if Path::new("/dev/full").exists() {
            let full = check_destination(Path::new("/dev/full"), "--stats-json").unwrap_err();
            assert_eq!(full.exit_code, 2);
        }
        assert!(check_image_destination(Path::new("x.txt"), "-o").is_err());
        assert!(check_destination(&std::env::temp_dir().join("pathtrace-dest-ok.json"), "--stats-json").is_ok());
    }
}
