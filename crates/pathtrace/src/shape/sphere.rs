//! Spheres `|p - c|² = r²`, and ellipsoids (spheres under a non-uniform transform, intersected
//! in object space).

use super::{PrimHit, Shape, SurfacePoint};
use crate::math::{Aabb, Ray, Transform, Vec2, Vec3, Vec4, PI};
use crate::wide::simd::{F32s, Ms, Vec3s};

/// A sphere, with outward normals unless `inward` (Mitsuba's `flip_normals`: the front of a
/// one-sided material or light is then the inside, as for a sky dome around a scene).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    pub center: Vec3,
    pub radius: f32,
    pub inward: bool,
}

impl Sphere {
    /// `None` unless the radius is positive and everything finite. Normals point outward.
    pub fn new(center: Vec3, radius: f32) -> Option<Self> {
        (radius > 0.0 && radius.is_finite() && center.is_finite()).then_some(Self { center, radius, inward: false })
    }

    /// The nearest hit with t ∈ [t_min, t_max]: the one-lane instance of [`Sphere::hits`].
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<PrimHit> {
        let (o, d) = (Vec3s::<1>::splat(ray.origin), Vec3s::<1>::splat(ray.dir));
        let (hit, t) = self.hits(&o, &d, F32s::splat(t_min), F32s::splat(t_max));
        hit.lane(0).then_some(PrimHit { t: t.0[0], u: 0.0, v: 0.0 })
    }

    /// [`sphere_hits`] for this sphere.
    #[inline(always)]
    pub fn hits<const N: usize>(&self, o: &Vec3s<N>, d: &Vec3s<N>, t_min: F32s<N>, t_max: F32s<N>) -> (Ms<N>, F32s<N>) {
        sphere_hits(&Vec3s::splat(self.center), F32s::splat(self.radius), o, d, t_min, t_max)
    }

    /// The surface point and unit normal where a ray met the sphere at `p_raw`: the point is
    /// re-projected onto the surface to cut the intersection's rounding error.
    #[inline(always)]
    pub fn point_and_normal(&self, p_raw: Vec3) -> (Vec3, Vec3) {
        let out = ((p_raw - self.center) / self.radius).normalize_or(Vec3::Z);
        (self.center + out * self.radius, if self.inward { -out } else { out })
    }

    // Inlined so that the SIMD kernels' hit records run it as AVX code: out of line it was
    // baseline x86-64 code, called per lane with a `vzeroupper` on each side.
    #[inline(always)]
    pub fn surface(&self, ray: &Ray, hit: &PrimHit) -> SurfacePoint {
        let (p, n) = self.point_and_normal(ray.at(hit.t));
        // The parameterisation is the outward direction's whichever way the normal faces (as
        // Mitsuba's flip_normals turns only the normal).
        let out = if self.inward { -n } else { n };
        let (dpdu, dpdv) = sphere_dp_duv(out);
        SurfacePoint {
            p,
            n_geometric: n,
            n_shading: n,
            uv: sphere_uv(out),
            dpdu: dpdu * self.radius,
            dpdv: dpdv * self.radius,
            vertex_tangent: Vec4::ZERO,
        }
    }

    pub fn bounds(&self) -> Aabb {
        Aabb::new(self.center - Vec3::splat(self.radius), self.center + Vec3::splat(self.radius))
    }

    pub fn area(&self) -> f32 {
        4.0 * PI * self.radius * self.radius
    }

    pub(super) fn transformed(&self, t: &Transform) -> Shape {
        match t.uniform_scale() {
            Some(s) => Shape::Sphere(Sphere { center: t.point(self.center), radius: self.radius * s, ..*self }),
            None => Shape::Ellipsoid(Ellipsoid {
                to_world: Box::new(
                    Transform::scale(Vec3::splat(self.radius))
                        .unwrap_or_default()
                        .then(&Transform::translate(self.center))
                        .then(t),
                ),
                inward: self.inward,
            }),
        }
    }
}

