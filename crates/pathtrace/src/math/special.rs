//! Special functions the microfacet models need: the error function, its inverse, and
//! Gauss–Legendre quadrature nodes (for tables precomputed when a material is built).

use super::exp_log::{exp_lanes, ln_lanes};
use crate::wide::simd::F32s;

/// The error function erf(x) = 2/√π ∫₀ˣ e^(−t²) dt, to double precision (libm's port of
/// FreeBSD's msun `erf`).
#[inline]
pub fn erf(x: f64) -> f64 {
    libm::erf(x)
}

/// erf(x) in single precision: Abramowitz & Stegun 7.1.26 (absolute error < 1.5·10⁻⁷ in exact
/// arithmetic, < 6·10⁻⁷ evaluated in f32), one exponential and a degree-5 polynomial — for the
/// render loop, where libm's double-precision `erf` costs several times more. In `f32`, the
/// number type of the SIMD lanes, so that a lane form can share it (one at a time it is about as
/// quick as the f64 form was).
#[inline]
pub fn erf_fast(x: f32) -> f32 {
    erf_and_gaussian_fast(x).0
}

/// [`erf_fast`]`(x)` together with the Gaussian e^(−x²) it is built on, for callers that need
/// both (Beckmann's Λ and its visible-slope CDF): one exponential instead of two.
#[inline]
pub fn erf_and_gaussian_fast(x: f32) -> (f32, f32) {
    let (erf, gaussian) = erf_and_gaussian_lanes(F32s([x]));
    (erf.0[0], gaussian.0[0])
}

/// [`erf_and_gaussian_fast`] per lane (the one implementation: the scalar form is its one-lane
/// instance).
#[inline(always)]
pub fn erf_and_gaussian_lanes<const N: usize>(x: F32s<N>) -> (F32s<N>, F32s<N>) {
    let t = 1.0 / (1.0 + 0.327_591_1 * x.abs());
    let poly = t * (0.254_829_6 + t * (-0.284_496_74 + t * (1.421_413_8 + t * (-1.453_152 + t * 1.061_405_4))));
    let gaussian = exp_lanes(-x * x);
    let y = 1.0 - poly * gaussian;
    (F32s::select(x.lt(F32s::ZERO), -y, y), gaussian)
}

/// Giles' single-precision approximation of the inverse error function ("Approximating the
/// erfinv function", GPU Computing Gems, 2011): relative error below ~4·10⁻⁷ on (−1, 1), at the
/// cost of one logarithm (and a square root in the tails). ±∞ at ±1, NaN outside.
#[inline]
pub fn erfinv_fast(y: f32) -> f32 {
    erfinv_lanes(F32s([y])).0[0]
}

/// [`erfinv_fast`] per lane (its one implementation): both of Giles' polynomials are evaluated
/// in every lane and each lane keeps its own.
#[inline(always)]
pub fn erfinv_lanes<const N: usize>(y: F32s<N>) -> F32s<N> {
    let w = -ln_lanes((1.0 - y) * (1.0 + y));
    let central = w - 2.5;
    let mut p = F32s::splat(2.810_226_4e-8);
    for c in [
        3.432_739_4e-7,
        -3.523_387_7e-6,
        -4.391_506_5e-6,
        0.000_218_580_87,
        -0.001_253_725,
        -0.004_177_681_6,
        0.246_640_73,
        1.501_409_4,
    ] {
        p = p * central + c;
    }
    let tail = w.sqrt() - 3.0;
    let mut q = F32s::splat(-0.000_200_214_26);
    for c in [
        0.000_100_950_56,
        0.001_349_343_2,
        -0.003_673_428_4,
        0.005_739_507_7,
        -0.007_622_461,
        0.009_438_870_5,
        1.001_674,
        2.832_976_8,
    ] {
        q = q * tail + c;
    }
    let x = F32s::select(w.lt(F32s::splat(5.0)), p, q) * y;
    // ±1: w = +∞ (both polynomials are ∞ or NaN there); beyond: NaN from the logarithm.
    let edge = y.abs().eq(F32s::ONE);
    F32s::select(edge, y * f32::INFINITY, x)
}

