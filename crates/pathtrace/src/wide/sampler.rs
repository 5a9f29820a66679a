//! The samplers of a lane group: every sampler continues each lane's sequence in SIMD lanes.
//!
//! Why: drawing numbers lane by lane cost about a quarter of the wide kernel's time with the
//! Sobol' sampler (its scrambles are hashes, bit reversals and multiplies, ~150 instructions per
//! 2D point). The lane-parallel versions below compute exactly the numbers the scalar
//! [`Sampler`] would (`sampling/sampler.rs`, `sampling/sobol.rs`, `sampling/pcg.rs`): each lane
//! takes its pixel's hashes from the scalar sampler (which caches them across the pixel's
//! samples), then the new lanes of a group set up their generators and draw together. Tested for equality
//! with the scalar sequences below.

use super::simd::{F32s, Ms};
use crate::sampling::hash::{mix64, permutation_lanes};
use crate::sampling::pcg;
use crate::sampling::sampler::{dimension_hash, jittered, pixel_hash, pixel_stream_prefix, sample_generator};
use crate::sampling::sobol::{dim1_next_column, owen_scramble, to_unit, DIM1_FIRST_COLUMN};
use crate::sampling::{Sampler, SamplerKind};

/// How the group draws its numbers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mode {
    Independent,
    Sobol,
    /// Jittered strata: `n` strata in 1D, an `nx × ny` grid in 2D (`Sampler::next_1d`,
    /// `Sampler::next_2d`).
    Stratified {
        n: u32,
        nx: u32,
        ny: u32,
    },
}

/// The samplers of `N` lanes.
pub(crate) struct LaneSamplers<const N: usize> {
    /// Starts every lane's samples: the queue hands out a pixel's samples one after another,
    /// so one sampler reuses the pixel's hashes across lanes.
    starter: Sampler,
    mode: Mode,
    /// The pixel the starter last began a sample of (the independent sampler's cache).
    started_pixel: (u32, u32),
    round_hash: [u64; N],
    /// Each lane's pixel's generator-stream hash (see `sampler::sample_generator`).
    stream_prefix: [u64; N],
    index: [u32; N],
    /// Each lane's sample's place in its round of strata (the stratified sampler's).
    index_in_round: [u32; N],
    dimension: [u32; N],
    state: [u64; N],
    inc: [u64; N],
}

impl<const N: usize> LaneSamplers<N> {
    pub fn new(proto: &Sampler) -> Self {
        let mode = match proto.kind() {
            SamplerKind::Independent => Mode::Independent,
            SamplerKind::Sobol => Mode::Sobol,
            SamplerKind::Stratified => {
                let (n, (nx, ny)) = (proto.strata_count(), proto.strata_grid());
                Mode::Stratified { n, nx, ny }
            }
        };
        Self {
            starter: proto.clone(),
            mode,
            started_pixel: (u32::MAX, u32::MAX),
            round_hash: [0; N],
            stream_prefix: [0; N],
            index: [0; N],
            index_in_round: [0; N],
            dimension: [0; N],
            state: [0; N],
            inc: [0; N],
        }
    }

    /// Starts sample `index` of pixel `(x, y)` in lane `i` and returns its first 2D point (the
    /// pixel filter's).
    #[cfg(test)]
    pub fn start(&mut self, i: usize, x: u32, y: u32, index: u32) -> crate::math::Vec2 {
        self.begin(i, x, y, index);
        let (u, _) = self.camera_points(Ms::from_fn(|j| j == i), false);
        crate::math::Vec2::new(u[0].0[i], u[1].0[i])
    }

