//! Per-pixel accumulation in exact fixed point: the sample count, and per channel the sum of the
//! samples and the sum of their squares, each sample truncated once to a multiple of 2⁻⁴⁰.
//!
//! **Why integers.** A floating-point running mean (Welford) merged by Chan's formula depends on
//! the order samples arrive in: the SIMD lane count, the wave boundaries and the machine a part
//! of the render ran on all change the last bits. Rounding each sample to a fixed grid is a pure
//! function of the sample, and integer addition is associative and commutative, so any split of
//! a pixel's samples, merged in any order, on any thread or lane count, gives the same bits —
//! what rendering one image across several machines needs (docs/distributed.md).
//!
//! **Range.** Sums are `i128`, squares `u128`, with [`FRACTION_BITS`] = 40 fractional bits
//! (quantum 2⁻⁴⁰ ≈ 9.1·10⁻¹³, far below an f32's resolution of any visible radiance):
//! - a sample's magnitude is clamped to [`SAMPLE_LIMIT`] = 2⁵² ≈ 4.5·10¹⁵ (a radiance no scene
//!   of ours comes near: a firefly that large would ruin the image anyway); then |sum| ≤ 2³² samples · 2⁵²⁺⁴⁰ = 2¹²⁴ < 2¹²⁷, so a sum
//!   cannot overflow for any `u32` sample count;
//! - a square is truncated to the same grid and the sum of squares saturates at `u128::MAX`
//!   (Σx² ≈ 3.1·10²⁶). Saturating addition of non-negative integers is still order-free
//!   (it is min(true sum, MAX)); a saturated pixel reports an infinite variance, never a wrong
//!   finite one.
//!
//! Values below 2⁻⁴⁰ ≈ 9.1·10⁻¹³ truncate to zero, and squares below that (|x| < 9.5·10⁻⁷) do too, so
//! the variance of pixels darker than about 10⁻⁶ is not resolved (they are far below what any
//! image format displays).

use crate::math::Rgb;

/// Fractional bits of the fixed-point sums (and of the sums of squares).
pub const FRACTION_BITS: i32 = 40;

/// Largest sample magnitude kept as is; larger ones are clamped to it (see the module docs).
pub const SAMPLE_LIMIT: f64 = (1u64 << 52) as f64;

/// 2^FRACTION_BITS, the fixed-point scale.
pub(super) const SCALE: f64 = (1u64 << FRACTION_BITS) as f64;

/// The statistics of one pixel's samples.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct PixelStats {
    pub count: u32,
    /// Σ trunc(x · 2⁴⁰) per channel.
    pub sum: [i128; 3],
    /// Σ trunc(x² · 2⁴⁰) per channel, saturating.
    pub sum_sq: [u128; 3],
}

/// `x · 2⁴⁰` truncated toward zero to an integer, `x` already clamped. Truncation is as pure a
/// function of the sample as rounding (which is all exactness needs) and is one instruction: an
/// f32 of magnitude ≥ 2⁻¹⁷ times 2⁴⁰ is an integer already, and below that the error is under
/// 2⁻⁴⁰. Most values fit an `i64`, whose conversion is one instruction; the `i128` one is a
/// library call.
#[inline(always)]
fn to_fixed(x: f64) -> i128 {
    let scaled = x * SCALE;
    if scaled.abs() < 9.0e18 {
        scaled as i64 as i128
    } else {
        scaled as i128
    }
}

/// A value on the fixed-point grid: clamped to ±[`SAMPLE_LIMIT`], then `x · 2⁴⁰` truncated. The
/// one conversion every exact sum uses (the film's radiance here, the feature buffers in
/// `features.rs`). NaN converts to 0 (`as` does), so even it is a pure function of the value.
#[inline(always)]
pub(super) fn fixed(x: f64) -> i128 {
    to_fixed(x.clamp(-SAMPLE_LIMIT, SAMPLE_LIMIT))
}

