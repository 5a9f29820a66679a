//! Path regeneration: a tile's pixel samples flow through a group of `N` lanes, and lanes whose
//! paths ended start the tile's next camera samples once half the group is idle, so lanes do not
//! wait for the longest path of a batch (as wavefront renderers and Mitsuba 3's vectorised
//! variants do), yet a group's paths stay together long enough to keep their rays coherent
//! ([`refill_due`]).

use super::lanes::{Output, Paths, Surfaces, TileSplat};
use super::path::vertex;
use crate::camera::Camera;
use crate::film::{FeaturePixel, PixelFilter, PixelStats, SplatBlock};
use crate::integrator::PathStats;
use crate::render::tile::{Tile, TileResult, WaveSamples};
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::wide::simd::{F32s, Ms};
use crate::wide::{LaneSamplers, WideScene};

/// What every tile of a render shares.
pub(crate) struct LaneJob<'a> {
    pub scene: &'a Scene,
    /// The scene's lane-parallel forms.
    pub lanes: &'a WideScene,
    pub camera: &'a Camera,
    pub filter: &'a PixelFilter,
    /// Record each sample's features (albedo, normal, depth) beside its radiance.
    pub features: bool,
}

/// The tile's pixel samples, pixel by pixel (so the camera rays of a batch are neighbours).
struct Queue<'a> {
    tile: Tile,
    samples: WaveSamples<'a>,
    /// The current pixel: its index in the tile and its film coordinates (kept as the index
    /// advances: two divisions per sample were 1.3% of the teapot's render).
    pixel: u32,
    x: u32,
    y: u32,
    next: u32,
    end: u32,
}

/// One pixel sample to start: index of the pixel in the tile, its coordinates, sample index.
struct Job {
    pixel: u32,
    x: u32,
    y: u32,
    sample: u32,
}

/// Samples for a whole lane group at once: lane `i` takes the `i`-th sample from `first` in the
/// queue's order. `first.sample` is sample `offset` of its pixel's `count` in this wave, so lane
/// `i` is `(offset + i) / count` pixels to the right of `first`'s and takes that pixel's sample
/// `(offset + i) % count` ([`Run::lanes`]).
struct Run {
    first: Job,
    offset: u32,
    count: u32,
}

/// The largest samples per pixel of a wave whose runs may span pixels: [`Run::lanes`] divides
/// by a multiply and shift that is exact for dividends below 2³² / `count`, and its dividends
/// stay below `count` plus the lanes.
const RUN_COUNT_LIMIT: u32 = 1 << 15;

impl Run {
    /// Each lane's pixel, as steps right of `first`'s, and its sample index.
    #[inline(always)]
    fn lanes<const N: usize>(&self) -> ([u32; N], [u32; N]) {
        // (offset + i) / count as ((offset + i) · m) >> 32 with m = ⌊2³² / count⌋ + 1: with
        // m · count = 2³² + e, 0 < e ≤ count, the product overshoots (offset + i) / count by
        // (offset + i) · e / (count · 2³²) < 1 / count, too little to reach the next integer
        // while (offset + i) < 2³² / count (Granlund & Montgomery, "Division by Invariant
        // Integers using Multiplication", PLDI 1994). Whole-vector integer code, where a
        // division would be one instruction per lane.
        let m = (1u64 << 32) / u64::from(self.count) + 1;
        let step: [u32; N] = std::array::from_fn(|i| ((u64::from(self.offset + i as u32) * m) >> 32) as u32);
        let sample = std::array::from_fn(|i| self.first.sample + i as u32 - step[i] * self.count);
        (step, sample)
    }
}

impl<'a> Queue<'a> {
    fn new(tile: Tile, samples: WaveSamples<'a>) -> Self {
        let mut q = Self { tile, samples, pixel: 0, x: tile.x0, y: tile.y0, next: 0, end: 0 };
        q.enter_pixel();
        q
    }

    fn enter_pixel(&mut self) {
        if self.pixel < self.tile.w * self.tile.h {
            let (first, count) = self.samples.range(self.x, self.y);
            self.next = first;
            self.end = first + count;
        }
    }

    /// Moves to the tile's next pixel, row by row.
    fn advance(&mut self) {
        self.pixel += 1;
        self.x += 1;
        if self.x == self.tile.x0 + self.tile.w {
            self.x = self.tile.x0;
            self.y += 1;
        }
    }

    /// Moves past finished pixels; false when the tile has no samples left.
    #[inline(always)]
    fn skip_finished(&mut self) -> bool {
        let pixels = self.tile.w * self.tile.h;
        while self.next >= self.end {
            if self.pixel >= pixels {
                return false;
            }
            self.advance();
            self.enter_pixel();
        }
        self.pixel < pixels
    }

    #[inline(always)]
    fn pop(&mut self) -> Option<Job> {
        if !self.skip_finished() {
            return None;
        }
        let sample = self.next;
        self.next += 1;
        Some(Job { pixel: self.pixel, x: self.x, y: self.y, sample })
    }

