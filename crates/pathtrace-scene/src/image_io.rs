//! Reading and writing images: PNG (display-referred, 8-bit sRGB), OpenEXR and PFM
//! (scene-linear 32-bit float).
//!
//! Writes go to a temporary file in the destination directory that is renamed into
//! place, so a failed write never leaves a partial file at the destination.

mod atomic;
mod error;
mod exr_codec;
mod guarded_decode;
mod hdr_codec;
mod pfm_codec;
mod png_codec;
#[cfg(test)]
mod scratch;
mod size_guard;
mod stale_temps;
#[cfg(test)]
mod tests;
mod texture_codec;

use std::fmt;
use std::fs;
use std::path::Path;

use pathtrace::film::tonemap::ToneMapSettings;
use pathtrace::film::Image;

pub(crate) use atomic::write_atomically;
pub use error::ImageIoError;
pub use size_guard::MAX_INPUT_PIXELS;

/// An image file format, chosen by file extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ImageFormat {
    /// PNG: tone mapped, sRGB-encoded 8-bit RGB.
    Png,
    /// OpenEXR: scene-linear 32-bit float RGB.
    Exr,
    /// Portable Float Map: scene-linear 32-bit float RGB.
    Pfm,
}

impl ImageFormat {
    /// The extensions [`ImageFormat::from_path`] recognises (case-insensitively).
    pub const SUPPORTED_EXTENSIONS: [&'static str; 3] = ["png", "exr", "pfm"];

    /// The format named by `path`'s extension, compared case-insensitively.
    pub fn from_path(path: &Path) -> Result<ImageFormat, ImageIoError> {
        let extension = path.extension().map(|e| e.to_string_lossy().into_owned()).unwrap_or_default();
        match extension.to_ascii_lowercase().as_str() {
            "png" => Ok(ImageFormat::Png),
            "exr" => Ok(ImageFormat::Exr),
            "pfm" => Ok(ImageFormat::Pfm),
            _ => Err(ImageIoError::UnsupportedFormat { path: path.to_path_buf(), extension }),
        }
    }

    /// The canonical lowercase extension, without the dot.
    pub fn extension(self) -> &'static str {
        match self {
            ImageFormat::Png => "png",
            ImageFormat::Exr => "exr",
            ImageFormat::Pfm => "pfm",
        }
    }

    /// True for formats that store scene-linear floats (no tone mapping, no exposure).
    pub fn is_linear(self) -> bool {
        matches!(self, ImageFormat::Exr | ImageFormat::Pfm)
    }
}

impl fmt::Display for ImageFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ImageFormat::Png => "PNG",
            ImageFormat::Exr => "OpenEXR",
            ImageFormat::Pfm => "PFM",
        })
    }
}

/// Writes `image` to `path` in the format named by its extension.
///
/// PNG is tone mapped with `settings` (exposure and curve) and sRGB encoded to 8 bits.
/// EXR and PFM store the scene-linear values unchanged: `settings` is ignored for them.
/// The file is written to a temporary sibling and renamed into place, so on error the
/// destination is untouched. Empty or inconsistent images are rejected.
pub fn write_image(path: &Path, image: &Image, settings: &ToneMapSettings) -> Result<(), ImageIoError> {
    let format = ImageFormat::from_path(path)?;
    check_writable(path, image, format)?;
    atomic::write_atomically(path, |out| match format {
        ImageFormat::Png => png_codec::encode(out, image, settings)
            .map_err(|source| ImageIoError::Png { path: path.to_path_buf(), source }),
        ImageFormat::Exr => {
            exr_codec::encode(out, image).map_err(|source| ImageIoError::Exr { path: path.to_path_buf(), source })
        }
        ImageFormat::Pfm => pfm_codec::encode(out, image).map_err(|e| ImageIoError::io(path, "write", e)),
    })
}

