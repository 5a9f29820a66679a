//! Per-pixel samplers. Both are deterministic functions of (seed, pixel, sample index,
//! dimension), so an image does not depend on how pixels are split among threads.
//!
//! - `Independent`: uniform random numbers (random supersampling).
//! - `Stratified`: every 1D and 2D dimension is jittered-stratified over the pixel's
//!   `strata_count` samples. In 2D the grid is `nx × ny` with `nx = ⌈√n⌉`, `ny = ⌈n / nx⌉`
//!   (`√n × √n` when n is a square). Each sample takes a distinct cell of a random permutation
//!   of the grid, so when `nx·ny > n` a few random cells stay empty: each sample is still
//!   uniform over the square (unbiased), and the strata are still disjoint. Sample indices past
//!   `n` start a new, independently permuted round.
//! - `sobol`: low-discrepancy — a padded, Owen-scrambled 2D Sobol' sequence, shuffled per pixel
//!   and dimension (see `sobol.rs`); any power-of-two prefix of a pixel's samples is a
//!   (0, k, 2)-net in every 2D dimension pair, and the hashed scrambles decorrelate pixels,
//!   which gives the error a blue-noise-like spread across the image.

use super::hash::{hash_word, hash_words, mix64, permutation_element, HASH_START};
use super::pcg::Pcg32;
use super::sobol;
use crate::math::Vec2;

/// Which sampler to use.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SamplerKind {
    #[default]
    Independent,
    Stratified,
    /// Low-discrepancy: Owen-scrambled Sobol'.
    Sobol,
}

impl SamplerKind {
    pub const NAMES: [&'static str; 3] = ["independent", "stratified", "sobol"];

    pub fn name(self) -> &'static str {
        match self {
            SamplerKind::Independent => "independent",
            SamplerKind::Stratified => "stratified",
            SamplerKind::Sobol => "sobol",
        }
    }
}

impl std::str::FromStr for SamplerKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "independent" | "random" => Ok(SamplerKind::Independent),
            "stratified" | "jittered" => Ok(SamplerKind::Stratified),
            "sobol" | "low-discrepancy" | "ld" => Ok(SamplerKind::Sobol),
            _ => Err(format!("unknown sampler '{s}' (expected one of: {})", Self::NAMES.join(", "))),
        }
    }
}

impl std::fmt::Display for SamplerKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The sampler state for one pixel sample. Create one per thread and call
/// [`Sampler::start`] before each pixel sample.
#[derive(Clone, Debug)]
pub struct Sampler {
    kind: SamplerKind,
    seed: u64,
    strata_count: u32,
    pixel_hash: u64,
    /// `hash_words(&[pixel_hash])`: each sample's generator stream is this hash continued with
    /// the sample index (see [`sample_generator`]).
    stream_prefix: u64,
    /// Hash of (pixel, round), from which each dimension's hash is one mix away (left unset by
    /// the independent sampler, which hashes no dimensions).
    round_hash: u64,
    index: u32,
    index_in_round: u32,
    round: u32,
    dimension: u32,
    rng: Pcg32,
    /// The pixel and round whose hashes `pixel_hash` and `round_hash` hold: consecutive
    /// samples of one pixel reuse them (hashing cost ~10% of the wide kernel's time).
    hashed: Option<(u32, u32, u32)>,
}

impl Sampler {
    /// `strata_count` is the number of samples per pixel the stratified sampler spreads its
    /// strata over (the render's spp target); ignored by the independent sampler.
    pub fn new(kind: SamplerKind, seed: u64, strata_count: u32) -> Self {
        Self {
            kind,
            seed,
            strata_count: strata_count.max(1),
            pixel_hash: 0,
            stream_prefix: 0,
            round_hash: 0,
            index: 0,
            index_in_round: 0,
            round: 0,
            dimension: 0,
            rng: Pcg32::new(0, 0),
            hashed: None,
        }
    }

    pub fn kind(&self) -> SamplerKind {
        self.kind
    }

    /// Begins sample `index` of pixel `(x, y)`.
    #[inline(always)]
    pub fn start(&mut self, x: u32, y: u32, index: u32) {
        self.start_hashes(x, y, index);
        // The Sobol' sampler draws no pseudo-random numbers.
        if self.kind != SamplerKind::Sobol {
            let (state, inc) = sample_generator(self.stream_prefix, index);
            self.rng = Pcg32::from_parts(state, inc);
        }
    }

