//! The warps of the lane-parallel forms, written once for every lane count: the concentric disk
//! and the cosine-weighted hemisphere (Malley's method), uniform directions on the sphere and in
//! a cone (sphere lights), and the orthonormal basis of a normal (Duff et al. 2017).
//! `sampling::warp` and `math::Frame::from_normal` are their one-lane instances.
//!
//! The warps only need sin and cos of angles in [-π/4, π/4] (other angles are reached by
//! swapping the two and by signs), where short Taylor polynomials are accurate to 3·10⁻⁷ and
//! vectorise, unlike calls to `sinf`/`cosf`.

use super::simd::{F32s, Ms, Vec3s};
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

/// (cos 2πu, sin 2πu) per lane, for u in [0, 1]: the angle is split into the nearest multiple
/// of π/2, kπ/2, and a remainder |x| ≤ π/4 (4u − k is exact), whose sine and cosine are then
/// rotated by k quarter turns.
#[inline(always)]
pub fn cos_sin_turn<const N: usize>(u: F32s<N>) -> (F32s<N>, F32s<N>) {
    let quarters = 4.0 * u;
    let k = (quarters + 0.5).floor();
    let x = (quarters - k) * (PI / 2.0);
    let (c, s) = (cos_quarter(x), sin_quarter(x));
    // k mod 4 picks the rotation: (c, s), (−s, c), (−c, −s), (s, −c).
    let k = k - 4.0 * (k * 0.25).floor();
    let (k1, k2, k3) = (k.eq(F32s::splat(1.0)), k.eq(F32s::splat(2.0)), k.eq(F32s::splat(3.0)));
    let cos = F32s::select(k1, -s, F32s::select(k2, -c, F32s::select(k3, s, c)));
    let sin = F32s::select(k1, c, F32s::select(k2, -s, F32s::select(k3, -c, s)));
    (cos, sin)
}

/// A direction with height `z` above the xy plane and azimuth 2π·`u`.
#[inline(always)]
fn at_height<const N: usize>(z: F32s<N>, u: F32s<N>) -> Vec3s<N> {
    let r = (1.0 - z * z).max(F32s::<N>::ZERO).sqrt();
    let (c, s) = cos_sin_turn(u);
    Vec3s { x: r * c, y: r * s, z }
}

/// Uniform direction on the unit sphere: z = 1 − 2u1, φ = 2πu2 (Archimedes' hat-box
/// theorem: z is uniform); pdf 1/(4π).
#[inline(always)]
pub fn square_to_uniform_sphere<const N: usize>(u1: F32s<N>, u2: F32s<N>) -> Vec3s<N> {
    at_height(1.0 - 2.0 * u1, u2)
}