/// One image's channels under the names tools expect, e.g. `["albedo.R", "albedo.G",
/// "albedo.B"]` or `["Z"]` (a one-name layer takes the image's first channel).
#[derive(Clone, Copy, Debug)]
pub struct ExrLayer<'a> {
    pub names: &'a [&'a str],
    pub image: &'a Image,
}

/// Writes `image` as the R, G, B channels of an OpenEXR file with `extra` layers beside them
/// (feature buffers: `albedo.R/G/B`, `N.X/Y/Z`, `Z`), atomically like [`write_image`]. Every
/// layer must have the image's size.
pub fn write_exr_with_layers(path: &Path, image: &Image, extra: &[ExrLayer]) -> Result<(), ImageIoError> {
    check_writable(path, image, ImageFormat::Exr)?;
    let mut channels: Vec<(String, Vec<f32>)> = Vec::new();
    let layers = std::iter::once(ExrLayer { names: &["R", "G", "B"], image }).chain(extra.iter().copied());
    for layer in layers {
        check_writable(path, layer.image, ImageFormat::Exr)?;
        if (layer.image.width, layer.image.height) != (image.width, image.height) {
            return Err(ImageIoError::PixelCountMismatch {
                path: path.to_path_buf(),
                width: image.width,
                height: image.height,
                actual: layer.image.pixels.len(),
            });
        }
        for (k, name) in layer.names.iter().enumerate().take(3) {
            channels.push((name.to_string(), layer.image.pixels.iter().map(|p| p.to_array()[k]).collect()));
        }
    }
    let (w, h) = (image.width as usize, image.height as usize);
    atomic::write_atomically(path, |out| {
        exr_codec::encode_channels(out, w, h, channels)
            .map_err(|source| ImageIoError::Exr { path: path.to_path_buf(), source })
    })
}

/// Rejects images that no format can store: empty, inconsistent, or too large.
fn check_writable(path: &Path, image: &Image, format: ImageFormat) -> Result<(), ImageIoError> {
    if image.is_empty() {
        return Err(ImageIoError::EmptyImage { path: path.to_path_buf(), width: image.width, height: image.height });
    }
    if !image.is_consistent() {
        return Err(ImageIoError::PixelCountMismatch {
            path: path.to_path_buf(),
            width: image.width,
            height: image.height,
            actual: image.pixels.len(),
        });
    }
    // The PNG specification limits each dimension to 2^31 − 1.
    let limit = if format == ImageFormat::Png { i32::MAX as u32 } else { u32::MAX };
    if image.width > limit || image.height > limit {
        return Err(ImageIoError::TooLarge {
            path: path.to_path_buf(),
            width: image.width.into(),
            height: image.height.into(),
            format: format.extension(),
        });
    }
    Ok(())
}

/// Reads the image at `path`, in the format named by its extension, as linear RGB.
///
/// - EXR: the first layer with R, G and B channels (f16, f32 or u32; alpha dropped).
/// - PFM: colour (`PF`) or greyscale (`Pf`), either byte order.
/// - PNG: 8- or 16-bit, grey or RGB (alpha dropped), sRGB decoded to linear.
pub fn read_image(path: &Path) -> Result<Image, ImageIoError> {
    match ImageFormat::from_path(path)? {
        ImageFormat::Pfm => {
            let bytes = fs::read(path).map_err(|e| ImageIoError::io(path, "read", e))?;
            pfm_codec::decode(&bytes).map_err(|reason| ImageIoError::InvalidPfm { path: path.to_path_buf(), reason })
        }
        ImageFormat::Png => {
            let png = |source| ImageIoError::Png { path: path.to_path_buf(), source };
            let decoded = guarded_decode::decode_file(path, image::ImageFormat::Png, png)?;
            texture_codec::to_linear(decoded, image::ImageFormat::Png, false).map_err(png)
        }
        ImageFormat::Exr => read_exr(path),
    }
}