    /// The next `n` samples as a [`Run`], when they lie in one row of the tile: `n` samples of
    /// one pixel, or, in a uniform wave, the rest of this pixel's samples, then the samples of
    /// the pixels to its right in the queue's order. Then the queue is where `n` calls of
    /// [`Queue::pop`] would leave it, and lane `i` of the run is what the `i`-th of those calls
    /// would give. Otherwise `None`, and the next `pop` gives what it would have.
    #[inline(always)]
    fn pop_run(&mut self, n: u32) -> Option<Run> {
        // The same moves past finished pixels as `pop` makes first.
        if !self.skip_finished() {
            return None;
        }
        let first = Job { pixel: self.pixel, x: self.x, y: self.y, sample: self.next };
        if self.end - self.next >= n {
            self.next += n;
            return Some(Run { first, offset: 0, count: n });
        }
        // Several pixels, all with this wave's `count` samples from `wave_first`, all in this
        // row of the tile.
        let WaveSamples::Uniform { first: wave_first, count } = self.samples else { return None };
        let offset = self.next - wave_first;
        let last = offset + n - 1;
        let span = last / count;
        if count > RUN_COUNT_LIMIT || self.x + span >= self.tile.x0 + self.tile.w {
            return None;
        }
        // Onto the run's last pixel, past the sample its last lane takes.
        self.pixel += span;
        self.x += span;
        self.next = wave_first + last % count + 1;
        Some(Run { first, offset, count })
    }
}

/// Renders the wave's samples of every pixel in `tile` in groups of `N` lanes. Each pixel
/// sample's random numbers come from a copy of `proto` started at (pixel, sample index), so the
/// result does not depend on the thread, the lane or the lane count.
#[inline(always)]
pub(crate) fn render_tile_lanes<const N: usize>(
    job: &LaneJob,
    proto: &Sampler,
    tile: Tile,
    samples: WaveSamples,
) -> TileResult {
    let mut samplers = LaneSamplers::<N>::new(proto);
    let tile_pixels = (tile.w * tile.h) as usize;
    let mut out = Output {
        pixels: vec![PixelStats::default(); tile_pixels],
        stats: PathStats::default(),
        dropped: 0,
        features: job.features.then(|| vec![FeaturePixel::default(); tile_pixels]),
        splat: job.filter.splats().then(|| TileSplat {
            block: SplatBlock::for_tile(
                job.filter,
                (tile.x0, tile.y0, tile.w, tile.h),
                job.camera.width,
                job.camera.height,
            ),
            filter: job.filter.clone(),
            x0: tile.x0,
            y0: tile.y0,
            w: tile.w,
        }),
    };
    let mut queue = Queue::new(tile, samples);
    let mut paths = Paths::<N>::new();
    // The group's closest hits, kept from vertex to vertex (see `Surfaces::clear`).
    let mut surfaces = Surfaces::<N>::none();
    let max_depth = job.lanes.settings.max_depth;
    let aperture = job.camera.needs_aperture_sample();
    loop {
        // Lanes whose path ended take the tile's next samples: their random numbers and pixel
        // offsets lane by lane, their camera rays together.
        let mut fresh = Ms::<N>::NONE;
        let mut pixel = [0u32; N];
        let mut at = [F32s::<N>::ZERO; 2];
        // When every lane is free and the next N samples lie in one tile row (one pixel's, or
        // consecutive pixels' in a uniform wave), the lanes are filled as whole vectors;
        // otherwise lane by lane. Both give lane i the same sample. Runs across pixels whatever
        // the wave's count: the waves of 15 and 7 samples per pixel that 16- and 8-spp renders
        // take after their first sample started their lanes one by one (docs/benchmarks.md).
        let run = if paths.active.any() { None } else { queue.pop_run(N as u32) };
        if let Some(run) = run {
            let (step, sample) = run.lanes::<N>();
            let Job { pixel: p, x, y, .. } = run.first;
            samplers.begin_run(x, y, &step, &sample);
            fresh = Ms::ALL;
            pixel = step.map(|k| p + k);
            at = [F32s(step.map(|k| (x + k) as f32)), F32s::splat(y as f32)];
        } else if refill_due(paths.active) {
            for i in (!paths.active).lanes() {
                let Some(next) = queue.pop() else { break };
                samplers.begin(i, next.x, next.y, next.sample);
                fresh.0[i] = u32::MAX;
                pixel[i] = next.pixel;
                (at[0].0[i], at[1].0[i]) = (next.x as f32, next.y as f32);
            }
        }
        if fresh.any() {
            let (u_filter, u_aperture) = samplers.camera_points(fresh, aperture);
            // Where in the pixel the ray goes (film/filter.rs); filters wider than the pixel
            // weight the sample when it is splatted (film/splat.rs). Lanes not started are
            // ignored from here on.
            let jitter = job.filter.sample_lanes(u_filter);
            let (origin, dir) = job.camera.generate_rays(at, jitter, u_aperture);
            paths.start(fresh, &pixel, &origin, &dir, job.scene.camera_medium(), &jitter, job.features);
            if max_depth == 0 {
                paths.finish_all(fresh, &mut out);
            }
            out.stats.camera_rays += u64::from(fresh.bitmask().count_ones());
        }
        if !paths.active.any() {
            break;
        }
        vertex(job, &mut paths, &mut samplers, &mut surfaces, &mut out);
    }
    TileResult {
        tile,
        pixels: out.pixels,
        stats: out.stats,
        dropped: out.dropped,
        features: out.features,
        splat: out.splat.map(|s| s.block),
    }
}

