//! Command-line arguments.

use crate::CliError;
use clap::{Args, Parser, Subcommand};
use pathtrace::film::{PixelFilter, ToneMap, ToneMapSettings};
use pathtrace::integrator::Strategy;
use pathtrace::light::LightSelection;
use pathtrace::sampling::SamplerKind;
use pathtrace::wide::Kernel;
use pathtrace::SampleRange;
use std::path::PathBuf;
use std::process::ExitCode;

/// A physically based Monte Carlo path tracer.
///
/// Renders a scene by following light paths from the camera, refining the image pass by pass.
/// Start with:  pathtrace render cornell-box -o cornell.png
#[derive(Debug, Parser)]
#[command(name = "pathtrace", version, propagate_version = true)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render a scene to an image file (PNG, EXR or PFM), with a progress bar.
    ///
    /// Ctrl-C stops early and still writes what was rendered so far.
    Render(RenderArgs),
    /// Run the benchmark suite: samples/s, rays/s, path length, peak memory and time to a target
    /// error on thirteen scenes (ten need ../shared/scenes), each checked against its stored reference; `bench bvh` measures the
    /// BVH alone (build time, memory, rays/s) on meshes of 10² to 10⁷ triangles.
    Bench(BenchArgs),
    /// Compare an image with a reference: MSE, RMSE, relative MSE, PSNR (8-bit and linear), SSIM.
    ///
    /// Both may be PNG, EXR or PFM. PSNR on 8-bit values uses MAX = 255 on the displayed (clamped,
    /// sRGB) images; linear PSNR uses the reference's peak value.
    Compare(CompareArgs),
    /// Measure convergence: error against a reference at 1, 2, 4, … spp for each strategy ×
    /// sampler × sampling (uniform, adaptive); writes a CSV, log–log plots as SVG and PNG (error
    /// vs spp and vs time) and a table of each method's error at equal time and the time it needs
    /// to reach a target error.
    Converge(ConvergeArgs),
    /// Convert a scene file (Mitsuba 3 .xml, .toml or .json) to the native .toml or .json format.
    ///
    /// Substitutions the native format cannot express are printed as warnings.
    Convert(ConvertArgs),
    /// Watch a scene render live in an OpenGL window; move the camera and change settings while it
    /// converges (F1 in the window lists the shortcuts; see docs/viewer.md).
    ///
    /// Needs a display; without one, use `pathtrace render`.
    View(ViewArgs),
    /// Merge films rendered in sample ranges (`render --sample-range A..B --film-out part.ptfilm`)
    /// into the image one render of every sample gives, bit for bit (docs/distributed.md).
    ///
    /// Refuses films of another scene, settings or engine build, and overlapping ranges (exit 2).
    Merge(MergeArgs),
}

/// How an image written as PNG is tone mapped (`render` and `merge`).
#[derive(Debug, Args)]
pub struct ToneArgs {
    /// Exposure in stops applied before tone mapping (PNG only)
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub exposure: f32,
    /// Tone map for PNG output: clamp or aces (filmic)
    #[arg(long, default_value = "clamp", value_parser = parse_from_str::<ToneMap>)]
    pub tonemap: ToneMap,
}

impl ToneArgs {
    /// The settings, or a usage error for an exposure that is not a finite number.
    pub fn settings(&self) -> Result<ToneMapSettings, CliError> {
        tone_settings(self.exposure, self.tonemap)
    }
}

/// `--exposure` and `--tonemap` as settings; the exposure must be a finite number of stops.
pub fn tone_settings(exposure: f32, tone_map: ToneMap) -> Result<ToneMapSettings, CliError> {
    if !exposure.is_finite() {
        return Err(CliError::usage("--exposure must be a finite number of stops"));
    }
    Ok(ToneMapSettings { exposure, tone_map })
}

