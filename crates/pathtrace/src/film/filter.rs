//! Pixel reconstruction filters, with Mitsuba 3's definitions (src/rfilters/*.cpp). Each is
//! separable, f(x, y) = f₁(x)·f₁(y), and [`PixelFilter::profile`] is its one-axis profile f₁,
//! the one implementation both uses below share:
//! - `box` of radius r: f₁ = 1 on [−r, r];
//! - `tent` of radius r: f₁ = max(0, 1 − |x|/r);
//! - `gaussian` (src/rfilters/gaussian.cpp): stddev σ (default ½), cut at r = 4σ,
//!   f₁(x) = max(0, exp(−x²/2σ²) − exp(−r²/2σ²)).
//!
//! How a filter is applied depends on its width:
//! - the pixel's own square (the default, box radius ½) and narrower boxes: each pixel's samples
//!   are uniform over the box and the pixel is their mean — every pixel an independent estimate;
//! - wider filters are **splatted** as Mitsuba does (`splat.rs`): the sample's position is uniform
//!   in its pixel and it adds f·L and f to every pixel within the radius, each pixel dividing at
//!   the end. (Sampling the filter by importance per pixel instead, as pbrt-v4 §8.8.4 does, gives
//!   every pixel its own samples only: about 4πσ² ≈ 3 times the variance of the splatted pixel
//!   for the σ = ½ gaussian at equal samples, and a different expected value at the image's
//!   border, where Mitsuba normalises by the clipped weights.)

use super::accumulator::integral_to_i64;
use crate::math::exp_f64_lanes;
use crate::math::Vec2;
use crate::wide::simd::F32s;

/// One coordinate of a sample of a box narrower than the pixel (`radius` < ½): uniform over
/// `[½ − radius, ½ + radius)` for `u` uniform in `[0, 1)`, relative to the pixel's corner.
#[inline(always)]
fn narrow_box_offset(u: f32, radius: f32) -> f32 {
    0.5 + (2.0 * u - 1.0) * radius
}

/// How the samples of a pixel are spread over and around it.
#[derive(Clone, Debug, PartialEq, Default)]
pub enum PixelFilter {
    /// Uniform over a square of half-width `radius` pixels (0.5 is the pixel itself).
    Box { radius: f32 },
    /// Linear falloff to zero at `radius` pixels.
    Tent { radius: f32 },
    /// Mitsuba 3's windowed gaussian.
    Gaussian(GaussianFilter),
    /// The pixel's own square: the default, identical to `Box { radius: 0.5 }`.
    #[default]
    Pixel,
}

impl PixelFilter {
    pub const NAMES: [&'static str; 3] = ["box", "tent", "gaussian"];

    /// Mitsuba's tent default radius (one pixel).
    pub const DEFAULT_TENT_RADIUS: f32 = 1.0;
    /// Mitsuba's gaussian default standard deviation (half a pixel).
    pub const DEFAULT_GAUSSIAN_STDDEV: f32 = 0.5;

    /// A filter by name with its default parameters.
    pub fn by_name(name: &str) -> Result<PixelFilter, String> {
        match name.to_ascii_lowercase().as_str() {
            "box" => Ok(PixelFilter::Pixel),
            "tent" => Ok(PixelFilter::Tent { radius: Self::DEFAULT_TENT_RADIUS }),
            "gaussian" => Ok(PixelFilter::Gaussian(GaussianFilter::new(Self::DEFAULT_GAUSSIAN_STDDEV)?)),
            _ => Err(format!("unknown filter '{name}' (expected one of: {})", Self::NAMES.join(", "))),
        }
    }

    /// The widest support a filter may have, in pixels from the sample: a splat keeps a row of
    /// weights across the support (`splat.rs`), so a radius of 10⁹ would ask for gigabytes
    /// before the first sample. 40 000 pixels is wider than any film.
    pub const MAX_RADIUS: f32 = 4.0e4;

    /// A box or tent of the given radius in pixels, which must be positive and at most
    /// [`PixelFilter::MAX_RADIUS`].
    pub fn with_radius(name: &str, radius: f32) -> Result<PixelFilter, String> {
        if !(radius > 0.0 && radius <= Self::MAX_RADIUS) {
            return Err(format!(
                "filter radius {radius} must be a positive number of pixels, at most {}",
                Self::MAX_RADIUS
            ));
        }
        match name {
            "box" if radius == 0.5 => Ok(PixelFilter::Pixel),
            "box" => Ok(PixelFilter::Box { radius }),
            "tent" => Ok(PixelFilter::Tent { radius }),
            _ => Err(format!("filter '{name}' takes no radius (box and tent do)")),
        }
    }

    pub fn name(&self) -> &'static str {
        match self {
            PixelFilter::Box { .. } | PixelFilter::Pixel => "box",
            PixelFilter::Tent { .. } => "tent",
            PixelFilter::Gaussian(_) => "gaussian",
        }
    }