/// Solves |o + t d - c|² = r² for the nearest root in [t_min, t_max], for `N` rays and spheres
/// at once (the BVH's one-ray test, the brute-force test of small scenes in `wide::geometry` and
/// sphere-light sampling share it). Both roots are tried, so rays starting inside the sphere
/// hit its far side. Uses the half-b form and the cancellation-free quadratic of Press et al.
/// (Numerical Recipes §5.6).
#[inline(always)]
pub(crate) fn sphere_hits<const N: usize>(
    center: &Vec3s<N>,
    radius: F32s<N>,
    o: &Vec3s<N>,
    d: &Vec3s<N>,
    t_min: F32s<N>,
    t_max: F32s<N>,
) -> (Ms<N>, F32s<N>) {
    let oc = o.sub(center);
    let a = d.dot(d);
    let half_b = oc.dot(d);
    // c = |oc|² - r², computed as (|oc| - r)(|oc| + r) for accuracy near the surface.
    let oc_len = oc.length();
    let c = (oc_len - radius) * (oc_len + radius);
    // Discriminant as r² - |oc - (oc·d̂)d̂|², which avoids cancellation for distant spheres
    // (Haines et al., "Precision Improvements for Ray/Sphere Intersection", Ray Tracing Gems 2019).
    let perp = oc.sub(&d.scale(half_b / a));
    let disc = a * (radius * radius - perp.dot(&perp));
    let real = disc.ge(F32s::ZERO);
    let sq = disc.max(F32s::ZERO).sqrt();
    let q = -(half_b + sq.copysign(half_b));
    let nonzero = !q.eq(F32s::ZERO);
    let t0 = F32s::select(nonzero, q / a, F32s::ZERO);
    let t1 = F32s::select(nonzero, c / q, F32s::ZERO);
    let (near, far) = (t0.min(t1), t0.max(t1));
    let near_in = near.ge(t_min) & near.le(t_max);
    let far_in = far.ge(t_min) & far.le(t_max);
    (real & (near_in | far_in), F32s::select(near_in, near, far))
}

/// (u, v) = (φ / 2π, θ / π) with θ from +y, the usual lat-long parameterisation.
fn sphere_uv(n: Vec3) -> Vec2 {
    let phi = (-n.z).atan2(n.x) + PI;
    let theta = (-n.y).clamp(-1.0, 1.0).acos();
    Vec2::new(phi / (2.0 * PI), theta / PI)
}

/// ∂n/∂u and ∂n/∂v of [`sphere_uv`]'s parameterisation: with φ = atan2(−n.z, n.x), θ = acos(−n.y)
/// and ρ = sin θ, n = (ρ cos φ, −cos θ, −ρ sin φ), so ∂n/∂φ = (n.z, 0, −n.x) (u = φ/2π: times 2π)
/// and ∂n/∂θ = (n.x·cos θ/ρ, ρ, n.z·cos θ/ρ) (v = θ/π: times π); both zero at the poles, where
/// the shading frame falls back to the normal's own basis. Keep it in step with `sphere_uv`.
fn sphere_dp_duv(n: Vec3) -> (Vec3, Vec3) {
    let rho = (n.x * n.x + n.z * n.z).sqrt();
    let dpdu = Vec3::new(n.z, 0.0, -n.x) * (2.0 * PI);
    if rho == 0.0 {
        return (dpdu, Vec3::ZERO);
    }
    let cos_theta = -n.y;
    let dpdv = Vec3::new(n.x * cos_theta / rho, rho, n.z * cos_theta / rho) * PI;
    (dpdu, dpdv)
}

/// A unit sphere at the origin placed by an arbitrary affine transform (boxed: it is rare, and
/// keeping it out of line keeps every other shape small).
#[derive(Clone, Debug, PartialEq)]
pub struct Ellipsoid {
    pub to_world: Box<Transform>,
    /// Normals point inward (see [`Sphere::inward`]).
    pub inward: bool,
}

impl Ellipsoid {
    const UNIT: Sphere = Sphere { center: Vec3::ZERO, radius: 1.0, inward: false };

    fn object_ray(&self, ray: &Ray) -> Ray {
        let inv = &self.to_world.inverse;
        Ray::new(inv.transform_point3(ray.origin), inv.transform_vector3(ray.dir))
    }

    /// Intersects in object space; `t` is unchanged by an affine map of the ray.
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<PrimHit> {
        Self::UNIT.intersect(&self.object_ray(ray), t_min, t_max)
    }

    // Inlined so that the SIMD kernels' hit records run it as AVX code: out of line it was
    // baseline x86-64 code, called per lane with a `vzeroupper` on each side.
    #[inline(always)]
    pub fn surface(&self, ray: &Ray, hit: &PrimHit) -> SurfacePoint {
        let local = Self::UNIT.surface(&self.object_ray(ray), hit);
        let n = self.to_world.normal(if self.inward { -local.n_geometric } else { local.n_geometric });
        SurfacePoint {
            p: self.to_world.point(local.p),
            n_geometric: n,
            n_shading: n,
            uv: local.uv,
            dpdu: self.to_world.vector(local.dpdu),
            dpdv: self.to_world.vector(local.dpdv),
            vertex_tangent: Vec4::ZERO,
        }
    }