#[derive(Debug, Args)]
pub struct MergeArgs {
    /// Film files (.ptfilm) to merge, in any order
    #[arg(required = true, value_name = "PART")]
    pub parts: Vec<PathBuf>,
    /// Write the merged image; the format follows the extension: .png, .exr or .pfm
    #[arg(short, long, value_name = "FILE")]
    pub output: Option<PathBuf>,
    /// Write the merged film (to merge further, or to render the missing ranges later)
    #[arg(long, value_name = "FILE")]
    pub film_out: Option<PathBuf>,
    /// Write the image even when sample ranges are missing (it is then noisier than the whole
    /// render's, but still unbiased)
    #[arg(long)]
    pub partial: bool,
    #[command(flatten)]
    pub tone: ToneArgs,
    // --aov and --denoise need -o and films rendered with the feature buffers.
    #[command(flatten)]
    pub features: FeatureArgs,
    /// No summary (errors and warnings are still printed)
    #[arg(short, long)]
    pub quiet: bool,
}

#[derive(Debug, Args)]
pub struct ViewArgs {
    /// A scene file (.toml, .json or Mitsuba 3 .xml) or a built-in scene name (cornell-box)
    #[arg(default_value = "cornell-box")]
    pub scene: String,
    /// Set a Mitsuba XML scene parameter (overrides its <default name=NAME>); repeatable
    #[arg(short = 'D', long = "define", value_name = "NAME=VALUE", value_parser = parse_define)]
    pub defines: Vec<(String, String)>,
    /// Samples per pixel to stop at; 0 renders until the window is closed [default: the scene's]
    #[arg(long, value_name = "N")]
    pub spp: Option<u32>,
    #[command(flatten)]
    pub quality: QualityArgs,
    /// Starting exposure in stops (keys - and = change it)
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub exposure: f32,
    /// Starting tone map: clamp or aces (key T toggles)
    #[arg(long, default_value = "clamp", value_parser = parse_from_str::<ToneMap>)]
    pub tonemap: ToneMap,
    /// Reference image (EXR, PFM or PNG) of the same size: shows live PSNR and relative MSE, and
    /// enables the difference view
    #[arg(long, value_name = "FILE")]
    pub reference: Option<PathBuf>,
    /// When the render is done, capture the window's picture area to this PNG
    #[arg(long, value_name = "FILE")]
    pub screenshot: Option<PathBuf>,
    /// Take the screenshot as soon as this many samples per pixel are shown (mid-render)
    #[arg(long, value_name = "N", requires = "screenshot")]
    pub screenshot_at_spp: Option<u32>,
    /// Capture the whole window, status bar included, instead of the picture area
    #[arg(long, requires = "screenshot")]
    pub screenshot_window: bool,
    /// Close the window when the render is done (after the screenshot)
    #[arg(long)]
    pub exit_when_done: bool,
}

#[derive(Debug, Args)]
pub struct ConvergeArgs {
    /// A scene file (.toml, .json) or built-in scene name
    #[arg(default_value = "cornell-box")]
    pub scene: String,
    /// Comma-separated strategies to compare
    #[arg(long, default_value = "bsdf,mis")]
    pub strategies: String,
    /// Comma-separated samplers to compare
    #[arg(long, default_value = "independent,sobol")]
    pub samplers: String,
    /// Comma-separated sample placement: uniform (every pixel the same spp) and/or adaptive
    /// (each level's spp on average, sent where the estimated error is largest)
    #[arg(long, default_value = "uniform")]
    pub sampling: String,
    /// Uniform samples per pixel before adaptive sampling starts
    #[arg(long, value_name = "N", default_value_t = 16, value_parser = clap::value_parser!(u32).range(2..))]
    pub min_spp: u32,
    /// Highest sample count (a power of two); levels are 1, 2, 4, … up to it
    #[arg(long, default_value_t = 256, value_parser = clap::value_parser!(u32).range(1..=65536))]
    pub max_spp: u32,
    /// Reference image (EXR/PFM) of the same size; by default one is rendered with mis + sobol
    #[arg(long, value_name = "FILE")]
    pub reference: Option<PathBuf>,
    /// Samples per pixel of the rendered reference
    #[arg(long, default_value_t = 4096, value_parser = clap::value_parser!(u32).range(1..))]
    pub reference_spp: u32,
    /// The relative MSE whose time-to-reach is tabulated
    #[arg(long, default_value_t = 1e-2, value_parser = parse_positive)]
    pub target_error: f64,
    /// Image size [default: the scene's, at most 256x256]
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub size: Option<(u32, u32)>,
    /// Maximum path length in segments (-1 unlimited) [default: the scene's]
    #[arg(long, value_name = "N", allow_negative_numbers = true, value_parser = parse_depth)]
    pub max_depth: Option<i32>,
    /// Worker threads, 1 to 1024; 0 or unset: one per logical core
    #[arg(long, value_name = "N", value_parser = parse_threads)]
    pub threads: Option<usize>,
    /// Base random seed
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Output folder [default: converge-SCENE]
    #[arg(short, long, value_name = "DIR")]
    pub out: Option<PathBuf>,
}