    /// Half-width of the filter's support in pixels.
    pub fn radius(&self) -> f32 {
        match self {
            PixelFilter::Pixel => 0.5,
            PixelFilter::Box { radius } | PixelFilter::Tent { radius } => *radius,
            PixelFilter::Gaussian(g) => g.radius(),
        }
    }

    /// Whether samples are splatted into the pixels around theirs (`splat.rs`): filters wider
    /// than the pixel. The default pixel box (and narrower boxes) never are, so that path
    /// stays the plain per-pixel mean.
    pub fn splats(&self) -> bool {
        match self {
            PixelFilter::Pixel => false,
            PixelFilter::Box { radius } => *radius > 0.5,
            PixelFilter::Tent { .. } | PixelFilter::Gaussian(_) => true,
        }
    }

    /// Where in its pixel a camera sample goes, from a uniform 2D sample: uniform in the pixel
    /// (`u` itself) for the pixel box and for splatting filters (whose weights are applied when
    /// the sample is splatted), uniform over the smaller square of a box narrower than the pixel
    /// (whose weight f/pdf is 1). The result is relative to the pixel's upper-left corner.
    #[inline(always)]
    pub fn sample(&self, u: Vec2) -> Vec2 {
        match self {
            PixelFilter::Box { radius } if *radius < 0.5 => {
                Vec2::new(narrow_box_offset(u.x, *radius), narrow_box_offset(u.y, *radius))
            }
            _ => u,
        }
    }

    /// [`PixelFilter::sample`] of every lane's point `(u[0], u[1])`, with the same operations
    /// per lane (so the same bits), as whole vectors.
    #[inline(always)]
    pub fn sample_lanes<const N: usize>(&self, u: [F32s<N>; 2]) -> [F32s<N>; 2] {
        match self {
            PixelFilter::Box { radius } if *radius < 0.5 => {
                let mut out = u;
                for (o, u) in out.iter_mut().zip(u) {
                    for i in 0..N {
                        o.0[i] = narrow_box_offset(u.0[i], *radius);
                    }
                }
                out
            }
            _ => u,
        }
    }

    /// The one-axis profile f₁ at an offset `x` (pixels) from the pixel centre, unnormalised as
    /// Mitsuba's `eval` (splatting divides by the sum of weights, which cancels any scale).
    #[inline(always)]
    pub fn profile(&self, x: f64) -> f64 {
        let r = self.radius() as f64;
        match self {
            PixelFilter::Pixel | PixelFilter::Box { .. } => f64::from(u8::from(x.abs() <= r)),
            PixelFilter::Tent { .. } => (1.0 - x.abs() / r).max(0.0),
            PixelFilter::Gaussian(g) => g.eval(x),
        }
    }

    /// The first pixel (one axis) whose centre, at index + ½, a sample at film coordinate `p`
    /// can give a non-zero weight; the others follow, [`PixelFilter::support_len`] in all.
    /// The tent's and the gaussian's f₁ are zero at ±r (support open: centres strictly
    /// within r of `p`), the box's is one there (closed). `p` and r are exact in f64, so is the
    /// comparison.
    #[inline(always)]
    pub fn support_start(&self, p: f64) -> i64 {
        let a = p - 0.5 - self.radius() as f64;
        // |a| is far below 2⁵¹ (film coordinates and radii are), so the conversion is exact.
        match self {
            PixelFilter::Pixel | PixelFilter::Box { .. } => integral_to_i64(a.ceil()),
            PixelFilter::Tent { .. } | PixelFilter::Gaussian(_) => integral_to_i64(a.floor()) + 1,
        }
    }