/// [`fixed`] of a value below [`EXACT_SMALL`] = 2¹¹ in magnitude, as an `i64` (the same
/// integer: no clamp applies, and truncation toward zero is what `to_fixed`'s conversion does).
///
/// Written without an `as` conversion so that it vectorises and has no branches: Rust's
/// saturating `f64 as i64` compiles to one scalar conversion per value with NaN and range
/// fix-ups, while an integer below 2⁵¹ in magnitude plus 1.5·2⁵² is exact and its bits are
/// 1.5·2⁵²'s plus the integer (the usual floating-point conversion trick, as in Hacker's
/// Delight); `trunc` and the add are packed instructions.
#[inline(always)]
pub(super) fn fixed_small(x: f64) -> i64 {
    integral_to_i64((x * SCALE).trunc())
}

/// An integral `f64` below 2⁵¹ in magnitude as an `i64`: the same integer as `t as i64`, by
/// the bits of `t + 1.5·2⁵²` (exact for such `t`), without the saturating conversion's scalar
/// range and NaN fix-ups, so it vectorises (see [`fixed_small`]).
#[inline(always)]
pub(super) fn integral_to_i64(t: f64) -> i64 {
    const MAGIC: f64 = (3u64 << 51) as f64;
    (t + MAGIC).to_bits() as i64 - MAGIC.to_bits() as i64
}

/// Magnitude below which [`fixed_small`] is exact: 2¹¹, a grid value below 2⁵¹.
pub(super) const EXACT_SMALL: f64 = 2048.0;

/// Terms below this magnitude (2⁶, so below 2⁴⁶ on the grid) may be summed in `i64`: up to 2¹⁶
/// of them stay below 2⁶³ (the splat's partial sums, `splat.rs`).
pub(super) const SMALL_LIMIT: f64 = 64.0;

/// Samples below this magnitude in every channel (their squares below 2¹⁰) take
/// [`small_terms`] for the value and its square in [`PixelStats::add`].
pub(crate) const SMALL_SAMPLE: f32 = 32.0;

// Every value the fast paths convert is within `fixed_small`'s exact range.
const _: () = assert!(SMALL_LIMIT < EXACT_SMALL && ((SMALL_SAMPLE * SMALL_SAMPLE) as f64) < EXACT_SMALL);
// 64 small samples' terms (each below 2¹⁰ · 2⁴⁰ = 2⁵⁰) sum without overflow in an `i64`, as
// [`PixelStats::add_small_terms`] lets lane groups of up to 64 do.
const _: () = assert!((SMALL_SAMPLE * SMALL_SAMPLE) as f64 * SCALE * 64.0 < 9.2e18);

/// A small sample's fixed-point value and square in one channel (`x` below [`SMALL_SAMPLE`] in
/// magnitude): what [`PixelStats::add`] adds for it. Branch-free, so lane groups convert
/// their estimates in SIMD.
#[inline(always)]
pub(crate) fn small_terms(x: f64) -> (i64, i64) {
    (fixed_small(x), fixed_small(x * x))
}

/// The mean of `count` values (1 if there are none) whose fixed-point sum is `sum`.
#[inline]
pub(super) fn fixed_mean(sum: i128, count: u32) -> f64 {
    sum_to_f64(sum) / SCALE / count.max(1) as f64
}

/// `x as f64` for a fixed-point sum. Both conversions round the exact integer to the nearest
/// f64 (ties to even), so going through `i64` when the value fits gives the same bits, in one
/// instruction where the `i128` conversion is a library call (`__floattidf`, about 40
/// instructions). With nine of those a pixel, the error estimate's pass over the film cost
/// about 340 instructions per pixel: a fifth of a fast 256² render's instructions.
#[inline(always)]
pub(super) fn sum_to_f64(x: i128) -> f64 {
    match i64::try_from(x) {
        Ok(v) => v as f64,
        Err(_) => wide_to_f64(x),
    }
}

/// [`sum_to_f64`] for a sum of squares (`u128`, whose library conversion is `__floatuntidf`).
#[inline(always)]
fn square_sum_to_f64(x: u128) -> f64 {
    match i64::try_from(x) {
        Ok(v) => v as f64,
        Err(_) => wide_unsigned_to_f64(x),
    }
}

