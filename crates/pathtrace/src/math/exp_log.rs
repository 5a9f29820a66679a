//! eˣ and ln x in single precision, written lane by lane without branches so that a loop over
//! SIMD lanes compiles to vector instructions (libm's `expf` and `logf` are calls, one lane at a
//! time: the Beckmann microfacet model's exponentials and the visible-slope inversion's
//! logarithms were most of its cost). The scalar callers use the one-lane instance, so every
//! kernel gets the same bits.
//!
//! Both follow Cephes' `expf.c` and `logf.c` (S. L. Moshier, Cephes Math Library 2.2): a range
//! reduction to a small interval, a minimax polynomial there, and an exact scaling by a power of
//! two. Relative error about 1.5 ulp (measured against f64 in the tests below).

use crate::wide::simd::F32s;

/// ln 2 split in two (Cephes' C1 + C2): `n·LN2_HI` is exact for the |n| ≤ 128 used here, so the
/// reduced argument x − n ln 2 keeps its low bits.
const LN2_HI: f32 = 0.693_359_4;
const LN2_LO: f32 = -2.121_944_4e-4;

/// Below this eˣ (e^−86.9 ≈ 1.8·10⁻³⁸, near the smallest normal f32) is answered 0: the
/// callers are Gaussian tails, where values this small and 0 weigh the same.
const EXP_UNDERFLOW: f32 = -86.9;
/// Above this eˣ is answered +∞ (e^88.72 is within 0.3% of the largest f32).
const EXP_OVERFLOW: f32 = 88.72;

/// 1.5·2²³: adding it to |y| < 2²² rounds y to an integer (round to nearest even).
const ROUND_MAGIC: f32 = 12_582_912.0;

/// eˣ per lane; 0 below [`EXP_UNDERFLOW`], +∞ above [`EXP_OVERFLOW`], NaN for NaN.
#[inline(always)]
pub fn exp_lanes<const N: usize>(x: F32s<N>) -> F32s<N> {
    x.map_lanes(exp_lane)
}

/// ln x per lane for x > 0 (normal numbers); −∞ at 0, NaN below 0 or for NaN, +∞ at +∞.
/// Subnormal x are taken as 0.
#[inline(always)]
pub fn ln_lanes<const N: usize>(x: F32s<N>) -> F32s<N> {
    x.map_lanes(ln_lane)
}

#[inline(always)]
fn exp_lane(x: f32) -> f32 {
    // x = n ln2 + r with |r| ≤ ln2/2; the argument is clamped so that n stays in [−125, 128].
    let xc = x.clamp(EXP_UNDERFLOW, EXP_OVERFLOW);
    let n = (xc * std::f32::consts::LOG2_E + ROUND_MAGIC) - ROUND_MAGIC;
    let r = xc - n * LN2_HI - n * LN2_LO;
    // eʳ ≈ 1 + r + r²·P(r) (Cephes expf's coefficients).
    let p = 1.987_569_1e-4;
    let p = p * r + 1.398_199_9e-3;
    let p = p * r + 8.333_452e-3;
    let p = p * r + 4.166_579_6e-2;
    let p = p * r + 0.166_666_65;
    let p = p * r + 0.5;
    let er = p * (r * r) + r + 1.0;
    // 2ⁿ as 2ⁿ⁻¹·2, so that n = 128 (eˣ just below the overflow) still has an exponent field.
    let half_scale = f32::from_bits((((n as i32) + 126) as u32) << 23);
    let value = er * half_scale * 2.0;
    // The comparisons are false for NaN, which then flows through the polynomial.
    if x < EXP_UNDERFLOW {
        0.0
    } else if x > EXP_OVERFLOW {
        f32::INFINITY
    } else {
        value
    }
}