    /// Begins sample `index` of pixel `(x, y)` in lane `i`. The lanes begun together then draw
    /// their first numbers together ([`LaneSamplers::camera_points`]).
    #[inline(always)]
    pub fn begin(&mut self, i: usize, x: u32, y: u32, index: u32) {
        if self.mode == Mode::Independent {
            // A lane of the independent sampler needs only its pixel's stream prefix and its
            // sample index (`camera_points` makes the generator from them): the starter runs
            // once per pixel, not once per sample (its per-sample bookkeeping, unused here, was
            // 5% of an empty frame's profile).
            self.stream_prefix[i] = self.pixel_prefix(x, y, index);
            self.index[i] = index;
        } else {
            // The pixel's hashes lane by lane (the starter caches them across a pixel's
            // samples); the generators of all new lanes at once in `camera_points`.
            let s = &mut self.starter;
            s.start_hashes(x, y, index);
            (self.round_hash[i], self.index[i], self.dimension[i], _, _) = s.lane_state();
            self.index_in_round[i] = s.index_in_round();
            self.stream_prefix[i] = s.stream_prefix();
        }
    }

    /// Begins, in lane `i`, sample `sample[i]` of pixel `(x + step[i], y)`, for steps that do
    /// not decrease: the same lane states as [`LaneSamplers::begin`] lane by lane. The
    /// independent sampler's lanes are made as whole vectors (a run of one pixel's samples, or
    /// of a row's pixels); begun lane by lane, their scalar stores held up the vector code that
    /// draws the lanes' first numbers.
    #[inline(always)]
    pub fn begin_run(&mut self, x: u32, y: u32, step: &[u32; N], sample: &[u32; N]) {
        if self.mode != Mode::Independent {
            for i in 0..N {
                self.begin(i, x + step[i], y, sample[i]);
            }
            return;
        }
        if step[N - 1] == 0 {
            self.stream_prefix = [self.pixel_prefix(x, y, sample[0]); N];
        } else if step[N - 1] == 1 {
            // Two pixels: the first is the last run's last (cached), so one new pixel hash
            // instead of one per lane.
            let first = self.pixel_prefix(x, y, sample[0]);
            let next = self.pixel_prefix(x + 1, y, sample[N - 1]);
            self.stream_prefix = step.map(|k| if k == 0 { first } else { next });
        } else {
            let seed = self.starter.seed();
            self.stream_prefix = std::array::from_fn(|i| pixel_stream_prefix(pixel_hash(seed, x + step[i], y)));
        }
        self.index = *sample;
    }

    /// The independent sampler's stream prefix of pixel `(x, y)`, its hashes made only when
    /// the starter last began another pixel.
    #[inline(always)]
    fn pixel_prefix(&mut self, x: u32, y: u32, index: u32) -> u64 {
        if self.started_pixel != (x, y) {
            self.starter.start_hashes(x, y, index);
            self.started_pixel = (x, y);
        }
        self.starter.stream_prefix()
    }

    /// The first 2D point (the pixel filter's) of every lane of `fresh`, begun with
    /// [`LaneSamplers::begin`], and, when `aperture` is set, its second (the camera's aperture
    /// point); without it the aperture point is the lens centre and no number is drawn, so
    /// pinhole renders keep their sequences.
    #[inline(always)]
    pub fn camera_points(&mut self, fresh: Ms<N>, aperture: bool) -> ([F32s<N>; 2], [F32s<N>; 2]) {
        // The pseudo-random generators (the Sobol' sampler draws no pseudo-random numbers).
        if self.mode != Mode::Sobol {
            for i in 0..N {
                let (state, inc) = sample_generator(self.stream_prefix[i], self.index[i]);
                let keep = fresh.0[i] as u64 | ((fresh.0[i] as u64) << 32);
                self.state[i] = (state & keep) | (self.state[i] & !keep);
                self.inc[i] = (inc & keep) | (self.inc[i] & !keep);
            }
        }
        let (x, y) = self.next_2d(fresh);
        let lens = if aperture { self.next_2d(fresh) } else { (F32s::splat(0.5), F32s::splat(0.5)) };
        ([x, y], [lens.0, lens.1])
    }

