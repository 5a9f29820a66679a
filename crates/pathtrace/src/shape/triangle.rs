//! Triangles, intersected with the Möller–Trumbore algorithm ("Fast, Minimum Storage
//! Ray/Triangle Intersection", JGT 1997).

use super::{PrimHit, SurfacePoint};
use crate::math::{Aabb, Ray, Vec2, Vec3, Vec4};
use crate::wide::simd::{F32s, Vec3s};
use std::ops::{Add, Mul};

/// Barycentric slack: edges are tested against `-EDGE_SLACK` rather than 0 so that a ray through
/// an edge shared by two triangles hits at least one of them despite rounding (both may
/// report a hit; the nearer wins). It widens each triangle by 1e-6 of its size.
pub(crate) const EDGE_SLACK: f32 = 1e-6;

/// Möller–Trumbore on the triangle spanned by `e1`, `e2` from `p0`.
#[inline(always)]
fn moller_trumbore(ray: &Ray, p0: Vec3, e1: Vec3, e2: Vec3, t_min: f32, t_max: f32) -> Option<PrimHit> {
    let pvec = ray.dir.cross(e2);
    let det = e1.dot(pvec);
    if det == 0.0 || !det.is_finite() {
        return None; // ray parallel to the plane
    }
    let inv_det = 1.0 / det;
    let tvec = ray.origin - p0;
    let u = tvec.dot(pvec) * inv_det;
    if !(-EDGE_SLACK..=1.0 + EDGE_SLACK).contains(&u) {
        return None;
    }
    let qvec = tvec.cross(e1);
    let v = ray.dir.dot(qvec) * inv_det;
    if v < -EDGE_SLACK || u + v > 1.0 + EDGE_SLACK {
        return None;
    }
    let t = e2.dot(qvec) * inv_det;
    (t >= t_min && t <= t_max).then_some(PrimHit { t, u, v })
}

/// A triangle `p0, p0 + e1, p0 + e2`, front face by counter-clockwise winding (normal e1 × e2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    pub p0: Vec3,
    pub e1: Vec3,
    pub e2: Vec3,
    /// Index into the scene's per-triangle vertex-normal table, or `u32::MAX` for flat shading.
    pub shading: u32,
}

impl Triangle {
    /// Sentinel for "no vertex normals".
    pub const FLAT: u32 = u32::MAX;

    /// `None` for degenerate (zero-area) or non-finite triangles.
    pub fn new(a: Vec3, b: Vec3, c: Vec3, shading: u32) -> Option<Self> {
        let e1 = b - a;
        let e2 = c - a;
        let area2 = e1.cross(e2).length();
        (area2 > 0.0 && area2.is_finite() && a.is_finite()).then_some(Self { p0: a, e1, e2, shading })
    }

    pub fn vertices(&self) -> [Vec3; 3] {
        [self.p0, self.p0 + self.e1, self.p0 + self.e2]
    }

    #[inline(always)]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<PrimHit> {
        moller_trumbore(ray, self.p0, self.e1, self.e2, t_min, t_max)
    }

    pub fn surface(&self, hit: &PrimHit, vertex_normals: &[[Vec3; 3]]) -> SurfacePoint {
        self.surface_with(hit, vertex_normals.get(self.shading as usize).copied(), None)
    }

    /// The surface at a hit, given the corners' vertex normals and texture coordinates (each
    /// optional, as in the mesh the triangle came from). `uv` interpolates the texture
    /// coordinates; without them it is the barycentric pair (b1, b2) of the second and third
    /// corners, as in Mitsuba 3.
    #[inline(always)]
    pub fn surface_with(&self, hit: &PrimHit, normals: Option<[Vec3; 3]>, uvs: Option<[Vec2; 3]>) -> SurfacePoint {
        with_unit_normals(self.surface_before_normalising(hit, normals, uvs))
    }

    /// [`Triangle::surface_with`] before [`unit_normals`]: the geometric normal is e1 × e2 and
    /// the shading normal the interpolated vertex normals (e1 × e2 without them), both of
    /// any length. The estimator's lanes record their hits this way and normalise the group's
    /// normals together, in SIMD: lane by lane, each hit's two square roots and divisions
    /// were a chain the render loop waited on (docs/benchmarks.md).
    #[inline(always)]
    pub fn surface_before_normalising(
        &self,
        hit: &PrimHit,
        normals: Option<[Vec3; 3]>,
        uvs: Option<[Vec2; 3]>,
    ) -> SurfacePoint {
        let (b1, b2) = (hit.u.max(0.0), hit.v.max(0.0));
        let p = self.p0 + b1 * self.e1 + b2 * self.e2;
        let n = self.e1.cross(self.e2);
        let n_shading = normals.map_or(n, |corners| barycentric_mix(b1, b2, corners));
        let uv = uvs.map_or(Vec2::new(b1, b2), |corners| barycentric_mix(b1, b2, corners));
        let (dpdu, dpdv) = dp_duv(self.e1, self.e2, uvs);
        SurfacePoint { p, n_geometric: n, n_shading, uv, dpdu, dpdv, vertex_tangent: Vec4::ZERO }
    }

    pub fn bounds(&self) -> Aabb {
        Aabb::from_points(&self.vertices())
    }

    pub fn area(&self) -> f32 {
        0.5 * self.e1.cross(self.e2).length()
    }
}

