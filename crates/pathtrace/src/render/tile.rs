//! Rendering one tile for one wave of samples.

use crate::camera::Camera;
use crate::film::{FeaturePixel, PixelFilter, PixelStats, SplatBlock};
use crate::integrator::{render_tile_lanes, LaneJob, PathStats};
use crate::sampling::Sampler;
use crate::scene::Scene;
#[cfg(not(all(feature = "avx512-only", target_arch = "x86_64", not(debug_assertions))))]
use crate::wide::simd::LANES_256;
#[cfg(all(target_arch = "x86_64", not(debug_assertions), not(feature = "avx2-only")))]
use crate::wide::simd::LANES_512;
use crate::wide::WideScene;

/// A rectangle of pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Tile {
    pub x0: u32,
    pub y0: u32,
    pub w: u32,
    pub h: u32,
}

/// Splits the image into tiles, row by row.
pub(super) fn tiles(width: u32, height: u32, size: u32) -> Vec<Tile> {
    let size = size.max(1);
    let mut out = Vec::new();
    for y0 in (0..height).step_by(size as usize) {
        for x0 in (0..width).step_by(size as usize) {
            out.push(Tile { x0, y0, w: size.min(width - x0), h: size.min(height - y0) });
        }
    }
    out
}

/// What every tile of a render shares: the scene and its lane-parallel forms (with the path
/// settings), the camera and the pixel filter.
pub(super) struct TileJob<'a> {
    pub scene: &'a Scene,
    pub camera: &'a Camera,
    pub lanes: &'a WideScene,
    /// Trace one path at a time (`Kernel::Scalar`) instead of a SIMD group.
    pub one_lane: bool,
    /// Run the AVX2 kernel (groups of 16 lanes) even where AVX-512 runs (`Kernel::Wide8`).
    /// Unread in builds with debug assertions, which have only the portable 8-lane loop
    /// (`render_tile`).
    #[cfg_attr(any(debug_assertions, feature = "avx2-only"), allow(dead_code))]
    pub avx2_kernel: bool,
    pub filter: &'a PixelFilter,
    /// Record feature buffers (`RenderSettings::features`).
    pub features: bool,
}

/// Which samples of each pixel a wave renders.
#[derive(Clone, Copy, Debug)]
pub(crate) enum WaveSamples<'a> {
    /// Samples `first .. first + count` of every pixel.
    Uniform { first: u32, count: u32 },
    /// Pixel `i` (row-major over an image `width` wide) takes samples
    /// `first[i] .. first[i] + count[i]` (adaptive sampling).
    PerPixel { width: u32, first: &'a [u32], count: &'a [u32] },
}

impl WaveSamples<'_> {
    /// The first sample index and the number of samples of pixel `(x, y)`.
    #[inline(always)]
    pub(crate) fn range(&self, x: u32, y: u32) -> (u32, u32) {
        match *self {
            WaveSamples::Uniform { first, count } => (first, count),
            WaveSamples::PerPixel { width, first, count } => {
                let i = (y * width + x) as usize;
                (first[i], count[i])
            }
        }
    }
}

/// The samples of one tile for one wave.
pub(crate) struct TileResult {
    pub tile: Tile,
    pub pixels: Vec<PixelStats>,
    pub stats: PathStats,
    pub dropped: u64,
    /// The tile's feature sums, when the render records features.
    pub features: Option<Vec<FeaturePixel>>,
    /// The tile's splatted sums over its halo, when the filter is wider than the pixel.
    pub splat: Option<SplatBlock>,
}