    /// How many pixels from [`PixelFilter::support_start`] a sample may reach, the same for
    /// every position: ⌈2r⌉ integers lie in an open interval of length 2r, at most ⌊2r⌋ + 1 in
    /// a closed one. (Splats loop over a fixed count, which branch predictors learn; a tent of
    /// radius 1 reaches 3 × 3 centres around its pixel but weights 2 × 2 of them.)
    pub fn support_len(&self) -> usize {
        let two_r = 2.0 * self.radius() as f64;
        match self {
            PixelFilter::Pixel | PixelFilter::Box { .. } => two_r.floor() as usize + 1,
            PixelFilter::Tent { .. } | PixelFilter::Gaussian(_) => two_r.ceil() as usize,
        }
    }

    /// f₁ at the offsets `x0`, `x0 + 1`, … of a row of pixel centres, into `out`: what a splat
    /// needs per axis. The gaussian's row costs two exponentials instead of one per pixel
    /// ([`GaussianFilter::eval_row`]); the others are [`PixelFilter::profile`] at each offset.
    #[inline(always)]
    pub fn profile_row(&self, x0: f64, out: &mut [f64]) {
        match self {
            PixelFilter::Gaussian(g) => g.eval_row(x0, out),
            _ => {
                for (i, w) in out.iter_mut().enumerate() {
                    *w = self.profile(x0 + i as f64);
                }
            }
        }
    }

    /// [`PixelFilter::profile_row`] for a splat's two axes at once: the gaussian's four
    /// exponentials in one vector ([`GaussianFilter::eval_rows`]).
    #[inline(always)]
    pub fn profile_rows(&self, x0: f64, y0: f64, wx: &mut [f64], wy: &mut [f64]) {
        match self {
            PixelFilter::Gaussian(g) => g.eval_rows(x0, y0, wx, wy),
            _ => {
                self.profile_row(x0, wx);
                self.profile_row(y0, wy);
            }
        }
    }
}

/// Mitsuba 3's windowed gaussian.
#[derive(Clone, Debug, PartialEq)]
pub struct GaussianFilter {
    stddev: f32,
    /// −1/2σ² and exp(−r²/2σ²), the constants of f₁.
    alpha: f64,
    cutoff: f64,
    /// exp(2α), the step of [`GaussianFilter::eval_row`]'s ratios.
    ratio_step: f64,
}

impl GaussianFilter {
    /// `stddev` in pixels; must be positive, its radius (4σ) at most [`PixelFilter::MAX_RADIUS`].
    pub fn new(stddev: f32) -> Result<Self, String> {
        let widest = PixelFilter::MAX_RADIUS / 4.0;
        if !(stddev > 0.0 && stddev <= widest) {
            return Err(format!("gaussian stddev {stddev} must be a positive number of pixels, at most {widest}"));
        }
        let r = 4.0 * stddev as f64;
        let alpha = -1.0 / (2.0 * stddev as f64 * stddev as f64);
        Ok(Self { stddev, alpha, cutoff: (alpha * r * r).exp(), ratio_step: (2.0 * alpha).exp() })
    }

    pub fn stddev(&self) -> f32 {
        self.stddev
    }

    /// Mitsuba cuts the gaussian off at four standard deviations.
    pub fn radius(&self) -> f32 {
        4.0 * self.stddev
    }

    /// f₁(x) = max(0, exp(−x²/2σ²) − exp(−r²/2σ²)), unnormalised as in Mitsuba.
    #[inline(always)]
    pub fn eval(&self, x: f64) -> f64 {
        ((self.alpha * x * x).exp() - self.cutoff).max(0.0)
    }

    /// f₁ at `x0 + i` for each `out[i]`, the exponentials by recurrence: with g(x) = exp(αx²),
    /// g(x + 1) = g(x) · exp(α(2x + 1)), and that ratio itself grows by exp(2α) per step, so a row
    /// takes two `exp` calls (g(x0) and the first ratio) and two products per further pixel. Each
    /// product rounds once: after the few steps of a splat (2⌈r − ½⌉ + 1 values) the result is
    /// within a few ulps of [`GaussianFilter::eval`]'s, and still a pure function of `x0`. The
    /// ratios stay finite: the first is at most exp(2|α|(⌈r − ½⌉)) ≤ e³² for any σ whose row has
    /// more than one value.
    #[inline(always)]
    pub fn eval_row(&self, x0: f64, out: &mut [f64]) {
        let [g, ratio, _, _] = exp_f64_lanes([self.alpha * x0 * x0, self.alpha * (2.0 * x0 + 1.0), 0.0, 0.0]);
        self.row_from(g, ratio, out);
    }