/// The `n` Gauss–Legendre nodes and weights on [−1, 1] (Newton's method on the Legendre
/// polynomial Pₙ from Chebyshev initial guesses; Numerical Recipes 3rd ed. §4.6.1).
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let mut out = vec![(0.0, 0.0); n];
    let nf = n as f64;
    for i in 0..n.div_ceil(2) {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
        let mut derivative = 1.0;
        for _ in 0..100 {
            // Recurrence (k+1)P_{k+1} = (2k+1)x P_k − k P_{k−1}.
            let (mut p0, mut p1) = (1.0, 0.0);
            for k in 0..n {
                let p2 = p1;
                p1 = p0;
                p0 = ((2 * k + 1) as f64 * x * p1 - k as f64 * p2) / (k + 1) as f64;
            }
            derivative = nf * (x * p0 - p1) / (x * x - 1.0);
            let step = p0 / derivative;
            x -= step;
            if step.abs() < 1e-15 {
                break;
            }
        }
        let w = 2.0 / ((1.0 - x * x) * derivative * derivative);
        out[i] = (-x, w);
        out[n - 1 - i] = (x, w);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The inverse error function on (−1, 1) to double precision, the reference for
    /// [`erfinv_fast`]: Newton's method on erf(x) = y (d/dx erf = 2/√π e^(−x²)) from the
    /// single-precision start, until the steps vanish.
    fn erfinv(y: f64) -> f64 {
        let start = (y as f32).clamp(-1.0 + f32::EPSILON / 2.0, 1.0 - f32::EPSILON / 2.0);
        let mut x = f64::from(erfinv_fast(start));
        for _ in 0..100 {
            let step = (erf(x) - y) / (std::f64::consts::FRAC_2_SQRT_PI * (-x * x).exp());
            x -= step;
            if step.abs() < 1e-15 * x.abs().max(1.0) {
                break;
            }
        }
        x
    }

    #[test]
    fn erfinv_inverts_erf() {
        for i in -99..=99 {
            let y = i as f64 / 100.0;
            assert!((erf(erfinv(y)) - y).abs() < 1e-14, "y = {y}");
        }
        assert!((erfinv(1.0 - 1e-12) - 5.042).abs() < 1e-3);
        for i in -999..=999 {
            let y = i as f64 / 1000.0;
            let (fast, exact) = (f64::from(erfinv_fast(y as f32)), erfinv(f64::from(y as f32)));
            assert!((fast - exact).abs() <= 1e-6 * exact.abs().max(1e-3), "y = {y}: {fast} vs {exact}");
        }
    }

    /// [`erf_fast`]'s documented bound: A&S 7.1.26's own 1.5·10⁻⁷ and the f32 evaluation's
    /// roundings (the most, 4.9·10⁻⁷ in all, where 1 − p·e^(−x²) cancels near |x| = 0.25).
    const ERF_FAST_ERROR: f64 = 6e-7;

    #[test]
    fn fast_erf_is_single_precision() {
        for i in -400..=400 {
            let x = i as f32 / 100.0;
            let error = f64::from(erf_fast(x)) - erf(f64::from(x));
            assert!(error.abs() < ERF_FAST_ERROR, "x = {x}: error {error:e}");
        }
    }

    #[test]
    fn gauss_legendre_integrates_polynomials_exactly() {
        // n nodes integrate degree 2n−1 exactly: ∫₋₁¹ x⁶ dx = 2/7.
        let rule = gauss_legendre(4);
        let sum: f64 = rule.iter().map(|(x, w)| w * x.powi(6)).sum();
        assert!((sum - 2.0 / 7.0).abs() < 1e-14);
        let weights: f64 = gauss_legendre(33).iter().map(|(_, w)| w).sum();
        assert!((weights - 2.0).abs() < 1e-13);
    }
}
