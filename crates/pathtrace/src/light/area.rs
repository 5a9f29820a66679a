//! Area lights: quads, triangles and spheres that emit a constant radiance from their front
//! face (or both faces); triangles and quads may scale it by a texture ([`RadianceTexture`]).
//!
//! Sampling densities, converted from area to solid angle at the reference point:
//! - quads, triangles and disks: uniform by area, pdf_ω = r² / (|cos θ_l| · A) (the area-to-solid-angle
//!   Jacobian; derived in docs/sampling.md);
//! - spheres seen from outside: uniform over the cone of directions they subtend,
//!   pdf_ω = 1 / (2π (1 - cos θ_max)), cos θ_max = √(1 - r²/d²) (pbrt-v3 §14.2.3);
//!   from inside: uniform by area.

use super::RadianceTexture;
use crate::math::{Ray, Rgb, Vec2, Vec3, INV_2PI, PI};
use crate::sampling::warp;
use crate::shape::{sphere_hits, Disk, Quad, Sphere, Triangle};
use crate::wide::simd::{F32s, Ms, Vec3s};
use crate::wide::warp as lanes;

/// What an object emits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Emission {
    /// Emitted radiance (W·sr⁻¹·m⁻² per channel).
    pub radiance: Rgb,
    /// Emit from both faces instead of only the front (normal) side.
    pub two_sided: bool,
}

/// The shapes that can emit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightShape {
    Quad(Quad),
    Triangle(Triangle),
    Sphere(Sphere),
    Disk(Disk),
}

/// One emissive primitive, with its area and (for flat shapes) unit normal precomputed: light
/// sampling runs at every path vertex.
#[derive(Clone, Debug, PartialEq)]
pub struct AreaLight {
    pub shape: LightShape,
    pub emission: Emission,
    area: f32,
    normal: Vec3,
    /// A texture scaling the radiance (triangles and quads only), if any.
    texture: Option<RadianceTexture>,
}

/// A point chosen on a light, with its solid-angle density at the reference point and the
/// unit direction and distance to it (computed once here, reused by the caller).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct ShapeSample {
    pub point: Vec3,
    pub normal: Vec3,
    pub wi: Vec3,
    pub dist: f32,
    pub pdf: f32,
}

/// Flat area lights (quads and triangles), one per lane: `origin + a·e1 + b·e2`, with unit
/// `normal` along e1 × e2.
pub(crate) struct FlatLights<const N: usize> {
    pub origin: Vec3s<N>,
    pub e1: Vec3s<N>,
    pub e2: Vec3s<N>,
    pub normal: Vec3s<N>,
    pub triangle: Ms<N>,
}

/// Points sampled uniformly on flat lights, seen from reference points.
pub(crate) struct FlatSamples<const N: usize> {
    pub point: Vec3s<N>,
    /// Unit direction from the reference point to `point`, and the distance.
    pub wi: Vec3s<N>,
    pub dist: F32s<N>,
    /// cos θ_l = normal · wi (negative where the front face looks at the reference point).
    pub cos_l: F32s<N>,
    /// The solid-angle density times the light's area, r² / |cos θ_l|: divide by the area (and
    /// multiply by the selection pmf) for the density.
    pub pdf_area_one: F32s<N>,
}

/// Uniform points on flat lights by area: quads at `(u1, u2)`, triangles at the square-root
/// warp (1 − √u1, u2·√u1) (`sampling::warp::square_to_uniform_triangle`), with the
/// area-to-solid-angle factor r² / |cos θ_l| (derived in docs/sampling.md). Every lane count
/// runs this one formula: the scalar light set (one lane) and the estimator's flat-light lanes.
#[inline(always)]
pub(crate) fn sample_flat_lanes<const N: usize>(
    l: &FlatLights<N>,
    ref_p: &Vec3s<N>,
    u1: F32s<N>,
    u2: F32s<N>,
) -> FlatSamples<N> {
    let (a, b) = crate::wide::warp::square_to_uniform_triangle(u1, u2);
    let a = F32s::select(l.triangle, a, u1);
    let b = F32s::select(l.triangle, b, u2);
    let point = l.origin.add(&l.e1.scale(a)).add(&l.e2.scale(b));
    let d = point.sub(ref_p);
    let dist2 = d.dot(&d);
    let dist = dist2.sqrt();
    let wi = d.scale(1.0 / dist);
    let cos_l = l.normal.dot(&wi);
    FlatSamples { point, wi, dist, cos_l, pdf_area_one: dist2 / cos_l.abs() }
}

