//! atan2 and acos per lane, to single precision: the environment map's direction → image
//! mapping, for every lane of a group at once (libm's `atan2f` and `acosf` are one call per
//! lane).
//!
//! Both reduce the argument to a small interval and evaluate an odd minimax polynomial there;
//! the reductions and polynomial coefficients are those of Cephes' single-precision `atanf`
//! and `asinf` (S. L. Moshier, "Methods and Programs for Mathematical Functions", 1989), whose
//! relative error is about 10⁻⁷ (the tests below bound ours against f64).

use super::simd::F32s;
use crate::math::PI;

/// tan(π/8): above it atan is reduced by atan(a) = π/4 + atan((a − 1)/(a + 1)).
const TAN_PI_8: f32 = 0.414_213_57;

/// atan(t) for |t| ≤ tan(π/8).
#[inline(always)]
fn atan_reduced<const N: usize>(t: F32s<N>) -> F32s<N> {
    let z = t * t;
    (((8.053_744_5e-2 * z - 1.387_768_6e-1) * z + 1.997_771_1e-1) * z - 3.333_295e-1) * z * t + t
}

/// asin(s) for 0 ≤ s ≤ ½, given z = s².
#[inline(always)]
fn asin_reduced<const N: usize>(s: F32s<N>, z: F32s<N>) -> F32s<N> {
    ((((4.216_32e-2 * z + 2.418_131e-2) * z + 4.547_002_6e-2) * z + 7.495_300_3e-2) * z + 1.666_675_2e-1) * z * s + s
}

/// atan2(y, x) in [−π, π] per lane, the angle of (x, y). atan2(±0, ±0) is ±0 (libm gives ±π
/// for x = −0; no caller depends on the angle of the zero vector).
#[inline(always)]
pub fn atan2<const N: usize>(y: F32s<N>, x: F32s<N>) -> F32s<N> {
    let zero = F32s::<N>::ZERO;
    let (ax, ay) = (x.abs(), y.abs());
    let (small, big) = (ax.min(ay), ax.max(ay));
    // In [0, 1]: the angle to the nearer axis, as a tangent.
    let a = F32s::select(big.gt(zero), small / big, zero);
    let reduce = a.gt(F32s::splat(TAN_PI_8));
    let t = F32s::select(reduce, (a - 1.0) / (a + 1.0), a);
    let r = atan_reduced(t);
    let r = F32s::select(reduce, r + PI / 4.0, r);
    // Unfold the octant, then the half plane, then the sign of y.
    let r = F32s::select(ay.gt(ax), PI / 2.0 - r, r);
    let r = F32s::select(x.lt(zero), PI - r, r);
    r.copysign(y)
}

/// acos(x) in [0, π] per lane, for x in [−1, 1]: asin of |x| ≤ ½ directly (acos = π/2 − asin),
/// beyond through acos|x| = 2 asin √((1 − |x|)/2).
#[inline(always)]
pub fn acos<const N: usize>(x: F32s<N>) -> F32s<N> {
    let ax = x.abs();
    let far = ax.gt(F32s::splat(0.5));
    let z = F32s::select(far, 0.5 * (1.0 - ax), ax * ax);
    let s = F32s::select(far, z.sqrt(), ax);
    let p = asin_reduced(s, z);
    let near_zero = PI / 2.0 - p.copysign(x);
    let near_one = F32s::select(x.lt(F32s::ZERO), PI - 2.0 * p, 2.0 * p);
    F32s::select(far, near_one, near_zero)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn one(v: f32) -> F32s<1> {
        F32s::splat(v)
    }

    #[test]
    fn atan2_agrees_with_double_precision_all_around_the_circle() {
        let mut worst = 0.0f64;
        for k in 0..100_000 {
            let angle = (k as f64 / 100_000.0 - 0.5) * 2.0 * std::f64::consts::PI;
            for radius in [1.0f64, 1e-3, 37.5] {
                let (x, y) = ((radius * angle.cos()) as f32, (radius * angle.sin()) as f32);
                let exact = f64::from(y).atan2(f64::from(x));
                let got = f64::from(atan2(one(y), one(x)).0[0]);
                worst = worst.max((got - exact).abs());
            }
        }
        assert!(worst < 4e-7, "worst absolute error {worst}");
        // The axes and the signs of zero.
        assert_eq!(atan2(one(0.0), one(1.0)).0[0], 0.0);
        assert!(atan2(one(-0.0), one(1.0)).0[0].is_sign_negative());
        assert!((atan2(one(0.0), one(-1.0)).0[0] - PI).abs() < 1e-7);
        assert!((atan2(one(1.0), one(0.0)).0[0] - PI / 2.0).abs() < 1e-7);
        assert!((atan2(one(-1.0), one(0.0)).0[0] + PI / 2.0).abs() < 1e-7);
        assert_eq!(atan2(one(0.0), one(0.0)).0[0], 0.0);
    }

    #[test]
    fn acos_agrees_with_double_precision_on_the_whole_interval() {
        let mut worst = 0.0f64;
        for k in 0..=200_000 {
            let x = (k as f32 / 100_000.0 - 1.0).clamp(-1.0, 1.0);
            let exact = f64::from(x).acos();
            let got = f64::from(acos(one(x)).0[0]);
            worst = worst.max((got - exact).abs());
        }
        assert!(worst < 4e-7, "worst absolute error {worst}");
        assert_eq!(acos(one(1.0)).0[0], 0.0);
        assert!((acos(one(-1.0)).0[0] - PI).abs() < 1e-7);
        assert!((acos(one(0.0)).0[0] - PI / 2.0).abs() < 1e-7);
    }
}
