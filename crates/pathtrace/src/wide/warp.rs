//! The warps of the Lambertian form, written once for every lane count: the concentric disk
//! and the cosine-weighted hemisphere (Malley's method), and the orthonormal basis of a normal
//! (Duff et al. 2017). `sampling::warp` and `math::Frame::from_normal` are their one-lane
//! instances.
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

/// Uniform barycentric coordinates on a triangle by the square-root warp, (1 − √u1, u2·√u1)
/// (pbrt-v3 §13.6.4), per lane.
#[inline(always)]
pub fn square_to_uniform_triangle<const N: usize>(u1: F32s<N>, u2: F32s<N>) -> (F32s<N>, F32s<N>) {
    let su = u1.sqrt();
    (1.0 - su, u2 * su)
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

/// The two tangents `(s, t)` completing the unit normal `n` to a right-handed orthonormal
/// basis, from Duff et al., "Building an Orthonormal Basis, Revisited" (JCGT 2017).
#[inline(always)]
pub fn basis<const N: usize>(n: &Vec3s<N>) -> (Vec3s<N>, Vec3s<N>) {
    let sign = sign_of(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let s = Vec3s { x: 1.0 + sign * n.x * n.x * a, y: sign * b, z: -(sign * n.x) };
    let t = Vec3s { x: b, y: sign + n.y * n.y * a, z: -n.y };
    (s, t)
}

/// Local direction `v` (normal along +z) to world space around the unit normal `n`, in the
/// basis of [`basis`].
#[inline(always)]
pub fn to_world<const N: usize>(n: &Vec3s<N>, v: &Vec3s<N>) -> Vec3s<N> {
    let (s, t) = basis(n);
    s.scale(v.x).add(&t.scale(v.y)).add(&n.scale(v.z))
}

#[cfg(test)]
mod tests {
    use super::*;
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
}