fn parse_positive(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v > 0.0 && v.is_finite() => Ok(v),
        _ => Err(format!("'{s}' is not a positive number")),
    }
}

#[derive(Debug, Args)]
pub struct ConvertArgs {
    /// The scene to read (.xml, .toml or .json)
    pub input: PathBuf,
    /// The file to write (.toml or .json); mesh paths stay relative to the input's folder
    pub output: PathBuf,
    /// Set a Mitsuba parameter (overrides its <default>); repeatable
    #[arg(short = 'D', long = "define", value_name = "NAME=VALUE", value_parser = parse_define)]
    pub defines: Vec<(String, String)>,
}

/// Parses `NAME=VALUE`.
pub fn parse_define(s: &str) -> Result<(String, String), String> {
    match s.split_once('=') {
        Some((n, v)) if !n.is_empty() => Ok((n.to_string(), v.to_string())),
        _ => Err(format!("expected NAME=VALUE, got '{s}'")),
    }
}

#[derive(Debug, Args)]
pub struct CompareArgs {
    /// The image to judge
    pub image: PathBuf,
    /// The reference image
    pub reference: PathBuf,
    /// Write a difference image: changed pixels in red over a grey copy of the reference
    #[arg(long, value_name = "FILE")]
    pub diff: Option<PathBuf>,
    /// A pixel counts as changed when a channel differs by more than this many 8-bit steps
    #[arg(long, default_value_t = 8)]
    pub threshold: u8,
    /// Print the metrics as JSON
    #[arg(long)]
    pub json: bool,
}

