//! Quads (parallelograms) given by a corner `q` and edge vectors `u`, `v`: the points
//! `q + a·u + b·v` with `a, b ∈ [0,1]`. Front face along `u × v`.
//!
//! Intersection is plane first, then edge coordinates ("Ray Tracing: The Next Week" §6): with
//! n = u × v, t = n·(q − o) / n·d, and for the in-plane offset h = o + t·d − q the coordinates
//! are a = h·ũ, b = h·ṽ with the dual vectors ũ = (v × n)/|n|², ṽ = (n × u)/|n|² (so ũ·u = 1,
//! ũ·v = 0). Precomputing n, ũ, ṽ lets most misses leave after the distance test.

use super::triangle::EDGE_SLACK;
use super::{PrimHit, SurfacePoint};
use crate::math::{Aabb, Ray, Transform, Vec2, Vec3, Vec4};

/// A parallelogram (with its intersection data precomputed).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quad {
    pub q: Vec3,
    pub u: Vec3,
    pub v: Vec3,
    n: Vec3,
    u_dual: Vec3,
    v_dual: Vec3,
}

impl Quad {
    /// `None` for degenerate (zero-area) or non-finite quads.
    pub fn new(q: Vec3, u: Vec3, v: Vec3) -> Option<Self> {
        let n = u.cross(v);
        let n2 = n.length_squared();
        let ok = n2 > 0.0 && n2.is_finite() && q.is_finite() && u.is_finite() && v.is_finite();
        ok.then(|| Self { q, u, v, n, u_dual: v.cross(n) / n2, v_dual: n.cross(u) / n2 })
    }

    /// Unit normal `u × v / |u × v|`.
    pub fn normal(&self) -> Vec3 {
        self.u.cross(self.v).normalize()
    }

    pub fn area(&self) -> f32 {
        self.u.cross(self.v).length()
    }

    /// The precomputed intersection data `(q, n, ũ, ṽ)`, for the BVH's SIMD packets.
    pub(crate) fn intersection_data(&self) -> [Vec3; 4] {
        [self.q, self.n, self.u_dual, self.v_dual]
    }

    #[inline(always)]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<PrimHit> {
        let denom = self.n.dot(ray.dir);
        let t = self.n.dot(self.q - ray.origin) / denom;
        // Also rejects NaN (ray parallel to the plane, 0/0).
        if !(t >= t_min && t <= t_max) {
            return None;
        }
        let h = ray.origin + t * ray.dir - self.q;
        let a = h.dot(self.u_dual);
        let b = h.dot(self.v_dual);
        let range = -EDGE_SLACK..=1.0 + EDGE_SLACK;
        (range.contains(&a) && range.contains(&b)).then_some(PrimHit { t, u: a, v: b })
    }

    pub fn surface(&self, _ray: &Ray, hit: &PrimHit) -> SurfacePoint {
        let (a, b) = (hit.u.clamp(0.0, 1.0), hit.v.clamp(0.0, 1.0));
        let n = self.normal();
        SurfacePoint {
            p: self.q + a * self.u + b * self.v,
            n_geometric: n,
            n_shading: n,
            uv: Vec2::new(a, b),
            dpdu: self.u,
            dpdv: self.v,
            vertex_tangent: Vec4::ZERO,
        }
    }

    pub fn bounds(&self) -> Aabb {
        Aabb::from_points(&[self.q, self.q + self.u, self.q + self.v, self.q + self.u + self.v])
    }

    /// The point at edge coordinates `(a, b)`.
    pub fn point_at(&self, a: f32, b: f32) -> Vec3 {
        self.q + a * self.u + b * self.v
    }

    /// The six outward-facing faces of the axis-aligned box `[min, max]`, each transformed by
    /// `t`. `None` if the box is degenerate.
    pub fn box_faces(min: Vec3, max: Vec3, t: &Transform) -> Option<[Quad; 6]> {
        let d = max - min;
        if !(d.x > 0.0 && d.y > 0.0 && d.z > 0.0) {
            return None;
        }
        let (dx, dy, dz) = (Vec3::new(d.x, 0.0, 0.0), Vec3::new(0.0, d.y, 0.0), Vec3::new(0.0, 0.0, d.z));
        // Pairs of opposite faces (-x, +x, -y, +y, -z, +z); for each, u × v points along +axis.
        let faces = [
            (min, dy, dz),
            (Vec3::new(max.x, min.y, min.z), dy, dz),
            (min, dz, dx),
            (Vec3::new(min.x, max.y, min.z), dz, dx),
            (min, dx, dy),
            (Vec3::new(min.x, min.y, max.z), dx, dy),
        ];
        let mut out = Vec::with_capacity(6);
        for (i, (q, u, v)) in faces.into_iter().enumerate() {
            // Faces at the min side get their edges swapped so the normal points outward.
            let (u, v) = if i % 2 == 0 { (v, u) } else { (u, v) };
            out.push(Quad::new(t.point(q), t.vector(u), t.vector(v))?);
        }
        out.try_into().ok()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_inside_and_misses_outside() {
        let q = Quad::new(Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 3.0)).unwrap();
        assert!((q.normal() - -Vec3::Y).length() < 1e-6);
        let down = -Vec3::Y;
        let hit = q.intersect(&Ray::new(Vec3::new(1.5, 1.0, 2.5), down), 0.0, 10.0).unwrap();
        assert!((hit.t - 1.0).abs() < 1e-6);
        assert!(q.intersect(&Ray::new(Vec3::new(2.5, 1.0, 1.0), down), 0.0, 10.0).is_none());
        assert!(q.intersect(&Ray::new(Vec3::new(1.0, 1.0, 3.5), down), 0.0, 10.0).is_none());
        assert!((q.area() - 6.0).abs() < 1e-6);
    }

    #[test]
    fn box_faces_point_outward() {
        let faces = Quad::box_faces(Vec3::ZERO, Vec3::new(1.0, 2.0, 3.0), &Transform::IDENTITY).unwrap();
        let centre = Vec3::new(0.5, 1.0, 1.5);
        for f in faces {
            let face_centre = f.point_at(0.5, 0.5);
            assert!(f.normal().dot(face_centre - centre) > 0.0, "{f:?}");
        }
        let total: f32 = faces.iter().map(Quad::area).sum();
        assert!((total - 2.0 * (2.0 + 6.0 + 3.0)).abs() < 1e-4);
    }
}
