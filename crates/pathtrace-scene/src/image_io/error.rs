//! The error type of image reading and writing.

use std::io;
use std::path::PathBuf;

/// Why an image file could not be read or written. Every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum ImageIoError {
    /// A Radiance `.hdr` file that could not be decoded.
    #[error("{}: invalid Radiance HDR file: {reason}", .path.display())]
    InvalidHdr {
        /// The offending path.
        path: PathBuf,
        /// What the decoder reported.
        reason: String,
    },

    /// The file extension is not one of the supported formats.
    #[error(
        "{}: unsupported image format {extension:?}; supported extensions are {}",
        .path.display(),
        crate::image_io::ImageFormat::SUPPORTED_EXTENSIONS.join(", ")
    )]
    UnsupportedFormat {
        /// The offending path.
        path: PathBuf,
        /// Its extension (empty when it has none).
        extension: String,
    },

    /// An alpha channel was asked of a format we read without one.
    #[error("{}: only PNG and JPEG textures give an alpha channel (opacity)", .path.display())]
    NoAlpha {
        /// The offending path.
        path: PathBuf,
    },

    /// The path cannot name an output file (for example it ends in `..`).
    #[error("{}: not a file path", .path.display())]
    NotAFilePath {
        /// The offending path.
        path: PathBuf,
    },

    /// The image to write has no pixels.
    #[error("cannot write {}: the image is empty ({width}x{height})", .path.display())]
    EmptyImage {
        /// The output path.
        path: PathBuf,
        /// The image width.
        width: u32,
        /// The image height.
        height: u32,
    },

    /// The image to write has a pixel buffer of the wrong length.
    #[error(
        "cannot write {}: a {width}x{height} image needs {width}·{height} pixels but has {actual}",
        .path.display()
    )]
    PixelCountMismatch {
        /// The output path.
        path: PathBuf,
        /// The image width.
        width: u32,
        /// The image height.
        height: u32,
        /// The length of the pixel buffer.
        actual: usize,
    },

    /// An operating-system level failure (open, create, write, rename, …).
    #[error("cannot {action} {}: {source}", .path.display())]
    Io {
        /// The file concerned.
        path: PathBuf,
        /// What was being done, as a verb phrase ("read", "create a temporary file for").
        action: &'static str,
        /// The underlying error.
        #[source]
        source: io::Error,
    },

    /// A PFM file is malformed or truncated.
    #[error("invalid PFM file {}: {reason}", .path.display())]
    InvalidPfm {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        reason: String,
    },

    /// The PNG encoder or decoder failed.
    #[error("PNG error in {}: {source}", .path.display())]
    Png {
        /// The file.
        path: PathBuf,
        /// The codec's error.
        #[source]
        source: image::ImageError,
    },

    /// A texture image (PNG or JPEG) could not be decoded.
    #[error("cannot decode {}: {source}", .path.display())]
    Texture {
        /// The file.
        path: PathBuf,
        /// The codec's error.
        #[source]
        source: image::ImageError,
    },

    /// The EXR encoder or decoder failed.
    #[error("EXR error in {}: {source}", .path.display())]
    Exr {
        /// The file.
        path: PathBuf,
        /// The codec's error.
        #[source]
        source: exr::error::Error,
    },

    /// An EXR file has no layer with R, G and B channels.
    #[error(
        "EXR file {} has no layer with R, G and B channels (channels found: {found})",
        .path.display()
    )]
    MissingChannels {
        /// The file.
        path: PathBuf,
        /// The channel names it does have, comma separated.
        found: String,
    },

    /// The image is larger than the format (or this platform) can hold.
    #[error("{}: a {width}x{height} image is too large for {format}", .path.display())]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// The width.
        width: u64,
        /// The height.
        height: u64,
        /// The format name.
        format: &'static str,
    },

    /// A header declares a size no file of this length could hold, or one beyond the input limit.
    #[error("{}: refusing a {width}x{height} image: {reason}", .path.display())]
    ImplausibleSize {
        /// The file.
        path: PathBuf,
        /// The declared width.
        width: u64,
        /// The declared height.
        height: u64,
        /// Why it is refused.
        reason: String,
    },
}

impl ImageIoError {
    /// An [`ImageIoError::Io`] for `path`.
    pub(crate) fn io(path: impl Into<PathBuf>, action: &'static str, source: io::Error) -> Self {
        ImageIoError::Io { path: path.into(), action, source }
    }
}