    /// [`Sampler::start`] but for the pseudo-random generator, which the lane samplers set up
    /// for a group of lanes at once from [`Sampler::lane_state`] (see [`sample_generator`]).
    #[inline(always)]
    pub(crate) fn start_hashes(&mut self, x: u32, y: u32, index: u32) {
        self.index = index;
        // One stratum per round (the independent sampler's case) needs no division.
        (self.round, self.index_in_round) = match self.strata_count {
            1 => (index, 0),
            n => (index / n, index % n),
        };
        if self.hashed != Some((x, y, self.round)) {
            if !matches!(self.hashed, Some((hx, hy, _)) if (hx, hy) == (x, y)) {
                self.pixel_hash = pixel_hash(self.seed, x, y);
                self.stream_prefix = pixel_stream_prefix(self.pixel_hash);
            }
            // The independent sampler draws every number from its generator and never asks for
            // a dimension hash; its round is the sample index, so this hash (four SplitMix64
            // steps, scalar) would be made for every sample and never used (`mix64` was 12.5% of
            // an empty frame's profile, most of it here).
            if self.kind != SamplerKind::Independent {
                self.round_hash = hash_words(&[self.pixel_hash, self.round as u64]);
            }
            self.hashed = Some((x, y, self.round));
        }
        self.dimension = 0;
    }

    /// What the lane samplers need to continue this sample's sequence in SIMD lanes:
    /// `(round hash, sample index, next dimension, PCG state, PCG increment)`.
    pub(crate) fn lane_state(&self) -> (u64, u32, u32, u64, u64) {
        let (state, inc) = self.rng.parts();
        (self.round_hash, self.index, self.dimension, state, inc)
    }

    /// The number of strata per round (the stratified sampler's samples per pixel).
    pub(crate) fn strata_count(&self) -> u32 {
        self.strata_count
    }

    /// The stratified sampler's 2D grid, `nx × ny` cells with nx = ⌈√n⌉, ny = ⌈n/nx⌉.
    pub(crate) fn strata_grid(&self) -> (u32, u32) {
        let n = self.strata_count;
        let nx = (n as f32).sqrt().ceil() as u32;
        (nx, n.div_ceil(nx))
    }

    /// The current sample's place in its round of strata.
    pub(crate) fn index_in_round(&self) -> u32 {
        self.index_in_round
    }

    /// The seed every pixel's hash starts from.
    pub(crate) fn seed(&self) -> u64 {
        self.seed
    }

    /// The hash from which sample `index`'s generator is made (see [`sample_generator`]).
    pub(crate) fn stream_prefix(&self) -> u64 {
        self.stream_prefix
    }

    fn next_dimension_hash(&mut self) -> u64 {
        let d = self.dimension;
        self.dimension += 1;
        dimension_hash(self.round_hash, d)
    }

    /// One uniform number in `[0, 1)`.
    #[inline(always)]
    pub fn next_1d(&mut self) -> f32 {
        match self.kind {
            SamplerKind::Independent => {
                self.dimension += 1;
                self.rng.next_f32()
            }
            SamplerKind::Stratified => {
                let n = self.strata_count;
                let h = self.next_dimension_hash();
                let stratum = permutation_element(self.index_in_round, n, h);
                jittered(stratum, self.rng.next_f32(), n)
            }
            SamplerKind::Sobol => {
                let h = self.next_dimension_hash();
                let j = sobol::shuffle(self.index, h as u32);
                sobol::to_unit(sobol::owen_scramble(sobol::sobol_dim0(j), (h >> 32) as u32))
            }
        }
    }

    /// A uniform point in `[0, 1)²`.
    #[inline(always)]
    pub fn next_2d(&mut self) -> Vec2 {
        match self.kind {
            SamplerKind::Independent => {
                self.dimension += 2;
                Vec2::new(self.rng.next_f32(), self.rng.next_f32())
            }
            SamplerKind::Stratified => {
                let (nx, ny) = self.strata_grid();
                let h = self.next_dimension_hash();
                let cell = permutation_element(self.index_in_round, nx * ny, h);
                let jx = self.rng.next_f32();
                let jy = self.rng.next_f32();
                Vec2::new(jittered(cell % nx, jx, nx), jittered(cell / nx, jy, ny))
            }
            SamplerKind::Sobol => {
                let h = self.next_dimension_hash();
                let j = sobol::shuffle(self.index, h as u32);
                let sx = (h >> 32) as u32;
                let sy = mix64(h) as u32;
                Vec2::new(
                    sobol::to_unit(sobol::owen_scramble(sobol::sobol_dim0(j), sx)),
                    sobol::to_unit(sobol::owen_scramble(sobol::sobol_dim1(j), sy)),
                )
            }
        }
    }
}

/// The largest f32 below 1, so `[0,1)` stays half-open after rounding.
const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

/// The point `jitter ∈ [0,1)` of the way through stratum `stratum` of `n` equal strata of
/// `[0,1)` (the stratified sampler's numbers, scalar and in lanes).
#[inline(always)]
pub(crate) fn jittered(stratum: u32, jitter: f32, n: u32) -> f32 {
    ((stratum as f32 + jitter) / n as f32).min(ONE_MINUS_EPSILON)
}

/// The hash of pixel `(x, y)` under `seed`, from which all of the pixel's numbers derive.
/// Always inlined, so the lane samplers' loop over it vectorises.
#[inline(always)]
pub(crate) fn pixel_hash(seed: u64, x: u32, y: u32) -> u64 {
    // `hash_words(&[seed, (x << 32) | y])`, its fold written out.
    hash_word(hash_word(HASH_START, seed), ((x as u64) << 32) | y as u64)
}