/// Options shared by everything that renders.
#[derive(Debug, Clone, Args)]
pub struct QualityArgs {
    /// Image size as WIDTHxHEIGHT, e.g. 512x512 [default: the scene's, 512x512 for cornell-box]
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub size: Option<(u32, u32)>,
    /// Maximum path length in segments: 1 = lights seen directly, 2 = direct lighting,
    /// -1 = unlimited (Russian roulette ends paths) [default: the scene's]
    #[arg(long, value_name = "N", allow_negative_numbers = true, value_parser = parse_depth)]
    pub max_depth: Option<i32>,
    /// Path segments after which Russian roulette may end a path, at least 1 (a large value
    /// turns it off) [default: the scene's, else 5]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub rr_depth: Option<u32>,
    /// Direction sampling: mis (unbiased, least noise), mis-balance, bsdf, mixture, or light (biased
    /// teaching mode: loses indirect light) [default: the scene's, else mis]
    #[arg(long, value_parser = parse_from_str::<Strategy>)]
    pub strategy: Option<Strategy>,
    /// Pixel sampler: independent (random supersampling), stratified (jittered strata) or sobol
    /// (low-discrepancy: Owen-scrambled Sobol') [default: the scene's, else independent]
    #[arg(long, value_parser = parse_from_str::<SamplerKind>)]
    pub sampler: Option<SamplerKind>,
    /// Pixel reconstruction filter, sampled by importance: box (the pixel itself), tent (radius 1)
    /// or gaussian (stddev 0.5, as Mitsuba) [default: the scene's, else box]
    #[arg(long, value_parser = PixelFilter::by_name)]
    pub filter: Option<PixelFilter>,
    /// How next-event estimation picks a light: power (in proportion to emitted power) or uniform
    /// (every light equally) [default: the scene's, else power]
    #[arg(long, value_name = "MODE", value_parser = parse_from_str::<LightSelection>)]
    pub light_selection: Option<LightSelection>,
    /// Paths traced at once: auto and wide (groups of 16 in SIMD lanes with AVX2, 32 with
    /// AVX-512: every scene), wide8 (the AVX2 kernel, 8-lane vectors, even with AVX-512) or scalar
    /// (one at a time: the same estimator in one lane, for debugging). All give the same image to
    /// the bit
    #[arg(long, value_parser = parse_from_str::<Kernel>, default_value = "auto")]
    pub kernel: Kernel,
    /// Random seed: the same seed, scene and settings give the same image [default: the scene's, else 0]
    #[arg(long)]
    pub seed: Option<u64>,
    /// Worker threads, 1 to 1024; 0 or unset: one per logical core
    #[arg(long, value_name = "N", value_parser = parse_threads)]
    pub threads: Option<usize>,
}

/// Adaptive sampling options of `render`.
#[derive(Debug, Clone, Args)]
pub struct AdaptiveArgs {
    /// Adaptive sampling: after --min-spp uniform samples, send each wave's samples to the pixels
    /// with the largest estimated relative error (--spp becomes the average per pixel)
    #[arg(long)]
    pub adaptive: bool,
    /// Stop when the estimated relative RMS error of the image reaches E (e.g. 0.05 for 5%);
    /// implies --adaptive; --spp is then a cap (average per pixel), unlimited if not given
    #[arg(long, value_name = "E", value_parser = parse_positive)]
    pub target_error: Option<f64>,
    /// Uniform samples per pixel before adaptive sampling starts
    #[arg(long, value_name = "N", default_value_t = 16, value_parser = clap::value_parser!(u32).range(2..))]
    pub min_spp: u32,
    /// Also write each pixel's sample count as a grey image (white = the most samples), to see
    /// where adaptive sampling sent them
    #[arg(long, value_name = "FILE")]
    pub spp_image: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct RenderArgs {
    /// A scene file (.toml, .json or Mitsuba 3 .xml, see docs/scene-format.md) or a built-in scene
    /// name (cornell-box)
    #[arg(default_value = "cornell-box")]
    pub scene: String,
    /// Set a Mitsuba XML scene parameter (overrides its <default name=NAME>); repeatable
    #[arg(short = 'D', long = "define", value_name = "NAME=VALUE", value_parser = parse_define)]
    pub defines: Vec<(String, String)>,
    /// Samples per pixel [default: the scene's, 256 for cornell-box]
    #[arg(long, value_name = "N", conflicts_with = "time", value_parser = clap::value_parser!(u32).range(1..))]
    pub spp: Option<u32>,
    /// Render for this many seconds instead of a fixed sample count
    #[arg(long, value_name = "SECONDS", value_parser = parse_seconds)]
    pub time: Option<f64>,
    #[command(flatten)]
    pub quality: QualityArgs,
    #[command(flatten)]
    pub adaptive: AdaptiveArgs,
    /// Output file; the format follows the extension: .png (tone mapped, sRGB), .exr or .pfm
    /// (linear radiance) [default: the scene's name or file stem + .png]
    #[arg(short, long, value_name = "FILE")]
    pub output: Option<PathBuf>,
    #[command(flatten)]
    pub tone: ToneArgs,
    /// No progress bar or summary (errors are still printed)
    #[arg(short, long)]
    pub quiet: bool,
    /// Also write timing and ray statistics as JSON to this file
    #[arg(long, value_name = "FILE")]
    pub stats_json: Option<PathBuf>,
    /// Render only samples A..B (A inclusive, B exclusive) of every pixel of an --spp render: one
    /// machine's share of a render split across several; `pathtrace merge` joins the parts
    #[arg(long, value_name = "A..B", value_parser = parse_from_str::<SampleRange>, conflicts_with_all = ["time", "adaptive", "target_error"])]
    pub sample_range: Option<SampleRange>,
    /// Also write the film (exact per-pixel sums, the scene and settings key, the sample ranges)
    /// to this .ptfilm file, for `pathtrace merge`
    #[arg(long, value_name = "FILE", conflicts_with_all = ["time", "adaptive", "target_error"])]
    pub film_out: Option<PathBuf>,
    #[command(flatten)]
    pub features: FeatureArgs,
}

/// Feature buffers and denoising (`render`, and `merge` from films that carry the buffers).
#[derive(Debug, Args)]
pub struct FeatureArgs {
    /// Feature buffers to save with the image, averaged over its samples: albedo, normal, depth
    /// (comma separated). EXR output gets them as channels albedo.R/G/B, N.X/Y/Z and Z; PNG and
    /// PFM output as sibling files NAME.albedo.exr (.pfm for PFM output), …
    #[arg(long, value_name = "LIST", value_delimiter = ',', value_parser = parse_from_str::<Aov>)]
    pub aov: Vec<Aov>,
    /// Denoise the image with Intel Open Image Denoise 2 (found at run time: see
    /// docs/denoising.md), guided by the albedo and normal buffers
    #[arg(long)]
    pub denoise: bool,
    /// With --denoise, also write the noisy image as NAME.noisy.EXT
    #[arg(long, requires = "denoise")]
    pub keep_noisy: bool,
}

impl FeatureArgs {
    /// Whether the feature buffers are needed.
    pub fn wanted(&self) -> bool {
        !self.aov.is_empty() || self.denoise
    }
}

/// A feature buffer `render --aov` can save.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Aov {
    Albedo,
    Normal,
    Depth,
}

