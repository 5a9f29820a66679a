//! Splatting for reconstruction filters wider than the pixel (gaussian, tent, box of radius
//! above ½), with Mitsuba 3's convention (src/render/imageblock.cpp `put`, src/films/hdrfilm.cpp
//! `develop`), so that our expected image is Mitsuba's, borders included:
//! - a camera sample's film position p is uniform in its pixel (the pixel's corner plus a uniform
//!   2D sample: src/render/integrator.cpp `render_sample`), and samples are drawn only inside the
//!   film (Mitsuba's `sample_border` is false by default);
//! - the sample adds f₁(cₓ − pₓ)·f₁(c_y − p_y) · L and that weight to every pixel whose centre
//!   c (pixel corner + ½) lies within the filter's radius, pixels outside the film being skipped
//!   (the footprint is clipped, not folded back);
//! - a pixel's value is Σ w·L / Σ w (normalised by the weights it actually received, so a border
//!   pixel is the ratio over its clipped footprint, as Mitsuba's weight channel gives).
//!
//! f₁ is the filter's one-axis profile, unnormalised ([`PixelFilter::profile`]): the ratio
//! cancels any constant factor. Mitsuba's llvm variants evaluate f₁ exactly (its discretised
//! table serves the scalar variants only); so do we.
//!
//! **Exactness.** Each weight and each product w·L is computed in f64 from the sample alone (a
//! pure function of it) and truncated once to the fixed-point grid of `accumulator.rs`; the sums
//! are integers, so tiles, threads, lanes, waves and machines merge to the same bits in any order.
//!
//! **Noise statistics.** The adaptive sampler, the error estimate and the variance image keep
//! using each pixel's own samples ([`super::PixelStats`]: count, Σx, Σx², unweighted since the
//! position is uniform in the pixel). That variance is of the box-filtered pixel; the splatted
//! pixel averages about 4πσ²≈3 (gaussian σ = ½) pixels' samples and is less noisy, so the
//! statistics are conservative per pixel. For a block of pixels much larger than the filter the
//! splat only moves each sample's weight within the block (except at its edge), so the block's
//! variance is close to the box estimate's — what the block z-tests use.

use super::accumulator::{fixed, integral_to_i64, sum_to_f64, SCALE, SMALL_LIMIT};
use super::filter::PixelFilter;
use super::grid::Mergeable;
use crate::math::{Rgb, Vec2};

/// The splatted sums of one pixel: Σ w and Σ w·L per channel, in fixed point.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct SplatPixel {
    /// Σ trunc(w · 2⁴⁰).
    pub weight: i128,
    /// Σ trunc(w·L · 2⁴⁰) per channel.
    pub sum: [i128; 3],
}

impl SplatPixel {
    /// Adds a sample of radiance `c` with filter weight `w`.
    #[inline(always)]
    pub fn add(&mut self, w: f64, c: Rgb) {
        self.weight += fixed(w);
        for (k, x) in c.to_array().into_iter().enumerate() {
            self.sum[k] += fixed(w * x as f64);
        }
    }

    /// Adds partial sums (Σw, Σw·L per channel) kept on the same grid in `i64`.
    #[inline]
    fn add_partial(&mut self, s: &[i64; 4]) {
        self.weight += i128::from(s[0]);
        for k in 0..3 {
            self.sum[k] += i128::from(s[k + 1]);
        }
    }

    /// Σ w·L / Σ w per channel; zero where no weight landed.
    pub fn value(&self) -> [f64; 3] {
        if self.weight == 0 {
            return [0.0; 3];
        }
        self.sum.map(|s| sum_to_f64(s) / sum_to_f64(self.weight))
    }
}

impl Mergeable for SplatPixel {
    #[inline]
    fn merge(&mut self, o: &Self) {
        self.weight += o.weight;
        for k in 0..3 {
            self.sum[k] += o.sum[k];
        }
    }
}

/// Pixels a sample may reach on each side of its own: ⌈r − ½⌉ (a centre is at most r away).
pub fn splat_margin(filter: &PixelFilter) -> u32 {
    (filter.radius() as f64 - 0.5).ceil().max(0.0) as u32
}

/// Splats a block takes in `i64` partial sums before adding them into its exact sums: each
/// adds at most one term below 2⁴⁶ to a pixel, so 2¹⁶ of them stay below 2⁶³.
const SMALL_SPLATS: u32 = 1 << 16;

