//! Denoising rendered images with Intel Open Image Denoise 2 (OIDN), the denoiser Blender,
//! Houdini and Arnold ship: its "RT" filter takes the noisy radiance with the albedo and normal
//! feature buffers (`pathtrace::film::FeatureBuffers`) and returns a clean estimate.
//!
//! The library is found and loaded at run time ([`locate`]), so building and running pathtrace
//! needs nothing new; only denoising needs it, and says how to get it when it is missing.

mod locate;
mod oidn;

use pathtrace::film::Image;
use std::path::PathBuf;

pub use locate::{candidates, LIBRARY_NAMES};

/// How to get the library, for error messages (the docs say the same: docs/denoising.md).
pub const HOW_TO_GET: &str = "install Intel Open Image Denoise 2, e.g. `pip install pyoidn==2.5.1.0` (its wheel ships \
     the Linux x86-64 libraries), and set OIDN_DIR to the folder holding lib/libOpenImageDenoise.so* (for the wheel: \
     SITE-PACKAGES/pyoidn/oidn)";

/// Why an image could not be denoised.
#[derive(Debug, thiserror::Error)]
pub enum DenoiseError {
    #[error("Intel Open Image Denoise was not found (looked in: {}); {HOW_TO_GET}", list(.searched))]
    NotFound { searched: Vec<PathBuf> },
    #[error("Intel Open Image Denoise at {path} could not be loaded: {message}; {HOW_TO_GET}")]
    Load { path: PathBuf, message: String },
    #[error("Intel Open Image Denoise failed: {0}")]
    Device(String),
    #[error("cannot denoise: the {what} image is {got_w}x{got_h}, the colour image {w}x{h}")]
    SizeMismatch { what: &'static str, got_w: u32, got_h: u32, w: u32, h: u32 },
}

fn list(paths: &[PathBuf]) -> String {
    paths.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ")
}

/// A loaded denoiser: the library and one CPU device, reusable for many images.
pub struct Denoiser {
    device: oidn::Device,
    /// Where the library was loaded from.
    pub library: PathBuf,
}

impl Denoiser {
    /// Finds and loads the library ([`locate`]) and starts a CPU device.
    pub fn new() -> Result<Self, DenoiseError> {
        let (library, api) = locate::load()?;
        let device = oidn::Device::new_cpu(api).map_err(DenoiseError::Device)?;
        Ok(Self { device, library })
    }

    /// Denoises `color` (linear HDR radiance) guided by the `albedo` and `normal` feature buffers
    /// of the same size (normals in [-1, 1], as pathtrace accumulates them).
    pub fn denoise(&self, color: &Image, albedo: &Image, normal: &Image) -> Result<Image, DenoiseError> {
        for (what, img) in [("albedo", albedo), ("normal", normal)] {
            if (img.width, img.height) != (color.width, color.height) || !img.is_consistent() {
                return Err(DenoiseError::SizeMismatch {
                    what,
                    got_w: img.width,
                    got_h: img.height,
                    w: color.width,
                    h: color.height,
                });
            }
        }
        let flat = |img: &Image| img.pixels.iter().flat_map(|p| p.to_array()).collect::<Vec<f32>>();
        let out = self
            .device
            .denoise_rgb(color.width as usize, color.height as usize, &flat(color), &flat(albedo), &flat(normal))
            .map_err(DenoiseError::Device)?;
        let pixels = out.chunks_exact(3).map(|c| pathtrace::math::Rgb::new(c[0], c[1], c[2])).collect();
        Ok(Image { width: color.width, height: color.height, pixels })
    }
}

/// Denoises one image with a fresh [`Denoiser`].
pub fn denoise(color: &Image, albedo: &Image, normal: &Image) -> Result<Image, DenoiseError> {
    Denoiser::new()?.denoise(color, albedo, normal)
}