impl Aov {
    pub const ALL: [Aov; 3] = [Aov::Albedo, Aov::Normal, Aov::Depth];

    pub fn name(self) -> &'static str {
        match self {
            Aov::Albedo => "albedo",
            Aov::Normal => "normal",
            Aov::Depth => "depth",
        }
    }
}

impl std::str::FromStr for Aov {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Aov::ALL
            .into_iter()
            .find(|a| a.name() == s.trim())
            .ok_or_else(|| format!("unknown feature buffer '{s}' (expected albedo, normal or depth)"))
    }
}

#[derive(Debug, Args)]
#[command(args_conflicts_with_subcommands = true)]
pub struct BenchArgs {
    #[command(subcommand)]
    pub target: Option<BenchTarget>,
    /// Comma-separated suite scenes, or all: cornell-d8, cornell-inf, spheres, bunny-env,
    /// mesh-1m, veach-mis (bunny-env and veach-mis need ../shared/scenes; skipped without)
    #[arg(long, default_value = "all")]
    pub scenes: String,
    /// Few samples per pixel and one run: a quick smoke test (CI)
    #[arg(long)]
    pub quick: bool,
    /// Samples per pixel per run, for every scene [default: each scene's]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub spp: Option<u32>,
    /// Timed runs per scene; medians are reported [default: 3, 1 with --quick]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub runs: Option<u32>,
    /// Worker threads, 1 to 1024; 0 or unset: one per logical core
    #[arg(long, value_name = "N", value_parser = parse_threads)]
    pub threads: Option<usize>,
    /// Also run each scene on one thread and print all threads' samples/s over one thread's
    #[arg(long)]
    pub scaling: bool,
    /// The relative MSE whose time-to-reach is measured against the stored references
    #[arg(long, value_name = "E", default_value_t = 1e-2, value_parser = parse_positive)]
    pub target_rel_mse: f64,
    /// Folder of the reference images [default: benches/references of the source tree]
    #[arg(long, value_name = "DIR")]
    pub references: Option<PathBuf>,
    /// Render the references of the selected scenes (at many samples per pixel) instead of
    /// benchmarking; they are written to the references folder
    #[arg(long, conflicts_with_all = ["compare", "json"])]
    pub make_references: bool,
    /// Samples per pixel of --make-references [default: each scene's]
    #[arg(long, value_name = "N", requires = "make_references", value_parser = clap::value_parser!(u32).range(1..))]
    pub reference_spp: Option<u32>,
    /// Print the results as JSON instead of a table
    #[arg(long)]
    pub json: bool,
    /// Compare two `bench --json` reports: per-scene ratios of speed, time to quality, memory
    #[arg(long, num_args = 2, value_names = ["OLD", "NEW"])]
    pub compare: Option<Vec<PathBuf>>,
    /// Measure the scenes in this process instead of one child process per scene (used by the
    /// parent; the peak memory is then cumulative)
    #[arg(long, hide = true)]
    pub in_process: bool,
}