/// Whether the idle lanes of a group whose active lanes are `active` take new samples now: once
/// half the group or more is idle (always when all are). Refilling every idle lane at once kept
/// the lanes busiest, but mixed a group's late bounce rays with the next pixels' camera rays:
/// waiting until half the group is idle keeps one pixel's samples together longer (their
/// camera rays and the bounce rays from their first hits walk the tree as a group, and more
/// groups start as whole vectors). Measured on two threads against refilling at once
/// (docs/benchmarks.md, "Lanes refilled once half the group is idle"): mesh-1m 0.925,
/// matpreview glass 0.881, copper 0.941, bunny 0.953, cornell-box-bitterli 1.026 (its long
/// paths leave more lanes idle), cbox, veach-mis and the teapot unchanged. Waiting for the
/// whole group gained more on the first four and lost 16% on cornell-box-bitterli.
#[inline(always)]
fn refill_due<const N: usize>(active: Ms<N>) -> bool {
    let idle = N as u32 - active.bitmask().count_ones();
    idle > 0 && 2 * idle >= N as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn groups_refill_once_half_their_lanes_are_idle() {
        let with_active = |n: usize| Ms::<16>::from_fn(|i| i < n);
        assert!(refill_due(with_active(0)), "an idle group refills");
        assert!(refill_due(with_active(8)), "half idle refills");
        assert!(!refill_due(with_active(9)), "less than half idle waits");
        assert!(!refill_due(with_active(16)), "a full group has nothing to refill");
        assert!(refill_due(Ms::<1>::from_fn(|_| false)), "the one-lane instance refills its lane");
        assert!(!refill_due(Ms::<1>::from_fn(|_| true)));
    }

    /// Taking runs of samples where they fit, and single samples elsewhere, hands out the same
    /// samples in the same order as taking them one by one: uniform waves of several sizes
    /// (runs within a pixel, runs across a row's pixels, counts that do not divide the run) and
    /// per-pixel counts (adaptive waves, with empty pixels), in a narrow and a wide tile.
    #[test]
    fn runs_hand_out_the_samples_one_by_one_pops_do() {
        let counts: Vec<u32> = (0..12 * 4).map(|i| [0, 16, 5, 33, 16, 1][i % 6]).collect();
        let firsts: Vec<u32> = (0..12 * 4).map(|i| 7 * i as u32).collect();
        let key = |j: Job| (j.pixel, j.x, j.y, j.sample);
        let mut across_pixels = 0;
        for tile in [Tile { x0: 2, y0: 1, w: 3, h: 2 }, Tile { x0: 1, y0: 0, w: 9, h: 3 }] {
            let waves = [
                WaveSamples::Uniform { first: 0, count: 16 },
                WaveSamples::Uniform { first: 3, count: 40 },
                WaveSamples::Uniform { first: 0, count: 4 },
                WaveSamples::Uniform { first: 5, count: 2 },
                WaveSamples::Uniform { first: 0, count: 1 },
                WaveSamples::Uniform { first: 1, count: 3 },
                WaveSamples::Uniform { first: 1, count: 15 },
                WaveSamples::Uniform { first: 1, count: 7 },
                WaveSamples::PerPixel { width: 12, first: &firsts, count: &counts },
            ];
            for samples in waves {
                let mut one = Queue::new(tile, samples);
                let expected: Vec<_> = std::iter::from_fn(|| one.pop()).map(key).collect();
                for n in [4, 8, 16] {
                    let mut q = Queue::new(tile, samples);
                    let mut got = Vec::new();
                    loop {
                        if let Some(run) = q.pop_run(n) {
                            let (step, sample) = run.lanes::<16>();
                            across_pixels += usize::from(step[n as usize - 1] > 0);
                            let j = run.first;
                            got.extend((0..n as usize).map(|i| (j.pixel + step[i], j.x + step[i], j.y, sample[i])));
                        } else if let Some(j) = q.pop() {
                            got.push(key(j));
                        } else {
                            break;
                        }
                    }
                    assert_eq!(got, expected, "{tile:?}, {samples:?}, runs of {n}");
                }
            }
        }
        assert!(across_pixels > 0);
    }
}
