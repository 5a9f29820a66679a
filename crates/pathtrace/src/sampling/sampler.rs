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

use super::hash::{hash_words, permutation_element};
use super::pcg::Pcg32;
use crate::math::Vec2;

/// Which sampler to use.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SamplerKind {
    #[default]
    Independent,
    Stratified,
}

impl SamplerKind {
    pub const NAMES: [&'static str; 2] = ["independent", "stratified"];

    pub fn name(self) -> &'static str {
        match self {
            SamplerKind::Independent => "independent",
            SamplerKind::Stratified => "stratified",
        }
    }
}

impl std::str::FromStr for SamplerKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "independent" | "random" => Ok(SamplerKind::Independent),
            "stratified" | "jittered" => Ok(SamplerKind::Stratified),
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
    index_in_round: u32,
    round: u32,
    dimension: u32,
    rng: Pcg32,
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
            index_in_round: 0,
            round: 0,
            dimension: 0,
            rng: Pcg32::new(0, 0),
        }
    }

    pub fn kind(&self) -> SamplerKind {
        self.kind
    }

    /// Begins sample `index` of pixel `(x, y)`.
    #[inline(always)]
    pub fn start(&mut self, x: u32, y: u32, index: u32) {
        self.pixel_hash = hash_words(&[self.seed, ((x as u64) << 32) | y as u64]);
        self.index_in_round = index % self.strata_count;
        self.round = index / self.strata_count;
        self.dimension = 0;
        let stream = hash_words(&[self.pixel_hash, index as u64]);
        self.rng = Pcg32::new(stream, stream >> 1);
    }

    fn next_dimension_hash(&mut self) -> u64 {
        let d = self.dimension;
        self.dimension += 1;
        hash_words(&[self.pixel_hash, d as u64, self.round as u64])
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
                let jitter = self.rng.next_f32();
                ((stratum as f32 + jitter) / n as f32).min(ONE_MINUS_EPSILON)
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
                let n = self.strata_count;
                let nx = (n as f32).sqrt().ceil() as u32;
                let ny = n.div_ceil(nx);
                let h = self.next_dimension_hash();
                let cell = permutation_element(self.index_in_round, nx * ny, h);
                let (cx, cy) = (cell % nx, cell / nx);
                let jx = self.rng.next_f32();
                let jy = self.rng.next_f32();
                Vec2::new(
                    ((cx as f32 + jx) / nx as f32).min(ONE_MINUS_EPSILON),
                    ((cy as f32 + jy) / ny as f32).min(ONE_MINUS_EPSILON),
                )
            }
        }
    }
}

/// The largest f32 below 1, so `[0,1)` stays half-open after rounding.
const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stratified_2d_puts_one_sample_in_each_stratum() {
        for n in [16u32, 64] {
            let mut s = Sampler::new(SamplerKind::Stratified, 3, n);
            let k = (n as f32).sqrt() as usize;
            for dim in 0..3 {
                let mut cells = vec![0; n as usize];
                for i in 0..n {
                    s.start(5, 9, i);
                    for _ in 0..dim {
                        s.next_2d();
                    }
                    let p = s.next_2d();
                    cells[(p.y * k as f32) as usize * k + (p.x * k as f32) as usize] += 1;
                }
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
    fn samplers_are_deterministic() {
        for kind in [SamplerKind::Independent, SamplerKind::Stratified] {
            let draw = || {
                let mut s = Sampler::new(kind, 11, 16);
                s.start(3, 4, 5);
                (s.next_2d(), s.next_1d(), s.next_2d())
            };
            assert_eq!(draw(), draw());
        }
    }
}
