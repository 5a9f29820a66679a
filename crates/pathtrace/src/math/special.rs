//! Special functions the microfacet models need: the error function, its inverse, and
//! Gauss–Legendre quadrature nodes (for tables precomputed when a material is built).

/// eˣ, with arguments far below the smallest positive result answered 0 at once: glibc's `exp`
/// returns +0 for every x < −745.14 too, but below −1024 it reaches that 0 through its
/// underflow handler (which sets `errno`), and Gaussian tails evaluated at grazing angles land
/// there often enough to show in profiles (2% of a veach-mis render). Same value, bit for bit.
#[inline(always)]
pub fn exp_flushed(x: f64) -> f64 {
    if x < -746.0 {
        0.0
    } else {
        x.exp()
    }
}

/// [`exp_flushed`] in single precision: `expf` returns +0 (through its underflow handler) for
/// every x < −103.98.
#[inline(always)]
pub fn exp_flushed_f32(x: f32) -> f32 {
    if x < -104.0 {
        0.0
    } else {
        x.exp()
    }
}

/// The error function erf(x) = 2/√π ∫₀ˣ e^(−t²) dt, to double precision (libm's port of
/// FreeBSD's msun `erf`).
#[inline]
pub fn erf(x: f64) -> f64 {
    libm::erf(x)
}

/// erf(x) to single precision (absolute error < 1.5·10⁻⁷): Abramowitz & Stegun 7.1.26, one
/// exponential and a degree-5 polynomial — for the render loop, where libm's double-precision
/// `erf` costs several times more.
#[inline]
pub fn erf_fast(x: f64) -> f64 {
    erf_and_gaussian_fast(x).0
}

/// [`erf_fast`]`(x)` together with the Gaussian e^(−x²) it is built on, for callers that need
/// both (Beckmann's Λ and its visible-slope CDF): one exponential instead of two.
#[inline]
pub fn erf_and_gaussian_fast(x: f64) -> (f64, f64) {
    let t = 1.0 / (1.0 + 0.327_591_1 * x.abs());
    let poly =
        t * (0.254_829_592 + t * (-0.284_496_736 + t * (1.421_413_741 + t * (-1.453_152_027 + t * 1.061_405_429))));
    let gaussian = exp_flushed(-x * x);
    let y = 1.0 - poly * gaussian;
    (if x < 0.0 { -y } else { y }, gaussian)
}

/// The inverse error function on (−1, 1); ±∞ at ±1, NaN outside.
///
/// Starts from [`erfinv_fast`] and polishes it by two Newton steps on erf(x) = y
/// (d/dx erf = 2/√π e^(−x²)), which brings it to double precision.
pub fn erfinv(y: f64) -> f64 {
    let mut x = erfinv_fast(y);
    if !x.is_finite() {
        return x;
    }
    let two_over_sqrt_pi = std::f64::consts::FRAC_2_SQRT_PI;
    for _ in 0..2 {
        let slope = two_over_sqrt_pi * (-x * x).exp();
        if slope <= 0.0 {
            break;
        }
        x -= (erf(x) - y) / slope;
    }
    x
}

/// Giles' approximation of the inverse error function ("Approximating the erfinv function",
/// GPU Computing Gems, 2011): relative error below ~4·10⁻⁷ on (−1, 1), enough for single
/// precision results, at the cost of one logarithm (and a square root in the tails).
pub fn erfinv_fast(y: f64) -> f64 {
    if !(-1.0..=1.0).contains(&y) {
        return f64::NAN;
    }
    if y.abs() == 1.0 {
        return y * f64::INFINITY;
    }
    let w = -((1.0 - y) * (1.0 + y)).ln();
    if w < 5.0 {
        let w = w - 2.5;
        let mut p = 2.810_226_36e-08;
        for c in [
            3.432_739_39e-07,
            -3.523_387_7e-06,
            -4.391_506_54e-06,
            0.000_218_580_87,
            -0.001_253_725_03,
            -0.004_177_681_64,
            0.246_640_727,
            1.501_409_41,
        ] {
            p = c + p * w;
        }
        p * y
    } else {
        let w = w.sqrt() - 3.0;
        let mut p = -0.000_200_214_257;
        for c in [
            0.000_100_950_558,
            0.001_349_343_22,
            -0.003_673_428_44,
            0.005_739_507_73,
            -0.007_622_461_3,
            0.009_438_870_47,
            1.001_674_06,
            2.832_976_82,
        ] {
            p = c + p * w;
        }
        p * y
    }
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

    #[test]
    fn flushed_exponentials_are_the_library_values() {
        let xs = [
            -1e30, -2000.0, -1024.5, -1023.0, -800.0, -746.0, -745.2, -745.1, -740.0, -104.5, -104.0, -103.9, -87.0,
            -1.0, 0.0, 2.5,
        ];
        for x in xs {
            assert_eq!(exp_flushed(x).to_bits(), x.exp().to_bits(), "{x}");
            let x32 = x as f32;
            assert_eq!(exp_flushed_f32(x32).to_bits(), x32.exp().to_bits(), "{x32}");
        }
        for k in 0..20_000 {
            let x = -700.0 - k as f64 * 0.005;
            assert_eq!(exp_flushed(x).to_bits(), x.exp().to_bits(), "{x}");
            let x32 = -80.0 - k as f32 * 0.002;
            assert_eq!(exp_flushed_f32(x32).to_bits(), x32.exp().to_bits(), "{x32}");
        }
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
            let (fast, exact) = (erfinv_fast(y), erfinv(y));
            assert!((fast - exact).abs() <= 1e-6 * exact.abs().max(1e-3), "y = {y}: {fast} vs {exact}");
        }
    }

    #[test]
    fn fast_erf_is_single_precision() {
        for i in -400..=400 {
            let x = i as f64 / 100.0;
            assert!((erf_fast(x) - erf(x)).abs() < 1.5e-7, "x = {x}");
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