/// The library conversions, out of line and cold. Written in the `match` arms, LLVM judged the
/// conversion cheap enough to compute for every value and pick afterwards (a select, not a
/// branch), so each call was still made.
#[cold]
#[inline(never)]
fn wide_to_f64(x: i128) -> f64 {
    x as f64
}

/// [`wide_to_f64`] for `u128`.
#[cold]
#[inline(never)]
fn wide_unsigned_to_f64(x: u128) -> f64 {
    x as f64
}

/// `x² · 2⁴⁰` truncated, saturating at `u128::MAX` (`as` saturates). x² of an f32 is exact in f64.
#[inline(always)]
fn square_to_fixed(x: f64) -> u128 {
    let scaled = x * x * SCALE;
    if scaled < 1.8e19 {
        scaled as u64 as u128
    } else {
        scaled as u128
    }
}

impl PixelStats {
    /// Adds a black sample (a camera ray that left an unlit scene, a path that found no light;
    /// 81% of teapot-simple's samples): it adds zero to every sum, so only the count changes.
    /// [`PixelStats::add`] of [`Rgb::BLACK`] (or of −0).
    #[inline(always)]
    pub fn add_black(&mut self) {
        self.add_blacks(1);
    }

    /// Adds `count` black samples.
    #[inline(always)]
    pub fn add_blacks(&mut self, count: u32) {
        self.count += count;
    }

    /// Adds `count` samples below [`SMALL_SAMPLE`] in every channel whose [`small_terms`] sum
    /// to `sum` and `sum_sq` per channel. The same integers as adding each sample: integer
    /// addition, and a saturating sum of non-negative terms is min(total, MAX) however it is
    /// grouped.
    #[inline(always)]
    pub(crate) fn add_small_terms(&mut self, count: u32, sum: [i64; 3], sum_sq: [i64; 3]) {
        self.count += count;
        for k in 0..3 {
            self.sum[k] += i128::from(sum[k]);
            self.sum_sq[k] = self.sum_sq[k].saturating_add(sum_sq[k] as u128);
        }
    }

    /// Adds one finite sample (channels beyond ±[`SAMPLE_LIMIT`] are clamped to it).
    // Always inlined: called from the render loop's AVX2/AVX-512 code, where the f64 → u64
    // conversion of the square is one instruction (out of line, compiled for the baseline
    // x86-64, it is a branchy sequence, and the call itself showed as 12% of the teapot's time).
    #[inline(always)]
    pub fn add(&mut self, c: Rgb) {
        if c == Rgb::BLACK {
            self.add_black();
            return;
        }
        // Nearly every sample: branch-free conversions, the same integers (NaN fails the test).
        if c.to_array().iter().all(|v| v.abs() < SMALL_SAMPLE) {
            let terms = c.to_array().map(|v| small_terms(f64::from(v)));
            self.add_small_terms(1, terms.map(|t| t.0), terms.map(|t| t.1));
            return;
        }
        self.count += 1;
        for (k, x) in c.to_array().into_iter().enumerate() {
            // f32 → f64 is exact, so is the scaling by a power of two; x² of an f32 fits f64's
            // 53 bits exactly: the only rounding is the truncation to the grid.
            let x = x as f64;
            self.sum[k] += fixed(x);
            let kept = x.clamp(-SAMPLE_LIMIT, SAMPLE_LIMIT);
            self.sum_sq[k] = self.sum_sq[k].saturating_add(square_to_fixed(kept));
        }
    }

    /// Combines two sets of samples: integer addition, so the result is the same whatever the
    /// grouping or order of the merges.
    #[inline]
    pub fn merge(&mut self, o: &PixelStats) {
        self.count += o.count;
        for k in 0..3 {
            self.sum[k] += o.sum[k];
            self.sum_sq[k] = self.sum_sq[k].saturating_add(o.sum_sq[k]);
        }
    }

    /// The mean per channel (zero without samples).
    #[inline]
    pub fn mean(&self) -> [f64; 3] {
        self.sum.map(|s| fixed_mean(s, self.count))
    }

