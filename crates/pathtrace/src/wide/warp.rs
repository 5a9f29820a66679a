//! Eight-lane versions of the warps the wide kernel needs: the cosine-weighted hemisphere
//! (Malley's method over the concentric disk, as `sampling::warp`) and the orthonormal basis
//! of a normal (Duff et al. 2017, as `math::Frame::from_normal`).
//!
//! The concentric map only needs sin and cos of angles in [-π/4, π/4] (the other octants are
//! reached by swapping the two and by the radius' sign), where short Taylor polynomials are
//! accurate to 3·10⁻⁷ and vectorise, unlike calls to `sinf`/`cosf`.

use super::simd::{F32s, Vec3s};
use crate::math::PI;

/// sin x for |x| ≤ π/4: x − x³/3! + x⁵/5! − x⁷/7! (truncation error ≤ (π/4)⁹/9! < 3·10⁻⁷).
#[inline(always)]
fn sin_quarter<const N: usize>(x: F32s<N>) -> F32s<N> {
    let x2 = x * x;
    x * (1.0 + x2 * (-1.0 / 6.0 + x2 * (1.0 / 120.0 + x2 * (-1.0 / 5040.0))))
}

/// cos x for |x| ≤ π/4: 1 − x²/2! + x⁴/4! − x⁶/6! + x⁸/8! (truncation error < 3·10⁻⁸).
#[inline(always)]
fn cos_quarter<const N: usize>(x: F32s<N>) -> F32s<N> {
    let x2 = x * x;
    1.0 + x2 * (-0.5 + x2 * (1.0 / 24.0 + x2 * (-1.0 / 720.0 + x2 * (1.0 / 40320.0))))
}

/// Concentric map from the square to the unit disk (Shirley & Chiu 1997), per lane.
#[inline(always)]
pub fn square_to_uniform_disk<const N: usize>(u1: F32s<N>, u2: F32s<N>) -> (F32s<N>, F32s<N>) {
    let a = 2.0 * u1 - 1.0;
    let b = 2.0 * u2 - 1.0;
    let a_wider = a.abs().gt(b.abs());
    let r = F32s::<N>::select(a_wider, a, b);
    // Angle within the octant; 0/0 at the centre (r = 0) is replaced by 0.
    let ratio = F32s::<N>::select(a_wider, b / a, a / b);
    let x = F32s::<N>::select(r.abs().gt(F32s::<N>::ZERO), ratio * (PI / 4.0), F32s::<N>::ZERO);
    let (c, s) = (r * cos_quarter(x), r * sin_quarter(x));
    // Where |a| ≤ |b| the angle is π/2 − x: cos and sin swap.
    (F32s::<N>::select(a_wider, c, s), F32s::<N>::select(a_wider, s, c))
}

/// Cosine-weighted direction about +z (pdf cos θ / π), per lane.
#[inline(always)]
pub fn square_to_cosine_hemisphere<const N: usize>(u1: F32s<N>, u2: F32s<N>) -> Vec3s<N> {
    let (x, y) = square_to_uniform_disk(u1, u2);
    let z = (1.0 - x * x - y * y).max(F32s::<N>::ZERO).sqrt();
    Vec3s { x, y, z }
}

/// ±1 with the sign bit of each lane (copysign(1, v)).
#[inline(always)]
fn sign_of<const N: usize>(v: F32s<N>) -> F32s<N> {
    let mut out = [0.0; N];
    for (o, &x) in out.iter_mut().zip(&v.0) {
        *o = f32::from_bits(1.0f32.to_bits() | (x.to_bits() & 0x8000_0000));
    }
    F32s(out)
}

/// Local direction `v` (normal along +z) to world space around the unit normal `n`, with the
/// tangents of Duff et al., "Building an Orthonormal Basis, Revisited" (JCGT 2017).
#[inline(always)]
pub fn to_world<const N: usize>(n: &Vec3s<N>, v: &Vec3s<N>) -> Vec3s<N> {
    let sign = sign_of(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let s = Vec3s { x: 1.0 + sign * n.x * n.x * a, y: sign * b, z: -(sign * n.x) };
    let t = Vec3s { x: b, y: sign + n.y * n.y * a, z: -n.y };
    s.scale(v.x).add(&t.scale(v.y)).add(&n.scale(v.z))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{Frame, Vec2, Vec3};
    use crate::sampling::warp;
    use crate::wide::simd::LANES_256 as N;

    #[test]
    fn polynomials_match_sin_and_cos_on_the_octant() {
        let xs = F32s::<N>::from_fn(|i| (i as f32 / 7.0 - 0.5) * PI / 2.0);
        let (s, c) = (sin_quarter(xs), cos_quarter(xs));
        for i in 0..N {
            assert!((s.0[i] - xs.0[i].sin()).abs() < 5e-7, "sin {}", xs.0[i]);
            assert!((c.0[i] - xs.0[i].cos()).abs() < 5e-7, "cos {}", xs.0[i]);
        }
    }

    #[test]
    fn disk_and_hemisphere_agree_with_the_scalar_warps() {
        // The same map as sampling::warp, so the same points up to rounding.
        for k in 0..64 {
            let u1 = F32s::<N>::from_fn(|i| ((k * 8 + i) as f32 * 0.618_034).fract());
            let u2 = F32s::<N>::from_fn(|i| ((k * 8 + i) as f32 * 0.414_214 + 0.5 * (i == 3) as u8 as f32).fract());
            let w = square_to_cosine_hemisphere(u1, u2);
            for i in 0..N {
                let expect = warp::square_to_cosine_hemisphere(Vec2::new(u1.0[i], u2.0[i]));
                let got = w.lane(i);
                // The disk point agrees to rounding; z = √(1 − r²) amplifies it at the rim, so
                // compare z².
                assert!((got.truncate() - expect.truncate()).length() < 2e-6, "{got:?} vs {expect:?}");
                assert!((got.z * got.z - expect.z * expect.z).abs() < 4e-6, "{got:?} vs {expect:?}");
            }
        }
        let centre = square_to_uniform_disk(F32s::<N>::splat(0.5), F32s::<N>::splat(0.5));
        assert_eq!((centre.0 .0[0], centre.1 .0[0]), (0.0, 0.0));
    }

    #[test]
    fn basis_matches_the_scalar_frame() {
        let normals = [
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::new(0.3, -0.5, 0.8).normalize(),
            Vec3::new(-0.7, 0.1, -0.2).normalize(),
            Vec3::new(0.0, 1.0, -1e-8).normalize(),
            Vec3::new(1e-3, 0.2, -0.9).normalize(),
            -Vec3::Y,
        ];
        let n = Vec3s::<N>::from_fn(|i| normals[i]);
        let v = Vec3::new(0.36, -0.48, 0.8);
        let w = to_world(&n, &Vec3s::<N>::splat(v));
        for (i, &normal) in normals.iter().enumerate() {
            assert!((w.lane(i) - Frame::from_normal(normal).to_world(v)).length() < 1e-6);
        }
    }
}