    /// [`GaussianFilter::eval_row`] at `x0` into `wx` and at `y0` into `wy`, the four
    /// exponentials computed together.
    #[inline(always)]
    pub fn eval_rows(&self, x0: f64, y0: f64, wx: &mut [f64], wy: &mut [f64]) {
        let a = self.alpha;
        let [gx, rx, gy, ry] = exp_f64_lanes([a * x0 * x0, a * (2.0 * x0 + 1.0), a * y0 * y0, a * (2.0 * y0 + 1.0)]);
        self.row_from(gx, rx, wx);
        self.row_from(gy, ry, wy);
    }

    /// The row's values from g(x0) and the first ratio, by the recurrence above.
    #[inline(always)]
    fn row_from(&self, mut g: f64, mut ratio: f64, out: &mut [f64]) {
        for (i, w) in out.iter_mut().enumerate() {
            if i > 0 {
                g *= ratio;
                ratio *= self.ratio_step;
            }
            *w = (g - self.cutoff).max(0.0);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A splat's row of f₁ values equals f₁ at each offset: to a few ulps for the gaussian's
    /// recurrence (every σ from narrow to wide, offsets across a pixel), exactly for the others.
    #[test]
    fn profile_rows_are_the_profile_at_each_offset() {
        for sigma in [0.13f32, 0.3, 0.5, 1.0, 2.5, 4.0] {
            let f = PixelFilter::Gaussian(GaussianFilter::new(sigma).unwrap());
            let n = 2 * (f.radius() as f64 - 0.5).ceil().max(0.0) as usize + 1;
            for k in 0..=64 {
                let x0 = -((n / 2) as f64) - 0.5 + k as f64 / 64.0;
                let mut row = vec![0.0; n];
                f.profile_row(x0, &mut row);
                for (i, &w) in row.iter().enumerate() {
                    let exact = f.profile(x0 + i as f64);
                    assert!((w - exact).abs() <= 1e-14, "σ {sigma}, x0 {x0}, i {i}: {w} vs {exact}");
                }
            }
        }
        for f in [PixelFilter::Tent { radius: 1.5 }, PixelFilter::Box { radius: 1.0 }] {
            let mut row = [0.0; 5];
            f.profile_row(-2.3, &mut row);
            assert_eq!(row, std::array::from_fn(|i| f.profile(-2.3 + i as f64)));
        }
    }

    /// Outside its support window a splat's row of f₁ holds only zeros (the gaussian's
    /// recurrence may leave values of a few ulps of its cut-off there, far below the film's
    /// fixed-point grid), and the window lies within the row: for positions across a pixel,
    /// its edges and the exact halves included, for narrow and wide filters of each kind.
    #[test]
    fn splat_rows_are_zero_outside_the_support_window() {
        let mut filters = vec![
            PixelFilter::Tent { radius: 1.0 },
            PixelFilter::Tent { radius: 0.75 },
            PixelFilter::Tent { radius: 1.5 },
            PixelFilter::Tent { radius: 2.3 },
            PixelFilter::Box { radius: 0.75 },
            PixelFilter::Box { radius: 1.0 },
            PixelFilter::Box { radius: 1.6 },
        ];
        for sigma in [0.13f32, 0.3, 0.375, 0.5, 1.0, 2.5] {
            filters.push(PixelFilter::Gaussian(GaussianFilter::new(sigma).unwrap()));
        }
        let mut fracs: Vec<f64> = (0..=512).map(|k| k as f64 / 512.0).filter(|&f| f < 1.0).collect();
        fracs.extend([1e-30, 0.5 - 1e-7, 0.5 + 6e-8, 1.0 - 6e-8].map(|f: f64| f as f32 as f64));
        for f in &filters {
            let m = (f.radius() as f64 - 0.5).ceil().max(0.0) as i64;
            let n = 2 * m as usize + 1;
            let len = f.support_len() as i64;
            assert!(len <= n as i64, "{f:?}: window {len} wider than the row {n}");
            for x in [0.0, 7.0, 1023.0] {
                for &frac in &fracs {
                    let p = x + frac;
                    let fx = p.floor() as i64 - m;
                    let mut row = vec![0.0; n];
                    f.profile_row(fx as f64 + 0.5 - p, &mut row);
                    let s = f.support_start(p) - fx;
                    for (i, &w) in row.iter().enumerate() {
                        let inside = (s..s + len).contains(&(i as i64));
                        let limit = if matches!(f, PixelFilter::Gaussian(_)) { 1e-18 } else { 0.0 };
                        assert!(inside || w <= limit, "{f:?} at {p}: weight {w} at {i} outside {s}..{}", s + len);
                        // Inside, only centres at the support's edge may be zero.
                        if inside && (0..n as i64).contains(&(i as i64)) && w == 0.0 {
                            let d = (fx + i as i64) as f64 + 0.5 - p;
                            assert!(d.abs() >= f.radius() as f64 * (1.0 - 1e-6), "{f:?} at {p}: zero at {d} inside");
                        }
                    }
                }
            }
        }
    }

    /// The lanes' film positions are each lane's [`PixelFilter::sample`], bit for bit.
    #[test]
    fn lanes_sample_the_filter_as_one_point_does() {
        let us: [f32; 8] = [0.0, 1e-8, 0.25, 0.3, 0.5, 0.7, 0.999_999_9, 0.123_456_7];
        let u = [F32s(us), F32s(std::array::from_fn(|i| us[7 - i]))];
        let filters = [
            PixelFilter::Pixel,
            PixelFilter::Box { radius: 0.3 },
            PixelFilter::Box { radius: 1.0 },
            PixelFilter::Tent { radius: 1.5 },
            PixelFilter::Gaussian(GaussianFilter::new(0.5).unwrap()),
        ];
        for f in filters {
            let lanes = f.sample_lanes(u);
            for i in 0..8 {
                let one = f.sample(Vec2::new(u[0].0[i], u[1].0[i]));
                assert_eq!(
                    (lanes[0].0[i].to_bits(), lanes[1].0[i].to_bits()),
                    (one.x.to_bits(), one.y.to_bits()),
                    "{f:?}"
                );
            }
        }
    }

    #[test]
    fn the_default_box_is_the_plain_jitter_and_wide_filters_sample_the_pixel() {
        let u = Vec2::new(1e-8, 0.999_999_9);
        assert_eq!(PixelFilter::default().sample(u), u);
        assert_eq!(PixelFilter::by_name("box").unwrap(), PixelFilter::Pixel);
        assert!(!PixelFilter::Pixel.splats());
        for f in ["tent", "gaussian"] {
            let f = PixelFilter::by_name(f).unwrap();
            assert!(f.splats());
            assert_eq!(f.sample(u), u);
        }
        let narrow = PixelFilter::Box { radius: 0.25 };
        assert!(!narrow.splats());
        assert_eq!(narrow.sample(Vec2::new(0.0, 1.0)), Vec2::new(0.25, 0.75));
        assert!(PixelFilter::Box { radius: 1.0 }.splats());
    }

    #[test]
    fn profiles_are_mitsubas() {
        let g = PixelFilter::by_name("gaussian").unwrap();
        let cut = (-8.0f64).exp();
        assert!((g.profile(0.0) - (1.0 - cut)).abs() < 1e-15);
        assert!((g.profile(0.5) - ((-0.5f64).exp() - cut)).abs() < 1e-15);
        assert_eq!(g.profile(2.0), 0.0);
        assert_eq!(g.profile(-2.5), 0.0);
        let t = PixelFilter::Tent { radius: 2.0 };
        assert_eq!((t.profile(0.0), t.profile(-1.0), t.profile(2.5)), (1.0, 0.5, 0.0));
        let b = PixelFilter::Box { radius: 1.5 };
        assert_eq!((b.profile(1.5), b.profile(-1.51)), (1.0, 0.0));
        assert!(GaussianFilter::new(0.0).is_err());
        assert!(GaussianFilter::new(f32::NAN).is_err());
    }

    /// Radii are positive and at most `MAX_RADIUS` (a huge one would allocate its splat row of
    /// weights before failing); the bound itself is accepted, for every kind.
    #[test]
    fn radii_are_bounded() {
        for name in ["box", "tent"] {
            for bad in [0.0, -1.0, f32::NAN, f32::INFINITY, 1e9, PixelFilter::MAX_RADIUS * 1.001] {
                let e = PixelFilter::with_radius(name, bad).unwrap_err();
                assert!(e.contains("at most 40000"), "{e}");
            }
            assert_eq!(
                PixelFilter::with_radius(name, PixelFilter::MAX_RADIUS).unwrap().radius(),
                PixelFilter::MAX_RADIUS
            );
        }
        assert!(GaussianFilter::new(1e6).unwrap_err().contains("at most 10000"));
        assert_eq!(GaussianFilter::new(1e4).unwrap().radius(), PixelFilter::MAX_RADIUS);
    }
}