    pub fn mean_rgb(&self) -> Rgb {
        let m = self.mean();
        Rgb::new(m[0] as f32, m[1] as f32, m[2] as f32)
    }

    /// Unbiased sample variance per channel, (Σx² − n·mean²) / (n − 1) (zero with fewer than
    /// two samples, infinite when the sum of squares saturated).
    pub fn sample_variance(&self) -> [f64; 3] {
        self.sample_variance_about(&self.mean())
    }

    /// [`PixelStats::sample_variance`] given the pixel's [`PixelStats::mean`], for callers that
    /// need both (the mean is three wide-integer conversions and six divisions).
    #[inline]
    pub(super) fn sample_variance_about(&self, mean: &[f64; 3]) -> [f64; 3] {
        if self.count < 2 {
            return [0.0; 3];
        }
        let n = self.count as f64;
        std::array::from_fn(|k| {
            if self.sum_sq[k] == u128::MAX {
                return f64::INFINITY;
            }
            let mean_sq = square_sum_to_f64(self.sum_sq[k]) / SCALE / n;
            // The difference of two rounded means can dip below zero for (near-)constant pixels.
            ((mean_sq - mean[k] * mean[k]) * (n / (n - 1.0))).max(0.0)
        })
    }

    /// Estimated variance of the pixel's mean, per channel: s² / n.
    pub fn variance_of_mean(&self) -> [f64; 3] {
        let n = self.count.max(1) as f64;
        self.sample_variance().map(|v| v / n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The vectorisable conversion gives `fixed`'s integers for every value it is used for.
    #[test]
    fn small_values_convert_as_the_exact_path_does() {
        let mut rng = crate::sampling::Pcg32::new(5, 9);
        let mut values = vec![0.0, -0.0, 1e-13, -1e-13, 9.1e-13, 63.999_999, -63.999_999, 1.0, -1.0];
        for _ in 0..200_000 {
            let m = rng.next_f32() as f64 * 2.0 - 1.0;
            let e = (rng.next_f32() * 56.0) as i32 - 44;
            values.push(m * 2f64.powi(e).min(EXACT_SMALL));
        }
        values.extend([2_047.999_999, -2_047.999_999, 1e3 + 1e-9]);
        for x in values.into_iter().filter(|x: &f64| x.abs() < EXACT_SMALL) {
            assert_eq!(i128::from(fixed_small(x)), fixed(x), "{x:e}");
            // Squares of samples below SMALL_SAMPLE, as `PixelStats::add` takes them.
            let y = (x / 64.0) * (x / 64.0);
            assert_eq!(fixed_small(y) as u128, square_to_fixed(x / 64.0), "{x:e}");
        }
    }

    /// The conversions through `i64` are the `as` conversions, bit for bit, on and around the
    /// range limits and for values too long for an f64's 53 bits (where rounding matters).
    #[test]
    fn sum_conversions_are_the_as_conversions() {
        let mut rng = crate::sampling::Pcg32::new(7, 3);
        let mut signed: Vec<i128> = vec![0, 1, -1, i64::MAX as i128, i64::MIN as i128, i64::MAX as i128 + 1];
        signed.extend([i64::MIN as i128 - 1, i128::MAX, i128::MIN, (1 << 53) + 1, -(1 << 53) - 3, (1 << 62) + 513]);
        for _ in 0..100_000 {
            let bits = rng.next_u32() % 127;
            let magnitude = ((rng.next_u32() as u128) << 96
                | (rng.next_u32() as u128) << 64
                | (rng.next_u32() as u128) << 32
                | rng.next_u32() as u128)
                >> (127 - bits);
            let m = magnitude as i128;
            signed.push(if rng.next_u32().is_multiple_of(2) { m } else { -m });
        }
        for &x in &signed {
            assert_eq!(sum_to_f64(x).to_bits(), (x as f64).to_bits(), "{x}");
            let u = x.unsigned_abs();
            assert_eq!(square_sum_to_f64(u).to_bits(), (u as f64).to_bits(), "{u}");
        }
        assert_eq!(square_sum_to_f64(u128::MAX).to_bits(), (u128::MAX as f64).to_bits());
    }

    #[test]
    fn black_samples_count_and_add_nothing() {
        let mut p = PixelStats::default();
        p.add(Rgb::new(0.5, -2.0, 3.0));
        let before = p;
        for black in [Rgb::BLACK, Rgb::new(-0.0, 0.0, -0.0)] {
            p.add(black);
        }
        assert_eq!(p.count, before.count + 2);
        assert_eq!((p.sum, p.sum_sq), (before.sum, before.sum_sq));
        // The conversions themselves give zero for ±0: skipping them changes no sum.
        assert_eq!((fixed(-0.0), fixed_small(-0.0), square_to_fixed(-0.0)), (0, 0, 0));
    }

    #[test]
    fn mean_and_variance_match_the_two_pass_formulas() {
        let xs: Vec<f32> = (0..50).map(|i| ((i * 37) % 11) as f32 * 0.3 + 1.0).collect();
        let mut all = PixelStats::default();
        let (mut a, mut b) = (PixelStats::default(), PixelStats::default());
        for (i, &x) in xs.iter().enumerate() {
            all.add(Rgb::splat(x));
            if i < 17 {
                a.add(Rgb::splat(x));
            } else {
                b.add(Rgb::splat(x));
            }
        }
        b.merge(&a);
        assert_eq!(all, b, "a merge is the same integers as adding one by one");
        let n = xs.len() as f64;
        let mean = xs.iter().map(|&x| x as f64).sum::<f64>() / n;
        let var = xs.iter().map(|&x| (x as f64 - mean).powi(2)).sum::<f64>() / (n - 1.0);
        assert_eq!(all.count, 50);
        assert!((all.mean()[0] - mean).abs() < 1e-12);
        assert!((all.sample_variance()[1] - var).abs() < 1e-9);
    }

    #[test]
    fn any_grouping_of_wildly_scaled_samples_gives_the_same_bits() {
        // Fireflies, tiny values and negatives (filter weights can be): floats would round
        // differently in each order; the fixed-point sums may not.
        let xs = [1e-9f32, 3.0e7, -2.5, 1e-3, 0.7, 6.0e12, 1e-12, 42.0, -1e-6, 0.1];
        let one_by_one = xs.iter().fold(PixelStats::default(), |mut p, &x| {
            p.add(Rgb::new(x, x * 0.5, -x));
            p
        });
        for split in 1..xs.len() {
            let mut parts = [PixelStats::default(); 2];
            for (i, &x) in xs.iter().enumerate().rev() {
                parts[usize::from(i >= split)].add(Rgb::new(x, x * 0.5, -x));
            }
            let (mut ab, mut ba) = (parts[0], parts[1]);
            ab.merge(&parts[1]);
            ba.merge(&parts[0]);
            assert_eq!(ab, one_by_one);
            assert_eq!(ba, one_by_one);
        }
    }

    #[test]
    fn constant_samples_have_zero_variance_and_an_exact_mean() {
        let mut p = PixelStats::default();
        for _ in 0..1000 {
            p.add(Rgb::new(15.0, 0.1, 0.0));
        }
        assert_eq!(p.mean()[0], 15.0);
        assert!((p.mean()[1] - 0.1f32 as f64).abs() < 1e-12);
        assert_eq!(p.sample_variance()[0], 0.0);
        assert!(p.sample_variance()[1] < 1e-12);
    }

    #[test]
    fn huge_samples_are_clamped_and_saturated_squares_report_infinite_variance() {
        let mut p = PixelStats::default();
        p.add(Rgb::splat(1.0));
        p.add(Rgb::new(1e30, 1.0, 1.0));
        assert_eq!(p.mean()[0], (SAMPLE_LIMIT + 1.0) / 2.0);
        assert_eq!(p.sample_variance()[0], f64::INFINITY);
        assert!(p.sample_variance()[1] == 0.0);
        // 2³² samples at the limit still fit the sum: check the bound the docs claim.
        let bound = (SAMPLE_LIMIT * SCALE) as i128 * (u32::MAX as i128);
        assert!(bound < i128::MAX);
    }
}
