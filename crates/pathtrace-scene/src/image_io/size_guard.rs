//! One check of an input image's declared size, made before any decoder allocates pixels.
//!
//! A header can claim any size: a 397-byte EXR may declare 100000×100000 pixels, and decoding it
//! would try to allocate 120 GB. Every reading path (EXR, Radiance HDR, PNG, JPEG) asks this
//! module before it decodes, so no file can make the renderer hold more than the caps below.

use std::path::Path;

use super::ImageIoError;

/// The most pixels an input image (texture, environment map, reference) may have: 2^28, e.g.
/// 16384 × 16384, which take 3 GiB as the linear RGB f32 texels the renderer keeps.
pub const MAX_INPUT_PIXELS: u64 = 1 << 28;

/// The most pixels one stored byte can stand for in any format we read. DEFLATE (PNG, EXR's ZIP)
/// cannot expand by more than 1032:1 and a pixel takes at least one byte before compression (PNG
/// grey), the other codecs (RLE, PIZ, RGBE runs) less; 4096 leaves room for 1-bit PNGs, whose pixels
/// are eighths of a byte.
const MAX_PIXELS_PER_STORED_BYTE: u64 = 4096;

/// The bytes a decoded pixel takes in memory (linear RGB f32), for the limits we give decoders.
pub(crate) const DECODED_BYTES_PER_PIXEL: u64 = 12;

/// Refuses a declared `width` × `height` that is empty, beyond [`MAX_INPUT_PIXELS`], or more than a
/// file of `file_len` bytes could hold.
pub(crate) fn check_declared_size(path: &Path, width: u64, height: u64, file_len: u64) -> Result<(), ImageIoError> {
    let refuse =
        |reason: String| Err(ImageIoError::ImplausibleSize { path: path.to_path_buf(), width, height, reason });
    if width == 0 || height == 0 {
        return refuse("it has no pixels".to_owned());
    }
    let pixels = width.saturating_mul(height);
    if pixels > MAX_INPUT_PIXELS {
        return refuse(format!("input images are limited to {MAX_INPUT_PIXELS} pixels (16384x16384)"));
    }
    if pixels > file_len.saturating_mul(MAX_PIXELS_PER_STORED_BYTE) {
        return refuse(format!(
            "the file has only {file_len} bytes, too few for that many pixels (its header is wrong)"
        ));
    }
    Ok(())
}

/// The length of the file at `path`, for [`check_declared_size`].
pub(crate) fn file_len(path: &Path) -> Result<u64, ImageIoError> {
    std::fs::metadata(path).map(|m| m.len()).map_err(|e| ImageIoError::io(path, "read", e))
}

/// Decoder limits for the `image` crate that match [`MAX_INPUT_PIXELS`].
pub(crate) fn image_crate_limits() -> image::Limits {
    let mut limits = image::Limits::default();
    limits.max_alloc = Some(MAX_INPUT_PIXELS * DECODED_BYTES_PER_PIXEL);
    limits
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lying_headers_are_refused_before_decoding() {
        let p = Path::new("x.exr");
        assert!(check_declared_size(p, 64, 64, 100).is_ok());
        let lie = check_declared_size(p, 10_000, 10_000, 397).unwrap_err().to_string();
        assert!(lie.contains("10000x10000") && lie.contains("397 bytes"), "{lie}");
        let huge = check_declared_size(p, 100_000, 100_000, u64::MAX).unwrap_err().to_string();
        assert!(huge.contains("limited to"), "{huge}");
        assert!(check_declared_size(p, 0, 0, 100).unwrap_err().to_string().contains("no pixels"));
        assert!(check_declared_size(p, u64::MAX, u64::MAX, u64::MAX).is_err());
    }
}
