//! Whether a render fits in this machine's memory, checked before it starts: the operating system
//! may promise a huge film and then kill the process once the render touches it, minutes later.

use crate::CliError;
use pathtrace::film::{FEATURE_BYTES_PER_PIXEL, FILM_BYTES_PER_PIXEL};

/// The bytes per pixel a render holds at its peak: the film, then the image taken from it
/// (linear RGB f32) and its 8-bit encoding for PNG.
pub const RENDER_BYTES_PER_PIXEL: u64 = FILM_BYTES_PER_PIXEL + 12 + 3;

/// What `--aov` or `--denoise` add: the feature sums, then the albedo, normal and depth images
/// taken from them (RGB f32 each).
pub const FEATURE_BYTES_PER_PIXEL_AT_PEAK: u64 = FEATURE_BYTES_PER_PIXEL + 3 * 12;

/// What `--denoise` adds on top: packed copies of the colour, albedo and normal images handed to
/// OIDN, its output and the denoised image (RGB f32 each). OIDN's own working memory is not
/// counted: it filters large images in tiles to bound it.
pub const DENOISE_BYTES_PER_PIXEL: u64 = 5 * 12;

/// What a render keeps per pixel beside its image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Extras {
    /// Feature buffers (`--aov` or `--denoise`).
    pub features: bool,
    /// `--denoise`.
    pub denoise: bool,
}

impl Extras {
    /// The bytes per pixel of a render with these extras, at its peak.
    pub fn bytes_per_pixel(self) -> u64 {
        RENDER_BYTES_PER_PIXEL
            + if self.features { FEATURE_BYTES_PER_PIXEL_AT_PEAK } else { 0 }
            + if self.denoise { DENOISE_BYTES_PER_PIXEL } else { 0 }
    }

    fn described(self) -> &'static str {
        match (self.features, self.denoise) {
            (_, true) => " with feature buffers and denoising",
            (true, false) => " with feature buffers",
            (false, false) => "",
        }
    }
}

/// Refuses a `width` × `height` render (with `extras`) that needs more memory than the machine
/// has.
pub fn check_render_fits(width: u32, height: u32, extras: Extras) -> Result<(), CliError> {
    check_fits_in(width, height, extras, physical_memory())
}

/// [`check_render_fits`] against `available` bytes (`None`: unknown, nothing is refused).
fn check_fits_in(width: u32, height: u32, extras: Extras, available: Option<u64>) -> Result<(), CliError> {
    let per_pixel = extras.bytes_per_pixel();
    let needed = (u64::from(width) * u64::from(height)).saturating_mul(per_pixel);
    match available {
        Some(total) if needed > total => Err(CliError::usage(format!(
            "a {width}x{height} render{} needs {:.1} GB of memory ({per_pixel} bytes per pixel), more than the {:.1} GB \
             this machine (or container) allows; choose a smaller --size",
            extras.described(),
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
        assert!(check_render_fits(64, 64, Extras::default()).is_ok());
        // 2^40 pixels need 140 TB.
        let err = check_render_fits(1 << 20, 1 << 20, Extras::default()).unwrap_err();
        assert_eq!(err.exit_code, 2);
        assert!(err.message.contains("GB of memory") && err.message.contains("--size"), "{}", err.message);
    }

    #[test]
    fn feature_buffers_and_denoising_are_counted() {
        let aov = Extras { features: true, denoise: false };
        let denoise = Extras { features: true, denoise: true };
        assert_eq!(aov.bytes_per_pixel(), RENDER_BYTES_PER_PIXEL + FEATURE_BYTES_PER_PIXEL + 36);
        assert_eq!(denoise.bytes_per_pixel(), aov.bytes_per_pixel() + 60);
        // A size that fits without the buffers but not with them (1 GB available).
        let gb = Some(1_000_000_000);
        let pixels = 1_000_000_000 / (RENDER_BYTES_PER_PIXEL + FEATURE_BYTES_PER_PIXEL_AT_PEAK / 2);
        let (w, h) = (1000, (pixels / 1000) as u32);
        assert!(check_fits_in(w, h, Extras::default(), gb).is_ok());
        let err = check_fits_in(w, h, aov, gb).unwrap_err();
        assert_eq!(err.exit_code, 2);
        let per_pixel = format!("({} bytes per pixel)", aov.bytes_per_pixel());
        assert!(err.message.contains("with feature buffers") && err.message.contains(&per_pixel), "{}", err.message);
        let err = check_fits_in(w, h * 2 / 3, denoise, gb).unwrap_err();
        assert!(err.message.contains("with feature buffers and denoising"), "{}", err.message);
        assert!(check_fits_in(w, h * 2 / 3, aov, gb).is_ok());
        assert!(check_fits_in(1 << 20, 1 << 20, denoise, None).is_ok(), "unknown memory refuses nothing");
    }
}
