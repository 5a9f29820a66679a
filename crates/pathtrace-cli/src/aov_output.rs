//! Writing `render --aov` feature buffers and `--denoise` results beside the image.

use crate::args::Aov;
use crate::CliError;
use pathtrace::film::{FeatureBuffers, Image, ToneMapSettings};
use pathtrace_scene::image_io::{write_exr_with_layers, write_image, ExrLayer, ImageFormat};
use std::path::{Path, PathBuf};

/// The EXR channel names of a buffer, as compositing tools and denoisers expect them.
pub fn exr_channels(aov: Aov) -> &'static [&'static str] {
    match aov {
        Aov::Albedo => &["albedo.R", "albedo.G", "albedo.B"],
        Aov::Normal => &["N.X", "N.Y", "N.Z"],
        Aov::Depth => &["Z"],
    }
}

fn buffer(features: &FeatureBuffers, aov: Aov) -> Image {
    match aov {
        Aov::Albedo => features.albedo(),
        Aov::Normal => features.normal(),
        Aov::Depth => features.depth(),
    }
}

/// `path` with `.TAG` put before its extension, and the extension `ext`: `out.png` → `out.TAG.ext`.
pub fn sibling(path: &Path, tag: &str, ext: &str) -> PathBuf {
    let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    path.with_file_name(format!("{stem}.{tag}.{ext}"))
}

/// The files the buffers go to apart from the image: none for EXR output (they become its
/// channels); `NAME.BUFFER.pfm` for PFM output, `NAME.BUFFER.exr` for PNG (linear values do not
/// belong in an 8-bit file).
pub fn sibling_files(output: &Path, aovs: &[Aov]) -> Result<Vec<(Aov, PathBuf)>, CliError> {
    let format = ImageFormat::from_path(output).map_err(|e| CliError::usage(e.to_string()))?;
    Ok(match format {
        ImageFormat::Exr => Vec::new(),
        ImageFormat::Pfm => aovs.iter().map(|&a| (a, sibling(output, a.name(), "pfm"))).collect(),
        ImageFormat::Png => aovs.iter().map(|&a| (a, sibling(output, a.name(), "exr"))).collect(),
    })
}

/// Writes `image` to `output`, with the `aovs` of `features` as EXR channels or sibling files.
pub fn write_with_aovs(
    output: &Path,
    image: &Image,
    tone: &ToneMapSettings,
    features: Option<&FeatureBuffers>,
    aovs: &[Aov],
) -> Result<Vec<PathBuf>, CliError> {
    let runtime = |e: pathtrace_scene::image_io::ImageIoError| CliError::runtime(e.to_string());
    let Some(features) = features.filter(|_| !aovs.is_empty()) else {
        write_image(output, image, tone).map_err(runtime)?;
        return Ok(Vec::new());
    };
    let images: Vec<(Aov, Image)> = aovs.iter().map(|&a| (a, buffer(features, a))).collect();
    let siblings = sibling_files(output, aovs)?;
    if siblings.is_empty() {
        let layers: Vec<ExrLayer> =
            images.iter().map(|(a, img)| ExrLayer { names: exr_channels(*a), image: img }).collect();
        write_exr_with_layers(output, image, &layers).map_err(runtime)?;
        return Ok(Vec::new());
    }
    write_image(output, image, tone).map_err(runtime)?;
    for ((_, path), (_, img)) in siblings.iter().zip(&images) {
        // Linear values as they are (the tone settings apply to PNG only).
        write_image(path, img, tone).map_err(runtime)?;
    }
    Ok(siblings.into_iter().map(|(_, p)| p).collect())
}