/// Renders the wave's samples (`samples`) of every pixel in `tile`, filtered by the job's pixel
/// filter. Each pixel sample's random numbers depend only on (seed, pixel, sample index), never
/// on the thread.
///
/// The same code runs compiled for the widest SIMD the CPU has, chosen at run time so the
/// binary stays portable: groups of 32 lanes (two vectors) with AVX-512, of 16 (two vectors) with
/// AVX2, of 8 in the portable build. Rust never fuses multiply-adds on its own, so every build
/// computes the same values per sample, and the film sums them exactly, so every build gives the
/// same image (to check it, `Kernel::Wide8` forces the AVX2 kernel where AVX-512 would run).
/// Setting `PATHTRACE_NO_AVX512` or `PATHTRACE_NO_AVX2` forces the narrower builds, to measure
/// them (docs/benchmarks.md).
///
/// Builds with debug assertions (the dev and test profiles) compile only the portable copy. Each
/// copy of the wide loop is one very large function, and LLVM's loop passes take time quadratic in
/// its size (`ScalarEvolution::forgetLoop` dominated a profile of the compiler): the test build
/// of this crate took over 40 minutes with three copies. Every copy computes the same image, so
/// tests of the portable copy hold for the others; release builds keep all three (experiment
/// builds keep one: `avx512_only`, `avx2_only`).
pub(super) fn render_tile(job: &TileJob, sampler: &mut Sampler, tile: Tile, samples: WaveSamples) -> TileResult {
    #[cfg(all(
        target_arch = "x86_64",
        not(debug_assertions),
        not(feature = "avx512-only"),
        not(feature = "avx2-only")
    ))]
    {
        let avx2 = has_avx2_loop_features() && std::env::var_os("PATHTRACE_NO_AVX2").is_none();
        let avx512 = avx2 && has_avx512_loop_features() && std::env::var_os("PATHTRACE_NO_AVX512").is_none();
        if avx512 && !job.one_lane && !job.avx2_kernel {
            // SAFETY: `render_tile_avx512` only requires AVX-512 F/VL/DQ/BW, AVX2 and the bit
            // instructions, which the CPU was just checked to have.
            #[allow(unsafe_code)]
            return unsafe { render_tile_avx512(job, sampler, tile, samples) };
        }
        if avx2 {
            // SAFETY: `render_tile_avx2` only requires AVX2 and the bit instructions, which the
            // CPU was just checked to have.
            #[allow(unsafe_code)]
            return unsafe { render_tile_avx2(job, sampler, tile, samples) };
        }
    }
    #[cfg(not(all(
        any(feature = "avx512-only", feature = "avx2-only"),
        target_arch = "x86_64",
        not(debug_assertions)
    )))]
    return render_tile_body::<LANES_256>(job, sampler, tile, samples);
    #[cfg(all(feature = "avx512-only", target_arch = "x86_64", not(debug_assertions)))]
    return avx512_only(job, sampler, tile, samples);
    #[cfg(all(feature = "avx2-only", target_arch = "x86_64", not(debug_assertions)))]
    return avx2_only(job, sampler, tile, samples);
}

/// Experiment builds (`--features pathtrace/avx512-only`, release profile) compile only the
/// AVX-512 loop: each copy of the loop is one very large function and most of the build's time
/// (see [`render_tile`]). Such a build takes 27 CPU minutes against a release build's 68, and
/// renders at the same speed (docs/benchmarks.md, "Experiment builds"), for speed A/Bs of two
/// such builds on an AVX-512 machine. Not for shipping: it renders nothing else (no `--kernel
/// scalar` or `wide8`, no CPU without AVX-512). Builds with debug assertions ignore the feature.
#[cfg(all(feature = "avx512-only", target_arch = "x86_64", not(debug_assertions)))]
fn avx512_only(job: &TileJob, sampler: &mut Sampler, tile: Tile, samples: WaveSamples) -> TileResult {
    assert!(
        has_avx2_loop_features() && has_avx512_loop_features() && !job.one_lane && !job.avx2_kernel,
        "this experiment build (feature avx512-only) renders only with the AVX-512 group loop"
    );
    // SAFETY: the CPU was just checked to have every feature `render_tile_avx512` enables.
    #[allow(unsafe_code)]
    unsafe {
        render_tile_avx512(job, sampler, tile, samples)
    }
}

#[cfg(all(feature = "avx512-only", feature = "avx2-only"))]
compile_error!("the experiment features avx512-only and avx2-only exclude each other");

/// Experiment builds for AVX2 machines (`--features pathtrace/avx2-only`, release profile):
/// only the AVX2 loop is compiled, as `avx512_only` does for AVX-512. Not for shipping.
#[cfg(all(feature = "avx2-only", target_arch = "x86_64", not(debug_assertions)))]
fn avx2_only(job: &TileJob, sampler: &mut Sampler, tile: Tile, samples: WaveSamples) -> TileResult {
    assert!(
        has_avx2_loop_features() && !job.one_lane,
        "this experiment build (feature avx2-only) renders only with the AVX2 group loop"
    );
    // SAFETY: the CPU was just checked to have every feature `render_tile_avx2` enables.
    #[allow(unsafe_code)]
    unsafe {
        render_tile_avx2(job, sampler, tile, samples)
    }
}

/// Whether the CPU has what [`render_tile_avx2`] enables. Every AVX2 CPU made (Intel since
/// Haswell, AMD since Excavator) also has the bit instructions, but they are separate CPUID bits,
/// so they are checked too.
#[cfg(all(target_arch = "x86_64", not(debug_assertions)))]
fn has_avx2_loop_features() -> bool {
    std::arch::is_x86_feature_detected!("avx2")
        && std::arch::is_x86_feature_detected!("popcnt")
        && std::arch::is_x86_feature_detected!("bmi1")
        && std::arch::is_x86_feature_detected!("bmi2")
        && std::arch::is_x86_feature_detected!("lzcnt")
}

/// Whether the CPU has the AVX-512 parts of what `render_tile_avx512` enables (the rest is
/// [`has_avx2_loop_features`]).
#[cfg(all(target_arch = "x86_64", not(debug_assertions), not(feature = "avx2-only")))]
fn has_avx512_loop_features() -> bool {
    std::arch::is_x86_feature_detected!("avx512f")
        && std::arch::is_x86_feature_detected!("avx512vl")
        && std::arch::is_x86_feature_detected!("avx512dq")
        && std::arch::is_x86_feature_detected!("avx512bw")
}