/// The stream prefix of the pixel whose hash is `pixel_hash` (see [`sample_generator`]).
#[inline(always)]
pub(crate) fn pixel_stream_prefix(pixel_hash: u64) -> u64 {
    hash_word(HASH_START, pixel_hash)
}

/// The PCG generator `(state, increment)` of sample `index` of a pixel whose stream prefix is
/// `prefix`: the stream is `hash_words(&[pixel_hash, index])`, seeding `Pcg32::new(stream,
/// stream >> 1)`. Always inlined, so the lane samplers' loop over it vectorises (one sample's
/// chain of eight 64-bit multiplies cost about 5% of the teapot's time lane by lane).
#[inline(always)]
pub(crate) fn sample_generator(prefix: u64, index: u32) -> (u64, u64) {
    let stream = hash_word(prefix, index as u64);
    Pcg32::new(stream, stream >> 1).parts()
}

/// The hash of dimension `d` of a sample whose round hash is `round_hash`: one SplitMix64 step
/// per dimension, the golden-ratio increment decorrelating dimensions. Always inlined, so the
/// lane samplers' loop over it vectorises.
#[inline(always)]
pub(crate) fn dimension_hash(round_hash: u64, d: u32) -> u64 {
    mix64(round_hash.wrapping_add((d as u64 + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// How many of samples `0..n` of pixel `(px, py)` fall in each cell of an `nx × ny` grid,
    /// in the 2D dimension pair after skipping `skip` pairs.
    fn cell_counts(s: &mut Sampler, (px, py): (u32, u32), n: u32, skip: usize, (nx, ny): (usize, usize)) -> Vec<u32> {
        let mut cells = vec![0; nx * ny];
        for i in 0..n {
            s.start(px, py, i);
            for _ in 0..skip {
                s.next_2d();
            }
            let p = s.next_2d();
            cells[(p.y * ny as f32) as usize * nx + (p.x * nx as f32) as usize] += 1;
        }
        cells
    }

    #[test]
    fn stratified_2d_puts_one_sample_in_each_stratum() {
        for n in [16u32, 64] {
            let mut s = Sampler::new(SamplerKind::Stratified, 3, n);
            let k = (n as f32).sqrt() as usize;
            for dim in 0..3 {
                let cells = cell_counts(&mut s, (5, 9), n, dim, (k, k));
                assert!(cells.iter().all(|&c| c == 1), "n={n} dim={dim}: {cells:?}");
            }
        }
    }

    #[test]
    fn stratified_non_square_counts_use_distinct_cells() {
        let n = 10; // grid 4 × 3 = 12 cells, two stay empty.
        let mut s = Sampler::new(SamplerKind::Stratified, 1, n);
        let mut cells = [0; 12];
        for i in 0..n {
            s.start(0, 0, i);
            let p = s.next_2d();
            cells[(p.y * 3.0) as usize * 4 + (p.x * 4.0) as usize] += 1;
        }
        assert!(cells.iter().all(|&c| c <= 1));
        assert_eq!(cells.iter().sum::<i32>(), 10);
    }

    #[test]
    fn stratified_1d_puts_one_sample_in_each_stratum() {
        let n = 32;
        let mut s = Sampler::new(SamplerKind::Stratified, 7, n);
        let mut cells = vec![0; n as usize];
        for i in 0..n {
            s.start(1, 2, i);
            s.next_2d();
            cells[(s.next_1d() * n as f32) as usize] += 1;
        }
        assert!(cells.iter().all(|&c| c == 1));
    }

    #[test]
    fn sobol_2d_dimensions_are_nets_in_every_pixel() {
        let n = 64u32;
        for (px, py) in [(0, 0), (5, 9), (300, 17)] {
            let mut s = Sampler::new(SamplerKind::Sobol, 3, n);
            for dim in 0..4 {
                for (nx, ny) in [(8usize, 8usize), (64, 1), (1, 64), (16, 4), (2, 32)] {
                    let cells = cell_counts(&mut s, (px, py), n, dim, (nx, ny));
                    assert!(cells.iter().all(|&c| c == 1), "pixel ({px},{py}) dim {dim} grid {nx}x{ny}");
                }
            }
        }
    }

    #[test]
    fn sobol_differs_between_pixels() {
        let mut s = Sampler::new(SamplerKind::Sobol, 3, 16);
        s.start(0, 0, 0);
        let a = s.next_2d();
        s.start(1, 0, 0);
        let b = s.next_2d();
        assert_ne!(a, b);
    }

    #[test]
    fn samplers_are_deterministic() {
        for kind in [SamplerKind::Independent, SamplerKind::Stratified, SamplerKind::Sobol] {
            let draw = || {
                let mut s = Sampler::new(kind, 11, 16);
                s.start(3, 4, 5);
                (s.next_2d(), s.next_1d(), s.next_2d())
            };
            assert_eq!(draw(), draw());
        }
    }
}