    /// The next number of every lane in `mask` (other lanes' values are meaningless and their
    /// sequences do not advance).
    #[inline(always)]
    pub fn next_1d(&mut self, mask: Ms<N>) -> F32s<N> {
        match self.mode {
            Mode::Independent => self.pcg(mask),
            Mode::Sobol => {
                let h = self.dimension_hash(mask);
                let mut out = F32s::default();
                for i in 0..N {
                    let j = owen_scramble(self.index[i], h[i] as u32);
                    out.0[i] = to_unit(owen_scramble(j.reverse_bits(), (h[i] >> 32) as u32));
                }
                out
            }
            Mode::Stratified { n, .. } => {
                let h = self.dimension_hash(mask);
                let stratum = permutation_lanes(&self.index_in_round, n, &h);
                let jitter = self.pcg(mask);
                F32s::from_fn(|i| jittered(stratum[i], jitter.0[i], n))
            }
        }
    }

    /// The next 2D point of every lane in `mask`.
    #[inline(always)]
    pub fn next_2d(&mut self, mask: Ms<N>) -> (F32s<N>, F32s<N>) {
        match self.mode {
            Mode::Independent => {
                let x = self.pcg(mask);
                (x, self.pcg(mask))
            }
            Mode::Sobol => {
                let h = self.dimension_hash(mask);
                let (mut x, mut y) = (F32s::default(), F32s::default());
                let mut j = [0u32; N];
                for i in 0..N {
                    j[i] = owen_scramble(self.index[i], h[i] as u32);
                    x.0[i] = to_unit(owen_scramble(j[i].reverse_bits(), (h[i] >> 32) as u32));
                }
                let dim1 = sobol_dim1(&j);
                for i in 0..N {
                    y.0[i] = to_unit(owen_scramble(dim1[i], mix64(h[i]) as u32));
                }
                (x, y)
            }
            Mode::Stratified { nx, ny, .. } => {
                let h = self.dimension_hash(mask);
                let cell = permutation_lanes(&self.index_in_round, nx * ny, &h);
                let jx = self.pcg(mask);
                let jy = self.pcg(mask);
                let x = F32s::from_fn(|i| jittered(cell[i] % nx, jx.0[i], nx));
                let y = F32s::from_fn(|i| jittered(cell[i] / nx, jy.0[i], ny));
                (x, y)
            }
        }
    }

    /// Each lane's hash of its next dimension; advances the lanes in `mask`.
    #[inline(always)]
    fn dimension_hash(&mut self, mask: Ms<N>) -> [u64; N] {
        let mut h = [0u64; N];
        for i in 0..N {
            h[i] = dimension_hash(self.round_hash[i], self.dimension[i]);
            self.dimension[i] += mask.0[i] & 1;
        }
        h
    }

    /// `Pcg32::next_f32` in every lane; advances the lanes in `mask`.
    #[inline(always)]
    fn pcg(&mut self, mask: Ms<N>) -> F32s<N> {
        let mut out = F32s::default();
        for i in 0..N {
            let old = self.state[i];
            let next = pcg::advance(old, self.inc[i]);
            let keep = (mask.0[i] as u64) | ((mask.0[i] as u64) << 32);
            self.state[i] = (next & keep) | (old & !keep);
            out.0[i] = pcg::unit_f32(pcg::output(old));
        }
        out
    }
}

