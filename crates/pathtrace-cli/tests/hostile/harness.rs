//! Running the binary on hostile input under a memory limit, and what every run must show: exit 0
//! or 2, no abort (134) or kill, and an error of one line that names where the problem is.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The address-space limit the binary runs under (`ulimit -v`, KiB): an allocation beyond it
/// fails at once, so a memory bomb shows as an abort instead of gigabytes resident.
pub const MEMORY_LIMIT_KIB: u64 = 2_000_000;

/// A fresh folder for one test's files.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pathtrace-hostile-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs `pathtrace ARGS` in `dir` under [`MEMORY_LIMIT_KIB`].
pub fn run_limited(dir: &Path, args: &[&str]) -> Output {
    Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {MEMORY_LIMIT_KIB} && exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_pathtrace"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

/// Asserts a clean refusal: exit 2 and one short error line containing each of `needles`.
pub fn assert_refused(o: &Output, needles: &[&str]) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "not a clean refusal: {:?}\n{err}", o.status);
    let lines: Vec<&str> = err.lines().filter(|l| l.starts_with("error")).collect();
    assert_eq!(lines.len(), 1, "expected one error line:\n{err}");
    assert!(lines[0].len() < 1000, "the error line echoes too much: {} bytes", lines[0].len());
    for needle in needles {
        assert!(lines[0].contains(needle), "missing {needle:?} in: {}", lines[0]);
    }
}
