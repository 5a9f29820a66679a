//! Disks (and, after a non-uniform scale, ellipses) given by a centre `c` and two semi-axis
//! vectors `u`, `v`: the points `c + a·u + b·v` with `a² + b² ≤ 1`. Front face along `u × v`.
//! Mitsuba's `disk` is the unit disk at z = 0 facing +z (u = x̂, v = ŷ) under its `to_world`.
//!
//! Intersection is the quad's (see quad.rs): plane first, then the coordinates (a, b) of the
//! hit through the dual vectors ũ = (v × n)/|n|², ṽ = (n × u)/|n|², accepted when a² + b² ≤ 1.
//! Area π·|u × v|; uniform area sampling maps the concentric disk sample (a, b) affinely, which
//! keeps the density uniform (constant Jacobian |u × v|).

use super::triangle::EDGE_SLACK;
use super::{PrimHit, SurfacePoint};
use crate::math::{Aabb, Frame, Ray, Transform, Vec2, Vec3, Vec4, INV_2PI, PI};

/// An elliptical disk with its intersection data precomputed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Disk {
    pub center: Vec3,
    pub u: Vec3,
    pub v: Vec3,
    n: Vec3,
    u_dual: Vec3,
    v_dual: Vec3,
}

impl Disk {
    /// `None` for degenerate (zero-area) or non-finite disks.
    pub fn new(center: Vec3, u: Vec3, v: Vec3) -> Option<Self> {
        let n = u.cross(v);
        let n2 = n.length_squared();
        let ok = n2 > 0.0 && n2.is_finite() && center.is_finite() && u.is_finite() && v.is_finite();
        ok.then(|| Self { center, u, v, n, u_dual: v.cross(n) / n2, v_dual: n.cross(u) / n2 })
    }

    /// The round disk of `radius` around `center` facing along `normal`.
    pub fn round(center: Vec3, normal: Vec3, radius: f32) -> Option<Self> {
        let n = normal.try_normalize()?;
        // Also rejects NaN.
        if radius.is_nan() || radius <= 0.0 {
            return None;
        }
        let f = Frame::from_normal(n);
        Self::new(center, f.s * radius, f.t * radius)
    }

    /// Unit normal `u × v / |u × v|`.
    pub fn normal(&self) -> Vec3 {
        self.n.normalize()
    }

    pub fn area(&self) -> f32 {
        PI * self.n.length()
    }

    #[inline(always)]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<PrimHit> {
        let t = self.n.dot(self.center - ray.origin) / self.n.dot(ray.dir);
        // Also rejects NaN (ray parallel to the plane, 0/0).
        if !(t >= t_min && t <= t_max) {
            return None;
        }
        let h = ray.origin + t * ray.dir - self.center;
        let (a, b) = (h.dot(self.u_dual), h.dot(self.v_dual));
        (a * a + b * b <= 1.0 + 2.0 * EDGE_SLACK).then_some(PrimHit { t, u: a, v: b })
    }

    /// The surface at a hit; `uv` is (radius, angle/2π) in the disk's own coordinates, as Mitsuba.
    // Inlined so that the SIMD kernels' hit records run it as AVX code: out of line it was
    // baseline x86-64 code, called per lane with a `vzeroupper` on each side.
    #[inline(always)]
    pub fn surface(&self, _ray: &Ray, hit: &PrimHit) -> SurfacePoint {
        let n = self.normal();
        let r = (hit.u * hit.u + hit.v * hit.v).sqrt();
        let (a, b) = if r > 1.0 { (hit.u / r, hit.v / r) } else { (hit.u, hit.v) };
        let phi = b.atan2(a);
        let phi = if phi < 0.0 { phi + 2.0 * PI } else { phi };
        // u is the radius: ∂p/∂u points outwards, cos φ·u + sin φ·v (Mitsuba's disk), with
        // (cos φ, sin φ) = (a, b)/r; at the centre, the first axis.
        let dpdu = if r > 0.0 { (a * self.u + b * self.v) / r.min(1.0) } else { self.u };
        SurfacePoint {
            p: self.point_at(a, b),
            n_geometric: n,
            n_shading: n,
            uv: Vec2::new(r.min(1.0), phi * INV_2PI),
            dpdu,
            // v is the angle over 2π: ∂p/∂v = 2π·r·(−sin φ·u + cos φ·v).
            dpdv: (a * self.v - b * self.u) * (2.0 * PI),
            vertex_tangent: Vec4::ZERO,
        }
    }

    /// Tight box of the ellipse: per axis, centre ± √(u_i² + v_i²).
    pub fn bounds(&self) -> Aabb {
        let ext = (self.u * self.u + self.v * self.v).map(f32::sqrt);
        Aabb::from_points(&[self.center - ext, self.center + ext])
    }

    /// The point at disk coordinates `(a, b)`.
    pub fn point_at(&self, a: f32, b: f32) -> Vec3 {
        self.center + a * self.u + b * self.v
    }

    pub fn transformed(&self, t: &Transform) -> Option<Self> {
        Self::new(t.point(self.center), t.vector(self.u), t.vector(self.v))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_inside_misses_outside_and_parallel_rays() {
        let d = Disk::round(Vec3::new(0.0, 1.0, 0.0), Vec3::Y, 2.0).unwrap();
        assert!((d.normal() - Vec3::Y).length() < 1e-6);
        assert!((d.area() - 4.0 * PI).abs() < 1e-4);
        let down = -Vec3::Y;
        let hit = d.intersect(&Ray::new(Vec3::new(1.9, 3.0, 0.0), down), 0.0, 10.0).unwrap();
        assert!((hit.t - 2.0).abs() < 1e-6);
        // (1.5, 1.5) is inside the bounding square but outside the circle (r ≈ 2.12).
        assert!(d.intersect(&Ray::new(Vec3::new(1.5, 3.0, 1.5), down), 0.0, 10.0).is_none());
        assert!(d.intersect(&Ray::new(Vec3::new(0.0, 1.0, -5.0), Vec3::Z), 0.0, 10.0).is_none());
        // Beyond t_max, or behind the origin.
        assert!(d.intersect(&Ray::new(Vec3::new(0.0, 3.0, 0.0), down), 0.0, 1.5).is_none());
        assert!(d.intersect(&Ray::new(Vec3::new(0.0, 3.0, 0.0), -down), 0.0, 10.0).is_none());
    }

    #[test]
    fn a_non_uniform_scale_makes_an_ellipse_with_tight_bounds() {
        let unit = Disk::new(Vec3::ZERO, Vec3::X, Vec3::Y).unwrap();
        let e = unit.transformed(&Transform::scale(Vec3::new(3.0, 1.0, 1.0)).unwrap()).unwrap();
        assert!((e.area() - 3.0 * PI).abs() < 1e-4);
        let b = e.bounds();
        assert!((b.max - Vec3::new(3.0, 1.0, 0.0)).length() < 1e-6, "{b:?}");
        let ray = |x: f32, y: f32| Ray::new(Vec3::new(x, y, 1.0), -Vec3::Z);
        assert!(e.intersect(&ray(2.9, 0.0), 0.0, 2.0).is_some());
        assert!(e.intersect(&ray(0.0, 1.1), 0.0, 2.0).is_none());
        assert!(Disk::new(Vec3::ZERO, Vec3::X, Vec3::X).is_none());
        assert!(Disk::round(Vec3::ZERO, Vec3::Z, 0.0).is_none());
    }
}
