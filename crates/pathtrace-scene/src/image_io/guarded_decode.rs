//! Opening an image through the `image` crate (PNG, JPEG, Radiance HDR) with its declared size
//! checked by [`size_guard`](super::size_guard) before the pixels are decoded.

use std::fs::File;
use std::io::{BufReader, Cursor};
use std::path::Path;

use image::{DynamicImage, ImageDecoder, ImageError, ImageReader};

use super::size_guard::{check_declared_size, image_crate_limits};
use super::ImageIoError;

/// Decodes the file at `path` as `format`; a codec failure becomes `wrap(error)`.
pub(crate) fn decode_file(
    path: &Path,
    format: image::ImageFormat,
    wrap: impl Fn(ImageError) -> ImageIoError,
) -> Result<DynamicImage, ImageIoError> {
    let file = File::open(path).map_err(|e| ImageIoError::io(path, "open", e))?;
    let file_len = file.metadata().map_err(|e| ImageIoError::io(path, "read", e))?.len();
    let mut reader = ImageReader::with_format(BufReader::new(file), format);
    reader.limits(image_crate_limits());
    let decoder = reader.into_decoder().map_err(&wrap)?;
    let (width, height) = decoder.dimensions();
    check_declared_size(path, width.into(), height.into(), file_len)?;
    DynamicImage::from_decoder(decoder).map_err(wrap)
}

/// Decodes in-memory `bytes` as `format` (an image embedded in a scene file), with the same size
/// guard; `label` names the image in errors.
pub(crate) fn decode_bytes(
    bytes: &[u8],
    label: &Path,
    format: image::ImageFormat,
    wrap: impl Fn(ImageError) -> ImageIoError,
) -> Result<DynamicImage, ImageIoError> {
    let mut reader = ImageReader::with_format(Cursor::new(bytes), format);
    reader.limits(image_crate_limits());
    let decoder = reader.into_decoder().map_err(&wrap)?;
    let (width, height) = decoder.dimensions();
    check_declared_size(label, width.into(), height.into(), bytes.len() as u64)?;
    DynamicImage::from_decoder(decoder).map_err(wrap)
}