/// Disk lights, one per lane: `center + a·u + b·v` for (a, b) on the unit disk, with unit
/// `normal` and `area`.
pub(crate) struct DiskLights<const N: usize> {
    pub center: Vec3s<N>,
    pub u: Vec3s<N>,
    pub v: Vec3s<N>,
    pub normal: Vec3s<N>,
    pub area: F32s<N>,
}

/// Points sampled uniformly on disk lights, seen from reference points.
pub(crate) struct DiskSamples<const N: usize> {
    pub point: Vec3s<N>,
    /// Unit direction from the reference point to `point`, and the distance.
    pub wi: Vec3s<N>,
    pub dist: F32s<N>,
    /// cos θ_l = normal · wi (negative where the front face looks at the reference point).
    pub cos_l: F32s<N>,
    /// Solid-angle density r² / (|cos θ_l| · A) (light selection not included).
    pub pdf: F32s<N>,
    /// Lanes with a sample: the point lies away from the reference point and the density is
    /// positive and finite.
    pub valid: Ms<N>,
}

/// Uniform points on disk lights by area: Shirley and Chiu's concentric map of `(u1, u2)`
/// (`wide::warp::square_to_uniform_disk`) onto the disk's axes, with the area-to-solid-angle
/// factor r² / (|cos θ_l| · A). The scalar light set runs it in one lane.
#[inline(always)]
pub(crate) fn sample_disk_lanes<const N: usize>(
    l: &DiskLights<N>,
    ref_p: &Vec3s<N>,
    u1: F32s<N>,
    u2: F32s<N>,
) -> DiskSamples<N> {
    let (a, b) = crate::wide::warp::square_to_uniform_disk(u1, u2);
    let point = l.center.add(&l.u.scale(a)).add(&l.v.scale(b));
    let d = point.sub(ref_p);
    let dist = d.length();
    let wi = Vec3s { x: d.x / dist, y: d.y / dist, z: d.z / dist };
    let cos_l = l.normal.dot(&wi);
    let pdf = dist * dist / (cos_l.abs() * l.area);
    let valid = dist.gt(F32s::ZERO) & pdf.gt(F32s::ZERO) & pdf.is_finite();
    DiskSamples { point, wi, dist, cos_l, pdf, valid }
}

/// Sphere lights, one per lane.
pub(crate) struct SphereLights<const N: usize> {
    pub center: Vec3s<N>,
    pub radius: F32s<N>,
    /// Spheres whose normals point inward ([`Sphere::inward`]).
    pub inward: Ms<N>,
}

/// Points sampled on sphere lights, seen from reference points.
pub(crate) struct SphereSamples<const N: usize> {
    pub point: Vec3s<N>,
    /// Unit normal at `point` (outward, or inward on an inward sphere).
    pub normal: Vec3s<N>,
    /// Unit direction from the reference point to `point`, and the distance.
    pub wi: Vec3s<N>,
    pub dist: F32s<N>,
    /// Solid-angle density (light selection not included).
    pub pdf: F32s<N>,
}