#[derive(Debug, Subcommand)]
pub enum BenchTarget {
    /// Benchmark the BVH on generated meshes (tessellated sphere, random triangle soup,
    /// subdivided Stanford bunny): build time (SAH serial and parallel, median split), memory
    /// per triangle, and million rays/s for camera and incoherent rays, closest and any hit,
    /// on 1 and all threads, against median split and brute force (see docs/bvh.md).
    Bvh(BvhBenchArgs),
}

#[derive(Debug, Args)]
pub struct BvhBenchArgs {
    /// Comma-separated meshes: sphere, soup, bunny (the bunny needs ../shared/scenes/bunny;
    /// its sizes are 69,451 × 4^k triangles)
    #[arg(long, default_value = "sphere,soup,bunny")]
    pub scenes: String,
    /// Smallest triangle count (e.g. 100 or 1e2)
    #[arg(long, default_value = "100", value_parser = parse_count)]
    pub min_tris: usize,
    /// Largest triangle count (at most 1e7)
    #[arg(long, default_value = "1e6", value_parser = parse_count)]
    pub max_tris: usize,
    /// Sizes per decade (1: 100, 1000, …; 2 adds 316, 3162, …)
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=10))]
    pub steps_per_decade: u32,
    /// Rays per ray set (camera rays and incoherent rays)
    #[arg(long, default_value = "2e5", value_parser = parse_count)]
    pub rays: usize,
    /// Timed repetitions of every measurement; the median is reported
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..))]
    pub runs: u32,
    /// Brute force (O(n) per ray) only up to this many triangles
    #[arg(long, default_value = "1e4", value_parser = parse_count)]
    pub brute_max: usize,
    /// SAH bins per axis
    #[arg(long, default_value_t = 16, value_parser = clap::value_parser!(u32).range(2..=32))]
    pub bins: u32,
    /// Largest SAH leaf, in triangles
    #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u32).range(1..=64))]
    pub max_leaf: u32,
    /// Threads for the all-threads columns and the parallel build, up to 1024 [default: one per core]
    #[arg(long, value_name = "N", value_parser = parse_threads)]
    pub threads: Option<usize>,
    /// Time one-thread work (serial builds, 1-thread rays) by the thread's CPU time instead of
    /// the wall clock, so other processes on a shared machine do not count (Linux only)
    #[arg(long)]
    pub cpu_time: bool,
    /// Also write the results as CSV to this file
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,
    /// Write log–log SVG plots (time per ray, build time, rays/s against triangles) into this folder
    #[arg(long, value_name = "DIR")]
    pub plots: Option<PathBuf>,
    /// Print the results as JSON instead of tables
    #[arg(long)]
    pub json: bool,
    /// Instead of benchmarking, write the first mesh at --max-tris, its incoherent rays and our
    /// closest hits to FILE for benches/peers/bvh_embree.py (prints our speed as JSON)
    #[arg(long, value_name = "FILE")]
    pub export: Option<PathBuf>,
    /// Instead of the size sweep: a unit-sphere mesh of --max-tris triangles placed N times as
    /// instances (a two-level BVH) against the mesh alone (build, memory, incoherent rays/s)
    #[arg(long, value_name = "N", value_parser = parse_count)]
    pub instances: Option<usize>,
}

