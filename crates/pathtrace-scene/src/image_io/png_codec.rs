//! PNG: tone-mapped, sRGB-encoded 8-bit RGB out; 8/16-bit sRGB in, decoded to linear.

use std::io::Write;

use image::codecs::png::PngEncoder;
use image::{ExtendedColorType, ImageEncoder, ImageError};
use pathtrace::film::tonemap::{to_srgb8, ToneMapSettings};
use pathtrace::film::Image;

/// Tone maps `image` with `settings` and writes it as 8-bit sRGB PNG. The caller
/// checks that the image is non-empty and consistent.
pub(crate) fn encode(out: &mut impl Write, image: &Image, settings: &ToneMapSettings) -> Result<(), ImageError> {
    let bytes: Vec<u8> = image.pixels.iter().flat_map(|&p| to_srgb8(p, settings)).collect();
    PngEncoder::new(out).write_image(&bytes, image.width, image.height, ExtendedColorType::Rgb8)
}
