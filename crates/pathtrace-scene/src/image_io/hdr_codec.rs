//! Radiance `.hdr` (RGBE) images as linear RGB, decoded by the `image` crate.

use image::DynamicImage;
use pathtrace::film::Image;
use pathtrace::math::Rgb;

/// Converts a decoded RGBE image; the error is a message.
pub fn to_linear(decoded: DynamicImage) -> Result<Image, String> {
    let rgb = decoded.into_rgb32f();
    let (w, h) = rgb.dimensions();
    let pixels = rgb.pixels().map(|p| Rgb::new(p.0[0], p.0[1], p.0[2])).collect();
    Image::from_pixels(w, h, pixels).ok_or_else(|| format!("inconsistent size {w}x{h}"))
}