    pub fn bounds(&self) -> Aabb {
        let corners = (0..8).map(|i| {
            let c = Vec3::new(
                if i & 1 == 0 { -1.0 } else { 1.0 },
                if i & 2 == 0 { -1.0 } else { 1.0 },
                if i & 4 == 0 { -1.0 } else { 1.0 },
            );
            self.to_world.point(c)
        });
        corners.fold(Aabb::EMPTY, Aabb::grow)
    }

    pub(super) fn transformed(&self, t: &Transform) -> Ellipsoid {
        Ellipsoid { to_world: Box::new(self.to_world.then(t)), inward: self.inward }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> Sphere {
        Sphere::new(Vec3::ZERO, 1.0).unwrap()
    }

    #[test]
    fn hits_the_near_side_from_outside() {
        let ray = Ray::new(Vec3::new(0.0, 0.0, -5.0), Vec3::Z);
        let hit = unit().intersect(&ray, 0.0, f32::INFINITY).unwrap();
        assert!((hit.t - 4.0).abs() < 1e-5);
        let s = unit().surface(&ray, &hit);
        assert!((s.n_geometric - -Vec3::Z).length() < 1e-5);
    }

    #[test]
    fn rays_from_inside_hit_the_far_side() {
        let ray = Ray::new(Vec3::new(0.2, 0.1, 0.0), Vec3::X);
        let hit = unit().intersect(&ray, 0.0, f32::INFINITY).unwrap();
        let p = ray.at(hit.t);
        assert!((p.length() - 1.0).abs() < 1e-5 && p.x > 0.0);
    }

    #[test]
    fn t_range_is_respected() {
        let ray = Ray::new(Vec3::new(0.0, 0.0, -5.0), Vec3::Z);
        assert!(unit().intersect(&ray, 0.0, 3.9).is_none());
        // t_min past the near root selects the far root.
        let far = unit().intersect(&ray, 4.5, 10.0).unwrap();
        assert!((far.t - 6.0).abs() < 1e-5);
        assert!(unit().intersect(&ray, 6.5, 10.0).is_none());
    }

    #[test]
    fn grazing_rays_hit_or_miss_consistently() {
        // Tangent ray at y = 1 touches the sphere; just above misses.
        let touch = Ray::new(Vec3::new(-5.0, 1.0 - 1e-4, 0.0), Vec3::X);
        assert!(unit().intersect(&touch, 0.0, f32::INFINITY).is_some());
        let miss = Ray::new(Vec3::new(-5.0, 1.0 + 1e-4, 0.0), Vec3::X);
        assert!(unit().intersect(&miss, 0.0, f32::INFINITY).is_none());
    }

    #[test]
    fn distant_spheres_are_hit_precisely() {
        let s = Sphere::new(Vec3::new(0.0, 0.0, 1e5), 1.0).unwrap();
        let ray = Ray::new(Vec3::ZERO, Vec3::Z);
        let hit = s.intersect(&ray, 0.0, f32::INFINITY).unwrap();
        assert!((hit.t - (1e5 - 1.0)).abs() < 0.02);
    }

    #[test]
    fn ellipsoid_normals_use_the_inverse_transpose() {
        let t = Transform::scale(Vec3::new(2.0, 1.0, 1.0)).unwrap();
        let e = match unit().transformed(&t) {
            Shape::Ellipsoid(e) => e,
            other => panic!("expected an ellipsoid, got {other:?}"),
        };
        let ray = Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::X);
        let hit = e.intersect(&ray, 0.0, f32::INFINITY).unwrap();
        assert!((hit.t - 3.0).abs() < 1e-5);
        // At (sqrt2, 1/sqrt2, 0) on x²/4 + y² = 1 the normal ∝ (x/4, y) = (0.3536, 0.7071).
        let dir = Vec3::new(0.0, -1.0, 0.0);
        let from = Vec3::new(2f32.sqrt(), 5.0, 0.0);
        let r2 = Ray::new(from, dir);
        let h2 = e.intersect(&r2, 0.0, f32::INFINITY).unwrap();
        let s = e.surface(&r2, &h2);
        let expected =
            Vec3::new(0.5 * std::f32::consts::FRAC_1_SQRT_2, std::f32::consts::FRAC_1_SQRT_2, 0.0).normalize();
        assert!((s.n_geometric - expected).length() < 1e-4, "{:?}", s.n_geometric);
    }
}