/// Points on sphere lights: from a reference point clearly outside, a direction uniform in the
/// cone the sphere subtends and the point where it meets the sphere, pdf 1/(2π(1 − cos θ_max));
/// from inside or on the surface, a point uniform by area, pdf r²/(|cos θ_l| · 4πR²) (see
/// [`sees_outside`]). Every lane count runs this one formula: the scalar light set (one lane)
/// and the estimator's light lanes (`wide::lights`).
#[inline(always)]
pub(crate) fn sample_sphere_lanes<const N: usize>(
    l: &SphereLights<N>,
    ref_p: &Vec3s<N>,
    u1: F32s<N>,
    u2: F32s<N>,
) -> SphereSamples<N> {
    let to_center = l.center.sub(ref_p);
    let d2 = to_center.dot(&to_center);
    let r2 = l.radius * l.radius;
    let outside = d2.gt(r2 * (1.0 + SURFACE_BAND));
    // Outside: the cone, cos θ_max = √(1 − R²/d²).
    let cos_max = (1.0 - (r2 / d2).min(F32s::ONE)).max(F32s::ZERO).sqrt();
    let axis = to_center.scale(1.0 / d2.sqrt());
    let dir = lanes::to_world(&axis, &lanes::square_to_uniform_cone(u1, u2, cos_max));
    let (hit, t) = sphere_hits(&l.center, l.radius, ref_p, &dir, F32s::ZERO, F32s::splat(f32::INFINITY));
    // Grazing the silhouette in f32: the nearest point on the sphere to the ray.
    let off_axis = ref_p.add(&dir.scale(to_center.dot(&dir))).sub(&l.center);
    let rcp = 1.0 / off_axis.length();
    let towards = Vec3s::select(rcp.is_finite() & rcp.gt(F32s::ZERO), &off_axis.scale(rcp), &dir.neg());
    let cone_point = Vec3s::select(hit, &ref_p.add(&dir.scale(t)), &l.center.add(&towards.scale(l.radius)));
    let cone_normal = cone_point.sub(&l.center).scale(1.0 / l.radius);
    let cone_pdf = F32s::select(cos_max.lt(F32s::ONE), INV_2PI / (1.0 - cos_max), F32s::ZERO);
    // Inside or on the surface: uniform by area.
    let area_normal = lanes::square_to_uniform_sphere(u1, u2);
    let area_point = l.center.add(&area_normal.scale(l.radius));

    let point = Vec3s::select(outside, &cone_point, &area_point);
    let normal = Vec3s::select(outside, &cone_normal, &area_normal);
    let d = point.sub(ref_p);
    let dist = d.length();
    let wi = d.scale(1.0 / dist);
    let area_pdf = dist * dist / (normal.dot(&wi).abs() * (4.0 * PI * r2));
    let normal = Vec3s::select(l.inward, &normal.neg(), &normal);
    SphereSamples { point, normal, wi, dist, pdf: F32s::select(outside, cone_pdf, area_pdf) }
}

fn area_to_solid_angle(ref_p: Vec3, point: Vec3, normal: Vec3, area: f32) -> f32 {
    let d = point - ref_p;
    let dist2 = d.length_squared();
    let cos_l = normal.dot(d).abs() / dist2.sqrt();
    if cos_l <= 0.0 || dist2 <= 0.0 {
        return 0.0;
    }
    dist2 / (cos_l * area)
}

impl AreaLight {
    pub fn new(shape: LightShape, emission: Emission) -> Self {
        let (area, normal) = match &shape {
            LightShape::Quad(q) => (q.area(), q.normal()),
            LightShape::Triangle(t) => (t.area(), t.e1.cross(t.e2).normalize()),
            LightShape::Sphere(s) => (s.area(), Vec3::ZERO),
            LightShape::Disk(d) => (d.area(), d.normal()),
        };
        Self { shape, emission, area, normal, texture: None }
    }

    /// The same triangle or quad light with its radiance scaled by `texture`; `None` for other
    /// shapes, whose sampled points carry no (u, v) here.
    pub fn with_texture(self, texture: RadianceTexture) -> Option<Self> {
        matches!(self.shape, LightShape::Triangle(_) | LightShape::Quad(_))
            .then_some(Self { texture: Some(texture), ..self })
    }

    /// The radiance texture, if any.
    pub fn texture(&self) -> Option<&RadianceTexture> {
        self.texture.as_ref()
    }

    /// The radiance averaged over the texture (the constant radiance without one): what
    /// selection by power weighs. Any positive weight keeps the estimator unbiased.
    fn mean_radiance(&self) -> Rgb {
        match &self.texture {
            None => self.emission.radiance,
            Some(t) => self.emission.radiance * t.texture.mean(),
        }
    }

    pub fn area(&self) -> f32 {
        self.area
    }

    /// Total emitted power in luminance units: L·A·π per emitting face (in f64: finite for any
    /// finite radiance and area).
    pub fn power(&self) -> f64 {
        let faces = if self.emission.two_sided { 2.0 } else { 1.0 };
        self.mean_radiance().luminance_f64() * f64::from(self.area()) * std::f64::consts::PI * faces
    }