/// Reads a scene-linear input image, such as an environment map: everything [`read_image`]
/// reads, and Radiance RGBE (`.hdr`, `.pic`), which the renderer reads but never writes.
pub fn read_linear_image(path: &Path) -> Result<Image, ImageIoError> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    if ext != "hdr" && ext != "pic" {
        return read_image(path);
    }
    let invalid = |reason| ImageIoError::InvalidHdr { path: path.to_path_buf(), reason };
    let decoded = guarded_decode::decode_file(path, image::ImageFormat::Hdr, |e| invalid(e.to_string()))?;
    hdr_codec::to_linear(decoded).map_err(invalid)
}

/// Reads a texture image as linear RGB: PNG and JPEG (`.jpg`, `.jpeg`) are sRGB-decoded unless
/// `raw` (then their values are only scaled to [0, 1]); EXR, HDR and PFM are linear already and
/// read as [`read_linear_image`] does.
pub fn read_texture(path: &Path, raw: bool) -> Result<Image, ImageIoError> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    let format = match ext.as_str() {
        "png" => image::ImageFormat::Png,
        "jpg" | "jpeg" => image::ImageFormat::Jpeg,
        _ => return read_linear_image(path),
    };
    let texture = |source| ImageIoError::Texture { path: path.to_path_buf(), source };
    let decoded = guarded_decode::decode_file(path, format, texture)?;
    texture_codec::to_linear(decoded, format, raw).map_err(texture)
}

/// Reads the alpha channel of a PNG texture as a grey image (alpha is linear in PNG: no
/// decoding); an image without alpha reads as opaque (1), as glTF says.
pub fn read_texture_alpha(path: &Path) -> Result<Image, ImageIoError> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    let format = match ext.as_str() {
        "png" => image::ImageFormat::Png,
        "jpg" | "jpeg" => image::ImageFormat::Jpeg,
        _ => return Err(ImageIoError::NoAlpha { path: path.to_path_buf() }),
    };
    let texture = |source| ImageIoError::Texture { path: path.to_path_buf(), source };
    let decoded = guarded_decode::decode_file(path, format, texture)?;
    texture_codec::alpha(decoded, format).map_err(texture)
}

/// Decodes an in-memory PNG or JPEG texture (an image embedded in a glTF file) as
/// [`read_texture`] (or, with `alpha`, [`read_texture_alpha`]) reads a file; `label` names it in
/// errors.
pub fn decode_texture(
    bytes: &[u8],
    label: &Path,
    format: image::ImageFormat,
    raw: bool,
    alpha: bool,
) -> Result<Image, ImageIoError> {
    let texture = |source| ImageIoError::Texture { path: label.to_path_buf(), source };
    let decoded = guarded_decode::decode_bytes(bytes, label, format, texture)?;
    if alpha {
        texture_codec::alpha(decoded, format).map_err(texture)
    } else {
        texture_codec::to_linear(decoded, format, raw).map_err(texture)
    }
}

/// Reads an EXR file, explaining a missing-channel failure in our own words.
fn read_exr(path: &Path) -> Result<Image, ImageIoError> {
    // Open it ourselves first, so "not found" and permissions read as IO errors.
    fs::File::open(path).map_err(|e| ImageIoError::io(path, "open", e))?;
    if let Some((width, height)) = exr_codec::declared_rgb_size(path) {
        size_guard::check_declared_size(path, width, height, size_guard::file_len(path)?)?;
    }
    let (width, height, pixels) =
        exr_codec::decode(path).map_err(|source| match exr_codec::missing_rgb_channels(path) {
            Some(found) => ImageIoError::MissingChannels { path: path.to_path_buf(), found },
            None => ImageIoError::Exr { path: path.to_path_buf(), source },
        })?;
    let too_large = || ImageIoError::TooLarge {
        path: path.to_path_buf(),
        width: width as u64,
        height: height as u64,
        format: "this renderer",
    };
    let w = u32::try_from(width).map_err(|_| too_large())?;
    let h = u32::try_from(height).map_err(|_| too_large())?;
    Image::from_pixels(w, h, pixels).ok_or_else(too_large)
}