/// The value at barycentric coordinates (b1, b2) of what is `corners[k]` at corner k:
/// (1 − b1 − b2)·c0 + b1·c1 + b2·c2 (vertex normals, texture coordinates).
#[inline(always)]
pub fn barycentric_mix<T>(b1: f32, b2: f32, [c0, c1, c2]: [T; 3]) -> T
where
    T: Mul<f32, Output = T> + Add<Output = T>,
{
    c0 * (1.0 - b1 - b2) + c1 * b1 + c2 * b2
}

/// A triangle hit's unit normals from [`Triangle::surface_before_normalising`]'s: the geometric
/// normal normalised; the shading normal normalised (the geometric one where that fails: a zero
/// or non-finite interpolation) and turned to the geometric normal's side. Lane by lane the
/// same operations as glam's `normalize` and `normalize_or` (times the reciprocal of the
/// length), so one lane gives the scalar code's bits.
#[inline(always)]
pub fn unit_normals<const N: usize>(geometric: &Vec3s<N>, shading: &Vec3s<N>) -> (Vec3s<N>, Vec3s<N>) {
    let n = geometric.normalize();
    let rcp = 1.0 / shading.length();
    let usable = rcp.is_finite() & rcp.gt(F32s::ZERO);
    let s = Vec3s::select(usable, &shading.scale(rcp), &n);
    // Keep the shading normal on the geometric normal's side.
    let behind = s.dot(&n).lt(F32s::ZERO);
    (n, Vec3s::select(behind, &s.neg(), &s))
}

/// `surface` with [`unit_normals`] (one lane of them).
#[inline(always)]
pub fn with_unit_normals(mut surface: SurfacePoint) -> SurfacePoint {
    let (n, s) = unit_normals::<1>(&Vec3s::splat(surface.n_geometric), &Vec3s::splat(surface.n_shading));
    (surface.n_geometric, surface.n_shading) = (n.lane(0), s.lane(0));
    surface
}