/// A count such as `1000`, `1e6` or `2.5e5`, from 1 to 10⁷.
fn parse_count(s: &str) -> Result<usize, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if (1.0..=1e7).contains(&v) && v.fract() == 0.0 => Ok(v as usize),
        _ => Err(format!("'{s}' is not a whole number from 1 to 1e7")),
    }
}

/// The most worker threads a render may ask for: far beyond any machine's cores, yet few enough to
/// start in milliseconds (100000 threads took ~50 s to spawn, then failed).
pub const MAX_THREADS: usize = 1024;

fn parse_threads(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if n <= MAX_THREADS => Ok(n),
        _ => Err(format!("'{s}': threads must be a whole number from 0 (one per core) to {MAX_THREADS}")),
    }
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(|| format!("'{s}' is not WIDTHxHEIGHT (e.g. 512x512)"))?;
    let parse = |v: &str| v.trim().parse::<u32>().ok().filter(|&n| (1..=32768).contains(&n));
    match (parse(w), parse(h)) {
        (Some(w), Some(h)) => Ok((w, h)),
        _ => Err(format!("'{s}': width and height must be whole numbers from 1 to 32768")),
    }
}

fn parse_depth(s: &str) -> Result<i32, String> {
    match s.parse::<i32>() {
        Ok(d) if d >= -1 => Ok(d),
        _ => Err(format!("'{s}' is not a path length (a whole number ≥ 1, 0, or -1 for unlimited)")),
    }
}

fn parse_seconds(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(t) if t > 0.0 && t.is_finite() && t < 1e7 => Ok(t),
        _ => Err(format!("'{s}' is not a positive number of seconds")),
    }
}

fn parse_from_str<T: std::str::FromStr>(s: &str) -> Result<T, String>
where
    T::Err: std::fmt::Display,
{
    s.parse().map_err(|e: T::Err| e.to_string())
}

/// Help and version go to stdout with exit 0; any other parse error is one line on stderr with
/// exit code 2.
pub fn report_parse_error(e: clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = e.print();
            if e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
                ExitCode::from(crate::EXIT_USAGE)
            } else {
                ExitCode::SUCCESS
            }
        }
        _ => {
            // clap's first paragraph, folded onto one line (e.g. the list of missing arguments).
            let rendered = e.render().to_string();
            let paragraph: Vec<&str> =
                rendered.lines().map(str::trim).skip_while(|l| l.is_empty()).take_while(|l| !l.is_empty()).collect();
            let message =
                if paragraph.is_empty() { "error: invalid arguments".to_string() } else { paragraph.join(" ") };
            eprintln!("{} (see 'pathtrace --help')", pathtrace_scene::elide::elide_long_runs(&message));
            ExitCode::from(crate::EXIT_USAGE)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_and_bad_ones_explain() {
        assert_eq!(parse_size("640x480"), Ok((640, 480)));
        assert_eq!(parse_size("16X8"), Ok((16, 8)));
        assert!(parse_size("640").unwrap_err().contains("WIDTHxHEIGHT"));
        assert!(parse_size("0x10").is_err());
        assert!(parse_size("axb").is_err());
    }

    #[test]
    fn depths_accept_minus_one_only() {
        assert_eq!(parse_depth("-1"), Ok(-1));
        assert_eq!(parse_depth("8"), Ok(8));
        assert!(parse_depth("-2").is_err());
    }

    #[test]
    fn cli_definition_is_consistent() {
        use clap::CommandFactory;
        Cli::command().debug_assert();
    }
}