    /// Radiance leaving a point with geometric normal `n` and texture coordinates `uv` (what a
    /// hit reports) in direction `w`.
    #[inline(always)]
    pub fn emitted(&self, n: Vec3, w: Vec3, uv: Vec2) -> Rgb {
        if !(self.emission.two_sided || n.dot(w) > 0.0) {
            return Rgb::BLACK;
        }
        match &self.texture {
            None => self.emission.radiance,
            Some(t) => self.emission.radiance * t.texture.eval(uv),
        }
    }

    /// Radiance leaving the light's point `p` (a sampled point: its uv is found from where it
    /// lies on the triangle or quad) with geometric normal `n` in direction `w`.
    #[inline(always)]
    pub fn emitted_at_point(&self, p: Vec3, n: Vec3, w: Vec3) -> Rgb {
        if !(self.emission.two_sided || n.dot(w) > 0.0) {
            return Rgb::BLACK;
        }
        match (&self.texture, &self.shape) {
            (Some(t), LightShape::Triangle(tri)) => self.emission.radiance * t.at_point(p, tri.p0, tri.e1, tri.e2),
            (Some(t), LightShape::Quad(q)) => self.emission.radiance * t.at_point(p, q.q, q.u, q.v),
            _ => self.emission.radiance,
        }
    }

    #[inline(always)]
    pub(super) fn sample(&self, ref_p: Vec3, u: Vec2) -> Option<ShapeSample> {
        match &self.shape {
            LightShape::Quad(q) => self.sample_flat(ref_p, q.q, q.u, q.v, false, u),
            LightShape::Triangle(t) => self.sample_flat(ref_p, t.p0, t.e1, t.e2, true, u),
            LightShape::Sphere(s) => sample_sphere(s, ref_p, u),
            LightShape::Disk(d) => self.sample_disk(ref_p, d, u),
        }
    }

    /// A disk: the one-lane instance of [`sample_disk_lanes`].
    #[inline(always)]
    fn sample_disk(&self, ref_p: Vec3, d: &Disk, u: Vec2) -> Option<ShapeSample> {
        let one = Vec3s::<1>::splat;
        let l = DiskLights {
            center: one(d.center),
            u: one(d.u),
            v: one(d.v),
            normal: one(self.normal),
            area: F32s([self.area]),
        };
        let s = sample_disk_lanes(&l, &one(ref_p), F32s([u.x]), F32s([u.y]));
        s.valid.lane(0).then(|| ShapeSample {
            point: s.point.lane(0),
            normal: self.normal,
            wi: s.wi.lane(0),
            dist: s.dist.0[0],
            pdf: s.pdf.0[0],
        })
    }

    /// A quad or triangle: the one-lane instance of [`sample_flat_lanes`].
    #[inline(always)]
    fn sample_flat(
        &self,
        ref_p: Vec3,
        origin: Vec3,
        e1: Vec3,
        e2: Vec3,
        triangle: bool,
        u: Vec2,
    ) -> Option<ShapeSample> {
        let one = Vec3s::<1>::splat;
        let tri = if triangle { Ms::ALL } else { Ms::NONE };
        let f = FlatLights { origin: one(origin), e1: one(e1), e2: one(e2), normal: one(self.normal), triangle: tri };
        let s = sample_flat_lanes(&f, &one(ref_p), F32s([u.x]), F32s([u.y]));
        let pdf = s.pdf_area_one.0[0] / self.area;
        (s.dist.0[0] > 0.0 && pdf > 0.0 && pdf.is_finite()).then(|| ShapeSample {
            point: s.point.lane(0),
            normal: self.normal,
            wi: s.wi.lane(0),
            dist: s.dist.0[0],
            pdf,
        })
    }

    /// Density (solid angle at `ref_p`) with which [`AreaLight::sample`] picks the surface
    /// point `p` (normal `n`) — the point a ray from `ref_p` actually hit.
    #[inline(always)]
    pub(super) fn pdf_hit(&self, ref_p: Vec3, p: Vec3, n: Vec3) -> f32 {
        match &self.shape {
            LightShape::Sphere(s) => sphere_pdf(s, ref_p, p, n),
            _ => area_to_solid_angle(ref_p, p, n, self.area()),
        }
    }

