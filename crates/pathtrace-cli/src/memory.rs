//! Whether a render fits in this machine's memory, checked before it starts: the operating system
//! may promise a huge film and then kill the process once the render touches it, minutes later.

use crate::CliError;
use pathtrace::film::FILM_BYTES_PER_PIXEL;

/// The bytes per pixel a render holds at its peak: the film, then the image taken from it
/// (linear RGB f32) and its 8-bit encoding for PNG.
pub const RENDER_BYTES_PER_PIXEL: u64 = FILM_BYTES_PER_PIXEL + 12 + 3;

/// Refuses a `width` × `height` render that needs more memory than the machine has.
pub fn check_render_fits(width: u32, height: u32) -> Result<(), CliError> {
    let needed = u64::from(width) * u64::from(height) * RENDER_BYTES_PER_PIXEL;
    match physical_memory() {
        Some(total) if needed > total => Err(CliError::usage(format!(
            "a {width}x{height} render needs {:.1} GB of memory ({RENDER_BYTES_PER_PIXEL} bytes per pixel), more than \
             the {:.1} GB this machine (or container) allows; choose a smaller --size",
            needed as f64 / 1e9,
            total as f64 / 1e9
        ))),
        _ => Ok(()),
    }
}

/// The memory this process may use in bytes, where the system tells it: Linux's physical memory
/// (`/proc/meminfo`), or a container's smaller cgroup v2 limit (`memory.max`), which is where a
/// farm job is killed.
fn physical_memory() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    let cgroup = std::fs::read_to_string("/sys/fs/cgroup/memory.max").ok().and_then(|s| s.trim().parse::<u64>().ok());
    Some(cgroup.map_or(kib * 1024, |limit| limit.min(kib * 1024)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_film_larger_than_any_machine_is_refused_with_the_memory_it_needs() {
        if physical_memory().is_none() {
            return; // Nothing to compare against on this system.
        }
        assert!(check_render_fits(64, 64).is_ok());
        // 2^40 pixels need 78 TB.
        let err = check_render_fits(1 << 20, 1 << 20).unwrap_err();
        assert_eq!(err.exit_code, 2);
        assert!(err.message.contains("GB of memory") && err.message.contains("--size"), "{}", err.message);
    }
}