/// ∂p/∂u and ∂p/∂v of a triangle with edges `e1 = p1 − p0`, `e2 = p2 − p0`: solving
/// e1 = Δu₁ ∂p/∂u + Δv₁ ∂p/∂v, e2 = Δu₂ ∂p/∂u + Δv₂ ∂p/∂v (Cramer's rule, as Mitsuba 3's
/// mesh does). Without texture coordinates, or with degenerate ones, zero: the shading frame
/// then takes Mitsuba's fallback, the basis of the geometric normal (built only when needed).
#[inline(always)]
fn dp_duv(e1: Vec3, e2: Vec3, uvs: Option<[Vec2; 3]>) -> (Vec3, Vec3) {
    if let Some([t0, t1, t2]) = uvs {
        let (d1, d2) = (t1 - t0, t2 - t0);
        let det = d1.x * d2.y - d1.y * d2.x;
        if det != 0.0 && det.is_finite() {
            let dpdu = (d2.y * e1 - d1.y * e2) / det;
            let dpdv = (d1.x * e2 - d2.x * e1) / det;
            if dpdu.is_finite() && dpdv.is_finite() {
                return (dpdu, dpdv);
            }
        }
    }
    (Vec3::ZERO, Vec3::ZERO)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri() -> Triangle {
        Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y, Triangle::FLAT).unwrap()
    }

    #[test]
    fn hits_inside_and_misses_outside() {
        let down = -Vec3::Z;
        let hit = tri().intersect(&Ray::new(Vec3::new(0.25, 0.25, 1.0), down), 0.0, 10.0);
        let hit = hit.unwrap();
        assert!((hit.t - 1.0).abs() < 1e-6 && (hit.u - 0.25).abs() < 1e-6);
        assert!(tri().intersect(&Ray::new(Vec3::new(0.6, 0.6, 1.0), down), 0.0, 10.0).is_none());
        assert!(tri().intersect(&Ray::new(Vec3::new(-0.1, 0.2, 1.0), down), 0.0, 10.0).is_none());
        // Parallel ray in the plane of the triangle.
        assert!(tri().intersect(&Ray::new(Vec3::new(-1.0, 0.2, 0.0), Vec3::X), 0.0, 10.0).is_none());
    }

    #[test]
    fn shared_edges_are_watertight() {
        // Two triangles sharing the diagonal of a skewed quad; rays through points on the
        // diagonal (computed in f32) must hit at least one of them.
        let (a, b, c, d) =
            (Vec3::new(0.1, 0.3, 2.0), Vec3::new(10.7, 0.2, 2.5), Vec3::new(11.3, 9.1, 3.0), Vec3::new(0.4, 8.9, 2.2));
        let t1 = Triangle::new(a, b, c, Triangle::FLAT).unwrap();
        let t2 = Triangle::new(a, c, d, Triangle::FLAT).unwrap();
        let origin = Vec3::new(3.3, 4.1, -20.0);
        let mut misses = 0;
        for i in 0..=10_000 {
            let s = i as f32 / 10_000.0;
            let target = a + s * (c - a);
            let ray = Ray::new(origin, (target - origin).normalize());
            let h1 = t1.intersect(&ray, 0.0, f32::INFINITY);
            let h2 = t2.intersect(&ray, 0.0, f32::INFINITY);
            if h1.is_none() && h2.is_none() {
                misses += 1;
            }
        }
        assert_eq!(misses, 0);
    }

    #[test]
    fn degenerate_triangles_are_rejected() {
        assert!(Triangle::new(Vec3::ZERO, Vec3::X, 2.0 * Vec3::X, Triangle::FLAT).is_none());
        assert!(Triangle::new(Vec3::NAN, Vec3::X, Vec3::Y, Triangle::FLAT).is_none());
    }

    #[test]
    fn interpolated_normals_face_the_geometric_side() {
        let table = [[-Vec3::Z, -Vec3::Z, Vec3::new(0.0, 0.6, -0.8)]];
        let t = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y, 0).unwrap();
        let hit = PrimHit { t: 1.0, u: 0.2, v: 0.2 };
        let s = t.surface(&hit, &table);
        assert!(s.n_shading.dot(s.n_geometric) > 0.0);
    }

    /// The lanes' unit normals are, bit for bit, glam's `normalize` of the geometric normal
    /// and `normalize_or` of the shading one turned to its side (the scalar formulas they
    /// replace), in every lane of a group: long, short, opposite, zero, infinite and NaN
    /// shading normals among them.
    #[test]
    fn lane_unit_normals_are_glams_bit_for_bit() {
        const N: usize = 8;
        let mut x = 0x2545_f491u32;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            (x >> 8) as f32 / (1u32 << 23) as f32 * 2.0 - 1.0
        };
        let special =
            [Vec3::ZERO, Vec3::splat(f32::INFINITY), Vec3::new(f32::NAN, 0.0, 1.0), Vec3::new(1e-30, 0.0, 0.0)];
        for round in 0..200 {
            let geometric: [Vec3; N] =
                std::array::from_fn(|_| Vec3::new(next(), next(), next()) * (1.0 + 100.0 * next().abs()));
            let shading: [Vec3; N] = std::array::from_fn(|i| match (round + i) % 6 {
                0 => special[(round / 6 + i) % special.len()],
                1 => -geometric[i] + Vec3::new(next(), next(), next()) * 0.1,
                _ => Vec3::new(next(), next(), next()) * 1e3,
            });
            let (n, s) = unit_normals::<N>(&Vec3s::from_fn(|i| geometric[i]), &Vec3s::from_fn(|i| shading[i]));
            for i in 0..N {
                let want_n = geometric[i].normalize();
                let unit = shading[i].normalize_or(want_n);
                let want_s = if unit.dot(want_n) < 0.0 { -unit } else { unit };
                let bits = |v: Vec3| v.to_array().map(f32::to_bits);
                assert_eq!(bits(n.lane(i)), bits(want_n), "geometric {:?}", geometric[i]);
                assert_eq!(bits(s.lane(i)), bits(want_s), "shading {:?}", shading[i]);
            }
        }
    }
}