    /// Density with which sampling this light produces direction `dir` from `ref_p`, summed over
    /// every point of the light along that direction (occluded or not) — what a one-sample
    /// mixture estimator needs.
    pub(super) fn pdf_direction(&self, ref_p: Vec3, dir: Vec3) -> f32 {
        let ray = Ray::new(ref_p, dir);
        match &self.shape {
            LightShape::Quad(q) => q
                .intersect(&ray, 0.0, f32::INFINITY)
                .map_or(0.0, |h| area_to_solid_angle(ref_p, ray.at(h.t), self.normal, self.area)),
            LightShape::Triangle(t) => t
                .intersect(&ray, 0.0, f32::INFINITY)
                .map_or(0.0, |h| area_to_solid_angle(ref_p, ray.at(h.t), self.normal, self.area)),
            LightShape::Disk(d) => d
                .intersect(&ray, 0.0, f32::INFINITY)
                .map_or(0.0, |h| area_to_solid_angle(ref_p, ray.at(h.t), self.normal, self.area)),
            LightShape::Sphere(s) => {
                if sees_outside(s, ref_p) {
                    let d2 = (s.center - ref_p).length_squared();
                    let cos_dir = (s.center - ref_p).normalize().dot(dir);
                    warp::uniform_cone_pdf(Vec3::new(0.0, 0.0, cos_dir), cone_cos_max(s, d2))
                } else {
                    // Inside or on the surface: area sampling, and exactly one point of the
                    // sphere lies ahead along any direction — where the ray exits.
                    exit_distance(s, &ray).map_or(0.0, |t| {
                        let p = ray.at(t);
                        area_to_solid_angle(ref_p, p, (p - s.center) / s.radius, s.area())
                    })
                }
            }
        }
    }
}

/// True when `p` is clearly outside the sphere, so the sphere is sampled by the cone it
/// subtends. Points on the surface (within rounding) count as inside and use area sampling:
/// from a point on a sphere, area sampling is exactly cosine-weighted (chord d = 2r cos θ
/// gives r²/(|cos θ_l| A) = cos θ / π), with no singularity.
fn sees_outside(s: &Sphere, p: Vec3) -> bool {
    (s.center - p).length_squared() > s.radius * s.radius * (1.0 + SURFACE_BAND)
}

/// How far beyond R² the squared distance to a sphere's centre must be for [`sees_outside`].
const SURFACE_BAND: f32 = 1e-3;

/// Distance to where a ray starting inside (or on) the sphere leaves it: the larger root.
fn exit_distance(s: &Sphere, ray: &Ray) -> Option<f32> {
    let oc = ray.origin - s.center;
    let a = ray.dir.length_squared();
    let half_b = oc.dot(ray.dir);
    let c = oc.length_squared() - s.radius * s.radius;
    let disc = half_b * half_b - a * c;
    if disc < 0.0 {
        return None;
    }
    let t = (-half_b + disc.sqrt()) / a;
    (t > 0.0).then_some(t)
}

fn cone_cos_max(s: &Sphere, dist2: f32) -> f32 {
    let sin2 = (s.radius * s.radius / dist2).min(1.0);
    (1.0 - sin2).max(0.0).sqrt()
}

/// A sphere light: the one-lane instance of [`sample_sphere_lanes`].
fn sample_sphere(s: &Sphere, ref_p: Vec3, u: Vec2) -> Option<ShapeSample> {
    let inward = if s.inward { Ms::ALL } else { Ms::NONE };
    let l = SphereLights { center: Vec3s::splat(s.center), radius: F32s([s.radius]), inward };
    let x = sample_sphere_lanes(&l, &Vec3s::splat(ref_p), F32s([u.x]), F32s([u.y]));
    let (dist, pdf) = (x.dist.0[0], x.pdf.0[0]);
    (dist > 0.0 && pdf > 0.0 && pdf.is_finite()).then(|| ShapeSample {
        point: x.point.lane(0),
        normal: x.normal.lane(0),
        wi: x.wi.lane(0),
        dist,
        pdf,
    })
}

fn sphere_pdf(s: &Sphere, ref_p: Vec3, p: Vec3, n: Vec3) -> f32 {
    if sees_outside(s, ref_p) {
        let d2 = (s.center - ref_p).length_squared();
        warp::uniform_cone_pdf(Vec3::Z, cone_cos_max(s, d2))
    } else {
        area_to_solid_angle(ref_p, p, n, s.area())
    }
}