/// A rectangle of splatted sums: a tile extended by the filter's margin (its halo), clipped to
/// the film. Blocks merge into the film by integer addition, in any order.
///
/// Why two tiers: the `i128` sums cost a splat four conversions with range checks and four
/// two-word additions per pixel (16 pixels for the gaussian of σ = ½), a quarter of veach-mis's
/// render time. A sample whose every term is small (weights and w·L below 2⁶: nearly all) adds
/// them in `i64`, four lanes per pixel; the others, and the `i64` sums every [`SMALL_SPLATS`]
/// splats, join the `i128` sums. Both tiers hold the same truncated terms, so the totals are
/// the same integers whichever tier a term went through.
#[derive(Clone, Debug)]
pub struct SplatBlock {
    pub x0: u32,
    pub y0: u32,
    pub w: u32,
    pub h: u32,
    /// Exact sums of the large terms and of the flushed partial sums.
    pixels: Vec<SplatPixel>,
    /// Partial sums of the small terms: Σw and Σw·L per channel, on the same grid.
    small: Vec<[i64; 4]>,
    /// Splats since `small` was last added into `pixels`.
    pending: u32,
    margin: u32,
    /// The filter's [`PixelFilter::support_len`].
    support_len: i64,
    /// f₁ at the footprint's columns and rows, reused from sample to sample.
    wx: Vec<f64>,
    wy: Vec<f64>,
}

impl SplatBlock {
    /// The block of the tile at `(x0, y0)` of `w` × `h` pixels in a `width` × `height` film.
    pub fn for_tile(filter: &PixelFilter, (x0, y0, w, h): (u32, u32, u32, u32), width: u32, height: u32) -> Self {
        let margin = splat_margin(filter);
        let bx0 = x0.saturating_sub(margin);
        let by0 = y0.saturating_sub(margin);
        let bx1 = (x0 + w).saturating_add(margin).min(width);
        let by1 = (y0 + h).saturating_add(margin).min(height);
        let (bw, bh) = (bx1 - bx0, by1 - by0);
        let n = 2 * margin as usize + 1;
        Self {
            x0: bx0,
            y0: by0,
            w: bw,
            h: bh,
            pixels: vec![SplatPixel::default(); bw as usize * bh as usize],
            small: vec![[0; 4]; bw as usize * bh as usize],
            pending: 0,
            margin,
            support_len: filter.support_len() as i64,
            wx: vec![0.0; n],
            wy: vec![0.0; n],
        }
    }

    /// Splats a sample of pixel `(x, y)` (film coordinates) at `jitter` within it (`[0, 1)²`
    /// from its corner) with radiance `c`.
    // Always inlined: it runs for every sample of a splatting render, inside the render loop's
    // AVX2/AVX-512 code (out of line, compiled for baseline x86-64, `floor` is a library call
    // and the whole splat was 14% of cbox's time, 18% of veach-mis's).
    #[inline(always)]
    pub fn splat(&mut self, filter: &PixelFilter, x: u32, y: u32, jitter: Vec2, c: Rgb) {
        let m = self.margin as i64;
        // Film-plane position in f64: exact from the f32 jitter, a pure function of the sample.
        let (px, py) = (x as f64 + jitter.x as f64, y as f64 + jitter.y as f64);
        // The floors are integers below 2³³, so `integral_to_i64` converts them exactly (Rust's
        // saturating `as` compiled to scalar conversions with NaN and range fix-ups here).
        let (fx, fy) = (integral_to_i64(px.floor()) - m, integral_to_i64(py.floor()) - m);
        // Offsets of the footprint's first pixel centres (exact: small integers, halves and the
        // position all fit f64's 53 bits); the row's others follow at +1, +2, ….
        filter.profile_rows(fx as f64 + 0.5 - px, fy as f64 + 0.5 - py, &mut self.wx, &mut self.wy);
        // Only the pixels within the filter's support, a fixed count per axis (the rows above
        // hold zeros at the others), clipped to the block once rather than tested pixel by
        // pixel. (Trimming the zeros by testing the weights made cbb's splats about 10% slower:
        // the tests' outcomes follow the sample's position, which no predictor can guess.)
        // A box's closed support can start one centre before the row, at exactly r from a
        // sample on a pixel edge; the `max(0)` leaves it out, as the footprint always has.
        let n = self.wx.len() as i64;
        let (sx, sy) = (filter.support_start(px) - fx, filter.support_start(py) - fy);
        let (bx0, by0) = (self.x0 as i64, self.y0 as i64);
        let (bw, bh) = (self.w as i64, self.h as i64);
        let (i0, i1) = ((bx0 - fx).max(sx).max(0), (bx0 + bw - fx).min(sx + self.support_len).min(n));
        let (j0, j1) = ((by0 - fy).max(sy).max(0), (by0 + bh - fy).min(sy + self.support_len).min(n));
        if i0 >= i1 || j0 >= j1 {
            return;
        }
        // Every weight is at most max wx · max wy (profiles are non-negative, rounding monotone).
        let w_max = self.wx[i0 as usize..i1 as usize].iter().fold(0.0f64, |a, &b| a.max(b))
            * self.wy[j0 as usize..j1 as usize].iter().fold(0.0f64, |a, &b| a.max(b));
        let l_max = c.to_array().iter().fold(0.0f32, |a, &x| a.max(x.abs())) as f64;
        // Small terms go to the `i64` partial sums, the others straight to the exact sums.
        let small = c.is_finite() && w_max < SMALL_LIMIT && w_max * l_max < SMALL_LIMIT;
        // The terms w·L scaled to the grid, as w·(L·2⁴⁰): scaling by a power of two is exact, so
        // this is the same product as (w·L)·2⁴⁰ (no term comes near f64's range limits), with
        // the scaling hoisted out of the pixel loop.
        let l = c.to_array().map(f64::from);
        let scaled = [SCALE, l[0] * SCALE, l[1] * SCALE, l[2] * SCALE];
        for j in j0..j1 {
            let wy = self.wy[j as usize];
            let row = (fy + j - by0) * bw - bx0 + fx;
            for i in i0..i1 {
                let wx = self.wx[i as usize];
                let p = (row + i) as usize;
                if small {
                    // A zero weight adds zeros: no branch, so the four sums go as one vector.
                    let w = wx * wy;
                    for (sum, s) in self.small[p].iter_mut().zip(scaled) {
                        *sum += integral_to_i64((w * s).trunc());
                    }
                } else if wx != 0.0 && wy != 0.0 {
                    self.pixels[p].add(wx * wy, c);
                }
            }
        }
        if small {
            self.pending += 1;
            if self.pending == SMALL_SPLATS {
                self.flush();
            }
        }
    }

