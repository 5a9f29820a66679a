//! Infinite planes `n · p = d`. Unbounded, so the BVH tests them separately; they cannot emit.

use super::{PrimHit, SurfacePoint};
use crate::math::{Frame, Ray, Transform, Vec2, Vec3, Vec4};

/// An infinite plane through `point` with unit `normal` (its front side).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    pub point: Vec3,
    pub normal: Vec3,
}

impl Plane {
    /// `None` for a zero or non-finite normal.
    pub fn new(point: Vec3, normal: Vec3) -> Option<Self> {
        let n = normal.try_normalize()?;
        point.is_finite().then_some(Self { point, normal: n })
    }

    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<PrimHit> {
        let denom = self.normal.dot(ray.dir);
        if denom.abs() < 1e-12 {
            return None; // parallel
        }
        let t = self.normal.dot(self.point - ray.origin) / denom;
        (t >= t_min && t <= t_max).then_some(PrimHit { t, u: 0.0, v: 0.0 })
    }

    pub fn surface(&self, ray: &Ray, hit: &PrimHit) -> SurfacePoint {
        let p = ray.at(hit.t);
        let f = Frame::from_normal(self.normal);
        let d = p - self.point;
        SurfacePoint {
            p,
            n_geometric: self.normal,
            n_shading: self.normal,
            uv: Vec2::new(d.dot(f.s), d.dot(f.t)),
            dpdu: f.s,
            dpdv: f.t,
            vertex_tangent: Vec4::ZERO,
        }
    }

    pub(super) fn transformed(&self, t: &Transform) -> Plane {
        Plane { point: t.point(self.point), normal: t.normal(self.normal) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_from_both_sides_and_misses_parallel_rays() {
        let p = Plane::new(Vec3::ZERO, Vec3::Y).unwrap();
        let down = Ray::new(Vec3::new(3.0, 2.0, 1.0), -Vec3::Y);
        assert!((p.intersect(&down, 0.0, f32::INFINITY).unwrap().t - 2.0).abs() < 1e-6);
        let up = Ray::new(Vec3::new(3.0, -2.0, 1.0), Vec3::Y);
        assert!(p.intersect(&up, 0.0, f32::INFINITY).is_some());
        let parallel = Ray::new(Vec3::new(0.0, 1.0, 0.0), Vec3::X);
        assert!(p.intersect(&parallel, 0.0, f32::INFINITY).is_none());
        assert!(p.intersect(&down, 0.0, 1.0).is_none());
        assert!(Plane::new(Vec3::ZERO, Vec3::ZERO).is_none());
    }
}