/// The bit instructions (`popcnt`, BMI1/2, `lzcnt`) come with the vector ones. Without them
/// each `count_ones` of a lane mask compiled to a dozen shifts and masks, and each
/// `mask & (mask - 1)` of the loops over a mask's lanes to two instructions where BMI1 has
/// `blsr`. Measured on two threads against the build without them (docs/benchmarks.md, "The bit
/// instructions enabled beside the vector ones"): mesh-1m 0.90×, copper 0.89×, glass 0.93×,
/// bunny 0.94× the time. They are integer instructions: no value of the render changes.
#[cfg(all(target_arch = "x86_64", not(debug_assertions), not(feature = "avx512-only")))]
#[target_feature(enable = "avx2,popcnt,bmi1,bmi2,lzcnt")]
fn render_tile_avx2(job: &TileJob, sampler: &mut Sampler, tile: Tile, samples: WaveSamples) -> TileResult {
    render_tile_body::<AVX2_GROUP>(job, sampler, tile, samples)
}

/// Lanes per group in the AVX2 kernel: two 8-lane vectors, as the AVX-512 kernel runs two
/// 16-lane ones, for the same reason (see `AVX512_GROUP`). Measured against groups of 8 on an
/// AVX2 machine, two threads (docs/benchmarks.md, "Groups of 16 lanes with AVX2"): copper 0.83,
/// bunny 0.83, glass 0.85, teapot-zoomed 0.88 the time; groups of 32 (four vectors) were slower
/// than 16 on cornell-box-bitterli (1.29) and veach-mis (1.13).
#[cfg(all(target_arch = "x86_64", not(debug_assertions), not(feature = "avx512-only")))]
const AVX2_GROUP: usize = 2 * LANES_256;

#[cfg(all(target_arch = "x86_64", not(debug_assertions), not(feature = "avx2-only")))]
#[target_feature(enable = "avx2,avx512f,avx512vl,avx512dq,avx512bw,popcnt,bmi1,bmi2,lzcnt")]
fn render_tile_avx512(job: &TileJob, sampler: &mut Sampler, tile: Tile, samples: WaveSamples) -> TileResult {
    render_tile_body::<AVX512_GROUP>(job, sampler, tile, samples)
}

/// Lanes per group in the AVX-512 kernel: two 16-lane vectors. A group's control (the walk's
/// per-node loop and stack, the lane loops of the hit records and samplers, the refill) is paid
/// once for twice the paths, and the camera rays of a pixel's samples share more node visits.
/// Measured against 16-lane groups on two threads (docs/benchmarks.md, "Groups of 32 lanes with
/// AVX-512"): mesh-1m 0.967, bunny 0.935, copper 0.957, cornell-box-bitterli 0.963, teapot
/// 0.978, veach-mis 0.976, cbox 1.009 the time; films byte-identical.
#[cfg(all(target_arch = "x86_64", not(debug_assertions), not(feature = "avx2-only")))]
const AVX512_GROUP: usize = 2 * LANES_512;

/// `N`: lanes per group (the one-lane instance when the job asks for it).
#[inline(always)]
fn render_tile_body<const N: usize>(
    job: &TileJob,
    sampler: &mut Sampler,
    tile: Tile,
    samples: WaveSamples,
) -> TileResult {
    let TileJob { scene, camera, lanes, one_lane, filter, features, .. } = *job;
    let job = LaneJob { scene, lanes, camera, filter, features };
    #[cfg(not(all(
        any(feature = "avx512-only", feature = "avx2-only"),
        target_arch = "x86_64",
        not(debug_assertions)
    )))]
    if one_lane {
        return render_tile_one_lane(&job, sampler, tile, samples);
    }
    #[cfg(all(any(feature = "avx512-only", feature = "avx2-only"), target_arch = "x86_64", not(debug_assertions)))]
    let _ = one_lane;
    render_tile_lanes::<N>(&job, sampler, tile, samples)
}

/// The one-lane instance, compiled on its own: inlined beside the wide loop it doubled that
/// function's size, and the wide loop's code got slower.
#[cfg(not(all(any(feature = "avx512-only", feature = "avx2-only"), target_arch = "x86_64", not(debug_assertions))))]
#[inline(never)]
fn render_tile_one_lane(job: &LaneJob, sampler: &mut Sampler, tile: Tile, samples: WaveSamples) -> TileResult {
    render_tile_lanes::<1>(job, sampler, tile, samples)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiles_cover_the_image_once() {
        let ts = tiles(37, 20, 16);
        let area: u32 = ts.iter().map(|t| t.w * t.h).sum();
        assert_eq!(area, 37 * 20);
        assert_eq!(ts.len(), 3 * 2);
        assert!(ts.iter().all(|t| t.x0 + t.w <= 37 && t.y0 + t.h <= 20));
    }
}