#[inline(always)]
fn ln_lane(x: f32) -> f32 {
    // x = m·2ᵉ with m ∈ [√½, √2), then ln x = ln m + e ln2 with ln(1 + f), f = m − 1, from
    // Cephes logf's polynomial.
    let bits = x.to_bits();
    let exponent = ((bits >> 23) & 0xff) as i32 - 126;
    let mantissa = f32::from_bits((bits & 0x007f_ffff) | 0x3f00_0000); // in [0.5, 1)
    let small = mantissa < std::f32::consts::FRAC_1_SQRT_2;
    let e = (exponent - i32::from(small)) as f32;
    let f = if small { mantissa + mantissa - 1.0 } else { mantissa - 1.0 };
    let z = f * f;
    let p = 7.037_683_6e-2;
    let p = p * f - 1.151_461_e-1;
    let p = p * f + 1.167_699_9e-1;
    let p = p * f - 1.242_014_1e-1;
    let p = p * f + 1.424_932_3e-1;
    let p = p * f - 1.666_805_8e-1;
    let p = p * f + 2.000_071_4e-1;
    let p = p * f - 2.499_999_4e-1;
    let p = p * f + 3.333_333e-1;
    let y = p * f * z + e * LN2_LO - 0.5 * z;
    let value = f + y + e * LN2_HI;
    if x.is_nan() || x < 0.0 {
        f32::NAN
    } else if x < f32::MIN_POSITIVE {
        f32::NEG_INFINITY
    } else if x == f32::INFINITY {
        f32::INFINITY
    } else {
        value
    }
}

/// ln 2 split in two for f64 (Cephes exp.c's C1 + C2): `n·EXP64_LN2_HI` is exact for the
/// |n| ≤ 1100 the clamp allows.
const EXP64_LN2_HI: f64 = 6.931_457_519_531_25e-1;
const EXP64_LN2_LO: f64 = 1.428_606_820_309_417_3e-6;
/// 1.5·2⁵²: adding it to |y| < 2⁵¹ rounds y to an integer (round to nearest even).
const ROUND_MAGIC_F64: f64 = 6_755_399_441_055_744.0;

/// eˣ in double precision for each of `N` values, written without branches or calls so that it
/// compiles to vector instructions (libm's `exp` is one call per value: the film's gaussian rows
/// made four per sample, 7.7% of veach-mis's render). Cephes' `exp.c` (S. L. Moshier): x is
/// n ln2 plus r with |r| ≤ ln2/2, eʳ = 1 + 2r·P(r²)/(Q(r²) − r·P(r²)) (a Padé form, relative
/// error about 2·10⁻¹⁶), scaled by 2ⁿ through the exponent bits. The coefficients are Cephes'
/// as the nearest f64 (Cephes' P₂ = 0.99999999999999999991 is 1.0 in f64). x is clamped to
/// [−708, 709], where eˣ is a normal f64; NaN gives NaN.
#[inline(always)]
pub fn exp_f64_lanes<const N: usize>(x: [f64; N]) -> [f64; N] {
    // A plain loop: `array::map` was compiled out of line (`try_map`, baseline x86-64, 8% of
    // veach-mis), outside the kernel's vector instruction set.
    let mut out = [0.0; N];
    for (o, &v) in out.iter_mut().zip(&x) {
        *o = exp_f64_lane(v);
    }
    out
}