    /// Adds the partial sums into the exact ones.
    fn flush(&mut self) {
        for (p, s) in self.pixels.iter_mut().zip(&mut self.small) {
            p.add_partial(s);
            *s = [0; 4];
        }
        self.pending = 0;
    }

    /// The block's sums, row by row: what it adds to the film.
    pub fn sums(&self) -> Vec<SplatPixel> {
        let mut out = self.pixels.clone();
        for (p, s) in out.iter_mut().zip(&self.small) {
            p.add_partial(s);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::GaussianFilter;

    fn gaussian() -> PixelFilter {
        PixelFilter::Gaussian(GaussianFilter::new(0.5).unwrap())
    }

    #[test]
    fn margins_follow_the_radius() {
        assert_eq!(splat_margin(&gaussian()), 2);
        assert_eq!(splat_margin(&PixelFilter::Tent { radius: 1.0 }), 1);
        assert_eq!(splat_margin(&PixelFilter::Box { radius: 1.5 }), 1);
        assert_eq!(splat_margin(&PixelFilter::Box { radius: 1.6 }), 2);
    }

    #[test]
    fn a_centred_sample_spreads_the_separable_profile_and_is_clipped_at_the_border() {
        let f = gaussian();
        let mut block = SplatBlock::for_tile(&f, (0, 0, 2, 2), 4, 4);
        assert_eq!((block.x0, block.y0, block.w, block.h), (0, 0, 4, 4));
        block.splat(&f, 0, 0, Vec2::new(0.5, 0.5), Rgb::splat(2.0));
        // Pixel (0,0) gets f₁(0)², (1,0) f₁(1)·f₁(0), (2,0) f₁(2)·f₁(0) = 0 (the cut-off).
        // The row recurrence of `profile_row` agrees with f₁ to a few ulps: within two quanta
        // of the fixed-point grid (2⁻⁴⁰ each) for weights near 1.
        let w = |x: f64, y: f64| fixed(f.profile(x) * f.profile(y));
        let near = |a: i128, b: i128| (a - b).abs() <= 2;
        assert!(near(block.sums()[0].weight, w(0.0, 0.0)), "{} vs {}", block.sums()[0].weight, w(0.0, 0.0));
        assert!(near(block.sums()[1].weight, w(1.0, 0.0)));
        assert_eq!(block.sums()[2].weight, 0);
        assert!(near(block.sums()[4 + 1].weight, w(1.0, 1.0)));
        // The ratio is the radiance up to the fixed-point quantum.
        assert!(block.sums()[0].value().iter().all(|v| (v - 2.0).abs() < 1e-11));
        // Nothing landed outside the 2-pixel radius.
        assert_eq!(block.sums()[3 * 4].weight, 0);
    }

    /// ∫₀ᵂ f₁(c − p) g(p) dp by the midpoint rule on a fine grid.
    fn integral(f: &PixelFilter, c: f64, extent: f64, g: impl Fn(f64) -> f64) -> f64 {
        let n = 200_000;
        let h = extent / n as f64;
        (0..n).map(|i| (i as f64 + 0.5) * h).map(|p| f.profile(c - p) * g(p)).sum::<f64>() * h
    }

    #[test]
    fn splatting_converges_to_mitsubas_clipped_filtered_image_border_pixels_included() {
        // A film-plane radiance L(p) = (1 + 0.3 pₓ) · (1 + 0.1 p_y²) per channel, sampled on a
        // fine stratified grid in every pixel. Mitsuba's expected pixel value is the filter-
        // weighted mean of L over the film (the footprint clipped to it, pixel centres at
        // corner + ½): by separability a product of one-axis ratios, integrated independently
        // here. Sampling outside the film, folding the weights back or a half-pixel shift would
        // each miss the border pixels by far more than the tolerance.
        let (width, height, k) = (6u32, 5u32, 48u32);
        let lx = |x: f64| 1.0 + 0.3 * x;
        let ly = |y: f64| 1.0 + 0.1 * y * y;
        for f in [gaussian(), PixelFilter::Tent { radius: 1.5 }, PixelFilter::Box { radius: 1.0 }] {
            let mut block = SplatBlock::for_tile(&f, (0, 0, width, height), width, height);
            for y in 0..height {
                for x in 0..width {
                    for j in 0..k {
                        for i in 0..k {
                            let jitter = Vec2::new((i as f32 + 0.5) / k as f32, (j as f32 + 0.5) / k as f32);
                            let l = lx(x as f64 + jitter.x as f64) * ly(y as f64 + jitter.y as f64);
                            block.splat(&f, x, y, jitter, Rgb::new(l as f32, 2.0 * l as f32, 0.5));
                        }
                    }
                }
            }
            let mut worst = 0.0f64;
            for y in 0..height {
                for x in 0..width {
                    let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
                    let ex = integral(&f, cx, width as f64, lx) / integral(&f, cx, width as f64, |_| 1.0);
                    let ey = integral(&f, cy, height as f64, ly) / integral(&f, cy, height as f64, |_| 1.0);
                    let v = block.sums()[(y * width + x) as usize].value();
                    let err =
                        ((v[0] - ex * ey) / (ex * ey)).abs().max(((v[1] - 2.0 * ex * ey) / (2.0 * ex * ey)).abs());
                    worst = worst.max(err);
                    assert!((v[2] - 0.5).abs() < 1e-6, "{f:?} ({x}, {y}): a constant stays constant: {}", v[2]);
                }
            }
            // The corner pixel's clipped footprint pulls its value well away from L(centre).
            let corner = block.sums()[0].value()[0];
            assert!((corner - lx(0.5) * ly(0.5)).abs() > 0.01, "{f:?}: corner {corner}");
            assert!(worst < 2e-3, "{f:?}: worst relative error {worst:.2e}");
        }
    }

    /// The two tiers hold the same integers: a block's sums equal the sums of one-sample blocks
    /// (each sample's terms alone), for small samples, large ones (the exact tier) and more
    /// splats than the partial sums take before they are flushed.
    #[test]
    fn partial_sums_and_flushes_keep_the_exact_sums() {
        for f in [gaussian(), PixelFilter::Tent { radius: 1.0 }] {
            let (width, height) = (5u32, 4u32);
            let mut all = SplatBlock::for_tile(&f, (0, 0, width, height), width, height);
            let mut expected = vec![SplatPixel::default(); (width * height) as usize];
            let mut rng = crate::sampling::Pcg32::new(3, 1);
            let count = SMALL_SPLATS as usize + 4321;
            for n in 0..count {
                let (x, y) = (n as u32 % width, (n as u32 / width) % height);
                let jitter = Vec2::new(rng.next_f32(), rng.next_f32());
                let scale = if n % 997 == 0 { 3e5 } else { 5.0 };
                let c = Rgb::new(rng.next_f32() * scale, -rng.next_f32(), rng.next_f32() * 1e-9);
                all.splat(&f, x, y, jitter, c);
                let mut one = SplatBlock::for_tile(&f, (0, 0, width, height), width, height);
                one.splat(&f, x, y, jitter, c);
                for (e, p) in expected.iter_mut().zip(one.sums()) {
                    e.merge(&p);
                }
            }
            assert!(all.sums() == expected, "{f:?}: the block's sums differ from its samples' sums");
            // About 69,700 small splats went through the partial sums: without the flush after
            // 2¹⁶ of them, `pending` would count them all.
            assert!(all.pending < 5000, "the partial sums were flushed ({} pending)", all.pending);
        }
    }

    #[test]
    fn the_halo_is_clipped_to_the_film() {
        let f = gaussian();
        let b = SplatBlock::for_tile(&f, (8, 8, 8, 8), 20, 18);
        assert_eq!((b.x0, b.y0, b.w, b.h), (6, 6, 12, 12));
        let b = SplatBlock::for_tile(&f, (16, 16, 4, 2), 20, 18);
        assert_eq!((b.x0, b.y0, b.w, b.h), (14, 14, 6, 4));
    }
}
