//! Reading Radiance `.hdr` (RGBE) images as linear RGB, through the `image` crate's decoder.

use std::io::BufRead;

use pathtrace::film::Image;
use pathtrace::math::Rgb;

/// Decodes an RGBE stream; the error is the decoder's message.
pub fn decode(reader: impl BufRead) -> Result<Image, String> {
    let decoder = image::codecs::hdr::HdrDecoder::new(reader).map_err(|e| e.to_string())?;
    let rgb = image::DynamicImage::from_decoder(decoder).map_err(|e| e.to_string())?.into_rgb32f();
    let (w, h) = rgb.dimensions();
    let pixels = rgb.pixels().map(|p| Rgb::new(p.0[0], p.0[1], p.0[2])).collect();
    Image::from_pixels(w, h, pixels).ok_or_else(|| format!("inconsistent size {w}x{h}"))
}