/// Uniform direction in the cone of half-angle θ_max about +z: z = 1 − u1(1 − cos θ_max),
/// φ = 2πu2; pdf 1/(2π(1 − cos θ_max)) (pbrt-v3 §13.6.4).
#[inline(always)]
pub fn square_to_uniform_cone<const N: usize>(u1: F32s<N>, u2: F32s<N>, cos_theta_max: F32s<N>) -> Vec3s<N> {
    at_height(1.0 - u1 * (1.0 - cos_theta_max), u2)
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

/// `(r cos φ, r sin φ, z)` with φ = 2π·`u2`, libm's cosine and sine taken in the lanes of
/// `active` (the scalar warps' bits; the other lanes' x and y are unspecified).
#[inline(always)]
fn around_z<const N: usize>(r: F32s<N>, z: F32s<N>, u2: F32s<N>, active: Ms<N>) -> Vec3s<N> {
    let phi = 2.0 * PI * u2;
    let (mut cos_phi, mut sin_phi) = (F32s::ZERO, F32s::ZERO);
    for i in active.lanes() {
        (cos_phi.0[i], sin_phi.0[i]) = (phi.0[i].cos(), phi.0[i].sin());
    }
    Vec3s { x: r * cos_phi, y: r * sin_phi, z }
}

/// Uniform directions on the upper hemisphere, z = `u1`, φ = 2π`u2`, in the lanes of `active`.
#[inline(always)]
pub fn square_to_uniform_hemisphere<const N: usize>(u1: F32s<N>, u2: F32s<N>, active: Ms<N>) -> Vec3s<N> {
    let z = u1;
    let r = (1.0 - z * z).max(F32s::ZERO).sqrt();
    around_z(r, z, u2, active)
}

/// Power-cosine lobes around +z, cos θ = `u1`^(1/(n + 1)), in the lanes of `active`.
#[inline(always)]
pub fn square_to_power_cosine<const N: usize>(u1: F32s<N>, u2: F32s<N>, exponent: F32s<N>, active: Ms<N>) -> Vec3s<N> {
    let power = 1.0 / (exponent + 1.0);
    let mut z = F32s::ZERO;
    for i in active.lanes() {
        z.0[i] = u1.0[i].powf(power.0[i]);
    }
    let r = (1.0 - z * z).max(F32s::ZERO).sqrt();
    around_z(r, z, u2, active)
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

/// The tangents `(s, t)` of a frame around the unit normal `n` whose first tangent follows
/// `tangent`, made perpendicular to `n` by Gram–Schmidt (as Mitsuba 3 builds its shading frame
/// from ∂p/∂u), t = n × s; where `tangent` is (nearly) parallel to `n`, zero or not finite,
/// [`basis`]'s. In glam's order of operations, so `Frame::from_normal_tangent` is its one-lane
/// instance.
#[inline(always)]
pub fn tangent_basis<const N: usize>(n: &Vec3s<N>, tangent: &Vec3s<N>) -> (Vec3s<N>, Vec3s<N>) {
    let along = tangent.sub(&n.scale(n.dot(tangent)));
    let len2 = along.dot(&along);
    // NaN fails both tests, so the fallback is taken.
    let floor = tangent.dot(tangent).map_lanes(|l| l.max(f32::MIN_POSITIVE));
    let usable = len2.gt(1e-12 * floor) & len2.is_finite();
    let len = len2.sqrt();
    let s = Vec3s { x: along.x / len, y: along.y / len, z: along.z / len };
    // n × s, as glam's `Vec3::cross`.
    let t = Vec3s { x: n.y * s.z - s.y * n.z, y: n.z * s.x - s.z * n.x, z: n.x * s.y - s.x * n.y };
    let (s0, t0) = basis(n);
    (Vec3s::select(usable, &s, &s0), Vec3s::select(usable, &t, &t0))
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

    /// The quarter-turn reduction matches `cos`/`sin` over the whole turn, at and between the
    /// quadrant boundaries.
    #[test]
    fn turns_match_cos_and_sin() {
        for k in 0..=4096 {
            let u = k as f32 / 4096.0;
            let (c, s) = cos_sin_turn(F32s::<N>::splat(u));
            let phi = 2.0 * std::f64::consts::PI * f64::from(u);
            assert!((f64::from(c.0[0]) - phi.cos()).abs() < 5e-7, "cos at u = {u}");
            assert!((f64::from(s.0[0]) - phi.sin()).abs() < 5e-7, "sin at u = {u}");
        }
    }

    #[test]
    fn polynomials_match_sin_and_cos_on_the_octant() {
        let xs = F32s::<N>::from_fn(|i| (i as f32 / 7.0 - 0.5) * PI / 2.0);
        let (s, c) = (sin_quarter(xs), cos_quarter(xs));
        for i in 0..N {
            assert!((s.0[i] - xs.0[i].sin()).abs() < 5e-7, "sin {}", xs.0[i]);
            assert!((c.0[i] - xs.0[i].cos()).abs() < 5e-7, "cos {}", xs.0[i]);
        }
    }

    /// Tangent frames of mixed lanes (usable, parallel, zero and NaN tangents) are orthonormal
    /// and right-handed, keep the tangent's direction where it is usable, and fall back to the
    /// normal's basis, lane by lane, where it is not.
    #[test]
    fn tangent_frames_follow_usable_tangents_and_fall_back_lane_by_lane() {
        let n = Vec3s::<N>::from_fn(|i| glam::Vec3::new(0.3 * i as f32 - 1.0, 0.5, 0.8).normalize());
        let tangent = Vec3s::<N>::from_fn(|i| match i % 4 {
            0 => glam::Vec3::new(1.0, 0.2 * i as f32, -0.3),
            1 => n.lane(i) * 2.0,
            2 => glam::Vec3::ZERO,
            _ => glam::Vec3::new(f32::NAN, 0.0, 1.0),
        });
        let (s, t) = tangent_basis(&n, &tangent);
        let (s0, t0) = basis(&n);
        for i in 0..N {
            let (ni, si, ti) = (n.lane(i), s.lane(i), t.lane(i));
            assert!((si.length() - 1.0).abs() < 1e-5 && (ti.length() - 1.0).abs() < 1e-5, "lane {i}");
            assert!(si.dot(ni).abs() < 1e-5 && ti.dot(ni).abs() < 1e-5 && si.dot(ti).abs() < 1e-5, "lane {i}");
            assert!((si.cross(ti) - ni).length() < 1e-5, "lane {i}: right-handed");
            if i % 4 == 0 {
                let along = tangent.lane(i) - ni * ni.dot(tangent.lane(i));
                assert!(si.dot(along.normalize()) > 1.0 - 1e-5, "lane {i}");
            } else {
                assert_eq!((si, ti), (s0.lane(i), t0.lane(i)), "lane {i}");
            }
        }
    }
}