#[inline(always)]
fn exp_f64_lane(x: f64) -> f64 {
    let xc = x.clamp(-708.0, 709.0);
    let shifted = xc * std::f64::consts::LOG2_E + ROUND_MAGIC_F64;
    let n = shifted - ROUND_MAGIC_F64;
    // n as an integer from the bits of n + 1.5·2⁵² (no saturating conversion, which would not
    // vectorise).
    let n_int = shifted.to_bits() as i64 - ROUND_MAGIC_F64.to_bits() as i64;
    let r = xc - n * EXP64_LN2_HI - n * EXP64_LN2_LO;
    let rr = r * r;
    let p = ((1.261_771_930_748_105_8e-4 * rr + 3.029_944_077_074_419_5e-2) * rr + 1.0) * r;
    let q = ((3.001_985_051_386_644_6e-6 * rr + 2.524_483_403_496_841e-3) * rr + 2.272_655_482_081_550_3e-1) * rr + 2.0;
    let er = 1.0 + 2.0 * (p / (q - p));
    // 2ⁿ as 2ⁿ⁻¹·2, so that n = 1023 (e⁷⁰⁹) keeps a finite exponent field.
    let half_scale = f64::from_bits(((n_int + 1022) as u64) << 52);
    er * half_scale * 2.0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Within 2 ulp of libm's `exp` over the whole normal range and on the gaussian rows'
    /// arguments (−50 to 50).
    #[test]
    fn exp_f64_is_libms_within_two_ulp() {
        let ulps = |a: f64, b: f64| (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs();
        let mut worst = 0;
        for k in 0..200_000 {
            for x in [-708.0 + 1417.0 * k as f64 / 200_000.0, -50.0 + 100.0 * k as f64 / 200_000.0] {
                let got = exp_f64_lanes([x])[0];
                worst = worst.max(ulps(got, x.exp()));
            }
        }
        assert!(worst <= 2, "worst {worst} ulp");
        assert_eq!(exp_f64_lanes([0.0, 1.0])[0], 1.0);
        assert!(exp_f64_lanes([f64::NAN])[0].is_nan());
    }

    fn exp1(x: f32) -> f32 {
        exp_lanes(F32s([x])).0[0]
    }

    fn ln1(x: f32) -> f32 {
        ln_lanes(F32s([x])).0[0]
    }

    /// Distance in units in the last place of the f32 nearest to `exact`.
    fn ulps(value: f32, exact: f64) -> f64 {
        let nearest = exact as f32;
        let ulp = f64::from(f32::from_bits(nearest.to_bits() + 1) - nearest);
        (f64::from(value) - exact).abs() / ulp
    }

    #[test]
    fn exp_is_within_two_ulps_over_its_range() {
        let mut worst = 0.0f64;
        for k in 0..=400_000 {
            let x = EXP_UNDERFLOW + (EXP_OVERFLOW - EXP_UNDERFLOW) * k as f32 / 400_000.0;
            worst = worst.max(ulps(exp1(x), f64::from(x).exp()));
        }
        assert!(worst < 2.0, "worst error {worst} ulp");
        assert_eq!(exp1(0.0), 1.0);
    }

    #[test]
    fn exp_edges() {
        assert_eq!(exp1(-88.0), 0.0);
        assert_eq!(exp1(-1e30), 0.0);
        assert_eq!(exp1(f32::NEG_INFINITY), 0.0);
        assert_eq!(exp1(89.0), f32::INFINITY);
        assert_eq!(exp1(f32::INFINITY), f32::INFINITY);
        assert!(exp1(f32::NAN).is_nan());
        assert!(exp1(EXP_OVERFLOW).is_finite());
        assert!(exp1(EXP_UNDERFLOW) > 0.0);
    }

    #[test]
    fn ln_is_within_two_ulps_on_normal_numbers() {
        let mut worst = 0.0f64;
        // Every binade's mantissas, coarsely, and the neighbourhood of 1 finely (where ln
        // cancels to small values).
        for k in 0..200_000u32 {
            let x = f32::from_bits(0x0080_0000 + k * ((0x7f7f_ffff - 0x0080_0000) / 200_000));
            worst = worst.max(ulps(ln1(x), f64::from(x).ln()));
        }
        for k in 1..100_000 {
            for x in [1.0 + k as f32 * 1e-6, 1.0 - k as f32 * 5e-7] {
                worst = worst.max(ulps(ln1(x), f64::from(x).ln()));
            }
        }
        assert!(worst < 2.0, "worst error {worst} ulp");
        assert_eq!(ln1(1.0), 0.0);
    }

    #[test]
    fn ln_edges() {
        assert_eq!(ln1(0.0), f32::NEG_INFINITY);
        assert_eq!(ln1(f32::INFINITY), f32::INFINITY);
        assert!(ln1(-1.0).is_nan());
        assert!(ln1(f32::NAN).is_nan());
    }

    #[test]
    fn lanes_are_independent() {
        let x = F32s([-1.0, 0.5, 3.0, -100.0]);
        let e = exp_lanes(x);
        let l = ln_lanes(F32s([0.25, 1.0, 7.5, 1e-30]));
        for i in 0..4 {
            assert_eq!(e.0[i], exp1(x.0[i]));
        }
        assert_eq!(l.0[0], ln1(0.25));
        assert_eq!(l.0[3], ln1(1e-30));
    }
}
