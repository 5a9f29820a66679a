//! Texture images: PNG and JPEG through the `image` crate, sRGB-decoded unless the scene says the
//! values are raw (Mitsuba's `raw` parameter); float formats are read as they are (linear).

use image::{DynamicImage, ImageError};
use pathtrace::film::tonemap::srgb_decode;
use pathtrace::film::Image;
use pathtrace::math::Rgb;

/// Converts a decoded 8- or 16-bit PNG or JPEG into RGB (grey expanded, alpha dropped): sRGB
/// decoded (IEC 61966-2-1) to linear, or with `raw` only scaled to [0, 1].
pub(crate) fn to_linear(decoded: DynamicImage, format: image::ImageFormat, raw: bool) -> Result<Image, ImageError> {
    let color = decoded.color();
    let eight_bit = color.bytes_per_pixel() == color.channel_count();
    let curve = |x: f32| if raw { x } else { srgb_decode(x) };
    let (width, height, pixels) = if eight_bit {
        let rgb = decoded.into_rgb8();
        let table: Vec<f32> = (0..=255u8).map(|v| curve(f32::from(v) / 255.0)).collect();
        let pixels =
            rgb.pixels().map(|p| Rgb::new(table[p[0] as usize], table[p[1] as usize], table[p[2] as usize])).collect();
        (rgb.width(), rgb.height(), pixels)
    } else {
        let rgb = DynamicImage::into_rgb16(decoded);
        let pixels = rgb.pixels().map(|p| Rgb::from_array(p.0.map(|v| curve(f32::from(v) / 65535.0)))).collect();
        (rgb.width(), rgb.height(), pixels)
    };
    Image::from_pixels(width, height, pixels).ok_or_else(|| {
        ImageError::Decoding(image::error::DecodingError::new(
            format.into(),
            "decoded pixel count does not match the image size",
        ))
    })
}

/// The alpha channel of a decoded PNG or JPEG as grey texels in [0, 1] (1 without alpha).
pub(crate) fn alpha(decoded: DynamicImage, format: image::ImageFormat) -> Result<Image, ImageError> {
    let rgba = decoded.into_rgba16();
    let pixels = rgba.pixels().map(|p| Rgb::splat(f32::from(p[3]) / 65535.0)).collect();
    Image::from_pixels(rgba.width(), rgba.height(), pixels).ok_or_else(|| {
        ImageError::Decoding(image::error::DecodingError::new(
            format.into(),
            "decoded pixel count does not match the image size",
        ))
    })
}
