//! PNG: tone-mapped, sRGB-encoded 8-bit RGB out; 8/16-bit sRGB in, decoded to linear.

use std::io::{BufRead, Seek, Write};

use image::codecs::png::PngEncoder;
use image::{DynamicImage, ExtendedColorType, ImageEncoder, ImageError, ImageReader};
use pathtrace::film::tonemap::{srgb_decode, to_srgb8, ToneMapSettings};
use pathtrace::film::Image;
use pathtrace::math::Rgb;

/// Tone maps `image` with `settings` and writes it as 8-bit sRGB PNG. The caller
/// checks that the image is non-empty and consistent.
pub(crate) fn encode(out: &mut impl Write, image: &Image, settings: &ToneMapSettings) -> Result<(), ImageError> {
    let bytes: Vec<u8> = image.pixels.iter().flat_map(|&p| to_srgb8(p, settings)).collect();
    PngEncoder::new(out).write_image(&bytes, image.width, image.height, ExtendedColorType::Rgb8)
}

/// Decodes a PNG, treating its values as sRGB-encoded and returning linear RGB.
/// Grey is expanded to RGB; alpha is dropped.
pub(crate) fn decode(input: impl BufRead + Seek) -> Result<Image, ImageError> {
    let decoded = ImageReader::with_format(input, image::ImageFormat::Png).decode()?;
    let color = decoded.color();
    let eight_bit = color.bytes_per_pixel() == color.channel_count();
    let (width, height, pixels) = if eight_bit {
        let rgb = decoded.into_rgb8();
        // sRGB (IEC 61966-2-1) decode through a 256-entry table.
        let table: Vec<f32> = (0..=255u8).map(|v| srgb_decode(f32::from(v) / 255.0)).collect();
        let pixels =
            rgb.pixels().map(|p| Rgb::new(table[p[0] as usize], table[p[1] as usize], table[p[2] as usize])).collect();
        (rgb.width(), rgb.height(), pixels)
    } else {
        let rgb = DynamicImage::into_rgb16(decoded);
        let pixels = rgb.pixels().map(|p| Rgb::from_array(p.0.map(|v| srgb_decode(f32::from(v) / 65535.0)))).collect();
        (rgb.width(), rgb.height(), pixels)
    };
    Image::from_pixels(width, height, pixels).ok_or_else(|| {
        ImageError::Decoding(image::error::DecodingError::new(
            image::ImageFormat::Png.into(),
            "decoded pixel count does not match the image size",
        ))
    })
}