/// `sobol::sobol_dim1` of every lane, as a loop over the 32 generator columns instead of
/// per-lane table lookups, so it vectorises.
#[inline(always)]
fn sobol_dim1<const N: usize>(j: &[u32; N]) -> [u32; N] {
    let mut out = [0u32; N];
    let mut column = DIM1_FIRST_COLUMN;
    for bit in 0..32 {
        for i in 0..N {
            out[i] ^= ((j[i] >> bit) & 1).wrapping_neg() & column;
        }
        column = dim1_next_column(column);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Vec2;
    use crate::wide::simd::LANES_512 as N;

    /// Every lane continues exactly the scalar sampler's sequence, including lanes that skip
    /// draws (masked out) and lanes at different dimensions.
    #[test]
    fn lanes_draw_the_scalar_samplers_numbers() {
        // Strata of 4 make samples 3i + 1 span several rounds; lanes come in fours per pixel,
        // so the starter's cached pixel and round hashes are both reused and replaced.
        let cases = [SamplerKind::Independent, SamplerKind::Sobol, SamplerKind::Stratified].map(|k| [(k, 64), (k, 4)]);
        for (kind, strata) in cases.into_iter().flatten() {
            let proto = Sampler::new(kind, 11, strata);
            let mut lanes = LaneSamplers::<N>::new(&proto);
            let mut reference: Vec<Sampler> = (0..N).map(|_| proto.clone()).collect();
            for (i, r) in reference.iter_mut().enumerate() {
                let (x, y, s) = (i as u32 / 4 % 3, 1, 3 * (i as u32 % 5) + 1);
                // A fresh scalar sampler per sample: what the lanes draw must not depend on caching.
                *r = proto.clone();
                assert_eq!(lanes.start(i, x, y, s), {
                    r.start(x, y, s);
                    r.next_2d()
                });
            }
            for step in 0..40u32 {
                let mask = Ms::from_fn(|i| !(i as u32 + step).is_multiple_of(3));
                if step % 2 == 0 {
                    let got = lanes.next_1d(mask);
                    for (i, r) in reference.iter_mut().enumerate().filter(|(i, _)| mask.lane(*i)) {
                        assert_eq!(got.0[i], r.next_1d(), "{kind} lane {i} step {step}");
                    }
                } else {
                    let (x, y) = lanes.next_2d(mask);
                    for (i, r) in reference.iter_mut().enumerate().filter(|(i, _)| mask.lane(*i)) {
                        assert_eq!(Vec2::new(x.0[i], y.0[i]), r.next_2d(), "{kind} lane {i} step {step}");
                    }
                }
            }
        }
    }

    /// A pixel's run of samples begun as whole vectors draws what the lanes begun one by one
    /// draw, for every sampler, on the pixel the starter last began and on a new one.
    #[test]
    fn a_run_begun_at_once_draws_what_lanes_begun_one_by_one_draw() {
        for kind in [SamplerKind::Independent, SamplerKind::Sobol, SamplerKind::Stratified] {
            let proto = Sampler::new(kind, 5, 64);
            let (mut run, mut each) = (LaneSamplers::<N>::new(&proto), LaneSamplers::<N>::new(&proto));
            // (x, y, the first lane's place in its pixel's samples, samples per pixel from 0)
            let runs = [
                (3, 4, 0, 64),
                (3, 4, 16, 64),
                (7, 2, 48, 64),
                (0, 5, 0, 1),
                (2, 5, 0, 4),
                (2, 5, 0, 8),
                (3, 4, 32, 64),
                (1, 1, 3, 15),
                (1, 1, 14, 15),
                (6, 3, 2, 3),
                (3, 4, 50, 64),
            ];
            for (x, y, offset, count) in runs {
                let step: [u32; N] = std::array::from_fn(|i| (offset + i as u32) / count);
                let sample: [u32; N] = std::array::from_fn(|i| (offset + i as u32) % count);
                run.begin_run(x, y, &step, &sample);
                for i in 0..N {
                    each.begin(i, x + step[i], y, sample[i]);
                }
                let (a, b) = (run.camera_points(Ms::ALL, true), each.camera_points(Ms::ALL, true));
                assert_eq!(a, b, "{kind} pixel ({x}, {y}) from {offset} of {count} per pixel");
                assert_eq!(run.next_1d(Ms::ALL), each.next_1d(Ms::ALL), "{kind}");
            }
        }
    }
}
