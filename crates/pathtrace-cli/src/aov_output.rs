//! Writing `--aov` feature buffers and `--denoise` results beside the image, for `render` and
//! for `merge` (from films that carry the buffers): one implementation for both.

use crate::args::{Aov, FeatureArgs};
use crate::destination::check_image_destination;
use crate::CliError;
use pathtrace::film::{FeatureBuffers, Image, ToneMapSettings};
use pathtrace_denoise::Denoiser;
use pathtrace_scene::image_io::{write_exr_with_layers, write_image, ExrLayer, ImageFormat};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The outputs `--aov`, `--denoise` and `--keep-noisy` ask for, checked before any work: the
/// destinations are writable and the denoiser is found (a missing library costs no render time).
pub struct FeatureOutputs {
    output: PathBuf,
    aovs: Vec<Aov>,
    denoiser: Option<Denoiser>,
    noisy_output: Option<PathBuf>,
}

/// What [`FeatureOutputs::write`] wrote beside the image.
pub struct Written {
    /// The files written apart from the image (sibling buffers, the noisy image).
    pub also: Vec<PathBuf>,
    pub denoise_time: Option<Duration>,
}

impl Written {
    /// ", denoised in 0.12 s" after `--denoise`, else nothing (for the command's summary).
    pub fn denoised_text(&self) -> String {
        self.denoise_time.map_or(String::new(), |t| format!(", denoised in {:.2} s", t.as_secs_f64()))
    }

    /// " (out.albedo.exr, …)" or " (with channels albedo, …)": what was written beside the image
    /// with the buffers `aovs`, for the command's summary.
    pub fn also_text(&self, aovs: &[Aov]) -> String {
        let mut also: Vec<String> = self.also.iter().map(|p| p.display().to_string()).collect();
        if !aovs.is_empty() && also.is_empty() {
            also.push(format!("with channels {}", aovs.iter().map(|a| a.name()).collect::<Vec<_>>().join(", ")));
        }
        if also.is_empty() {
            String::new()
        } else {
            format!(" ({})", also.join(", "))
        }
    }
}

impl FeatureOutputs {
    /// Checks the destinations of the image `output` and of its feature outputs, and finds the
    /// denoiser if asked for.
    pub fn prepare(args: &FeatureArgs, output: &Path) -> Result<Self, CliError> {
        check_image_destination(output, "-o")?;
        let mut aovs: Vec<Aov> = Vec::new();
        for aov in &args.aov {
            if !aovs.contains(aov) {
                aovs.push(*aov);
            }
        }
        for (_, path) in sibling_files(output, &aovs)? {
            check_image_destination(&path, "--aov")?;
        }
        let ext = output.extension().map(|e| e.to_string_lossy().into_owned()).unwrap_or_default();
        let noisy_output = args.keep_noisy.then(|| sibling(output, "noisy", &ext));
        if let Some(path) = &noisy_output {
            check_image_destination(path, "--keep-noisy")?;
        }
        let denoiser = match args.denoise {
            true => Some(Denoiser::new().map_err(|e| CliError::usage(format!("--denoise: {e}")))?),
            false => None,
        };
        Ok(Self { output: output.to_path_buf(), aovs, denoiser, noisy_output })
    }

    /// The buffers asked for with `--aov`, in order, without repeats.
    pub fn aovs(&self) -> &[Aov] {
        &self.aovs
    }

    /// Writes `image` (denoised first with `--denoise`) and the buffers asked for. `features`
    /// must be there when they were asked for (render and merge check this first).
    pub fn write(
        &self,
        image: Image,
        tone: &ToneMapSettings,
        features: Option<&FeatureBuffers>,
    ) -> Result<Written, CliError> {
        let mut image = image;
        let mut denoise_time = None;
        let mut also = Vec::new();
        if let Some(denoiser) = &self.denoiser {
            let features = features.ok_or_else(|| CliError::runtime("--denoise: the render has no feature buffers"))?;
            if let Some(path) = &self.noisy_output {
                write_image(path, &image, tone).map_err(|e| CliError::runtime(e.to_string()))?;
                also.push(path.clone());
            }
            let start = Instant::now();
            image = denoiser
                .denoise(&image, &features.albedo(), &features.normal())
                .map_err(|e| CliError::runtime(e.to_string()))?;
            denoise_time = Some(start.elapsed());
        }
        let siblings = write_with_aovs(&self.output, &image, tone, features, &self.aovs)?;
        also.splice(0..0, siblings);
        Ok(Written { also, denoise_time })
    }
}

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
fn write_with_aovs(
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
