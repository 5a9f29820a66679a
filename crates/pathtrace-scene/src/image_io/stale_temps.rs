//! Removing temporary files that an earlier, killed write left behind.
//!
//! [`atomic`](super::atomic) writes `.<name>.<pid>.<n>.tmp` beside the destination and renames it
//! into place; a process killed in between (SIGKILL, a second Ctrl-C, a power cut) leaves that file
//! hidden in the user's folder. Before writing `<name>` again we delete such files whose process is
//! gone. Only our own naming pattern is touched, and only where the system can tell that the
//! process is gone (`/proc`, on Linux); elsewhere they are left alone.

use std::ffi::OsStr;
use std::fs;
use std::path::Path;

/// Deletes stale temporaries of `target` (best effort: failing to tidy up is no reason to fail).
pub(crate) fn remove_stale_temps(target: &Path) {
    let (Some(name), Some(dir)) = (target.file_name(), target.parent()) else { return };
    let dir = if dir.as_os_str().is_empty() { Path::new(".") } else { dir };
    let Ok(entries) = fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        let file_name = entry.file_name();
        if let Some(pid) = temp_owner(&file_name, name) {
            if pid != std::process::id() && process_is_gone(pid) {
                let _ = fs::remove_file(entry.path());
            }
        }
    }
}

/// The process id in `file_name` if it is `.<target_name>.<pid>.<n>.tmp`.
pub(crate) fn temp_owner(file_name: &OsStr, target_name: &OsStr) -> Option<u32> {
    let file_name = file_name.to_str()?;
    let rest = file_name.strip_prefix('.')?.strip_prefix(target_name.to_str()?)?;
    let mut parts = rest.strip_prefix('.')?.strip_suffix(".tmp")?.split('.');
    let pid = parts.next()?.parse().ok()?;
    parts.next()?.parse::<u64>().ok()?;
    parts.next().is_none().then_some(pid)
}

/// True only when the system says no process `pid` exists.
fn process_is_gone(pid: u32) -> bool {
    let proc_root = Path::new("/proc/self");
    proc_root.exists() && !Path::new("/proc").join(pid.to_string()).exists()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_io::scratch::ScratchDir;

    #[test]
    fn only_our_pattern_is_recognised() {
        let name = OsStr::new("out.png");
        assert_eq!(temp_owner(OsStr::new(".out.png.1234.0.tmp"), name), Some(1234));
        for other in
            [".out.png.tmp", ".out.png.x.0.tmp", "out.png.1.0.tmp", ".out.png.1.0.tmp.bak", ".other.png.1.0.tmp"]
        {
            assert_eq!(temp_owner(OsStr::new(other), name), None, "{other}");
        }
    }

    #[test]
    fn temporaries_of_dead_processes_are_removed_and_others_kept() {
        if !Path::new("/proc/self").exists() {
            return; // Cannot tell dead processes from live ones here.
        }
        let dir = ScratchDir::new("stale-temps");
        // Process ids above the kernel's maximum (2^22) are never alive.
        let dead = format!(".out.png.{}.0.tmp", 1u32 << 30);
        let alive = format!(".out.png.{}.0.tmp", std::process::id());
        for name in [&dead, &alive, &".other.png.1073741824.0.tmp".to_owned(), &"keep.txt".to_owned()] {
            fs::write(dir.path().join(name), b"x").unwrap();
        }
        remove_stale_temps(&dir.path().join("out.png"));
        assert_eq!(dir.entries(), [".other.png.1073741824.0.tmp", &alive, "keep.txt"]);
    }
}
