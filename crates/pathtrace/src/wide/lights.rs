//! Light samples for a group of lanes: computed together when every light is an area light of
//! constant radiance on a quad, triangle or sphere, or the environment, else gathered lane by
//! lane from the scene's light set.
//!
//! Each lane picks its light with the scene's own selection distribution ([`LightSet::pick`]),
//! then the point on it, the direction and the density are computed for all lanes together by
//! `light::area::sample_flat_lanes`, `sample_sphere_lanes` and
//! `EnvironmentLight::sample_lanes`, the formulas the scalar light set runs in one lane.

use super::simd::{F32s, Ms, Vec3s};
use crate::light::area::{sample_flat_lanes, sample_sphere_lanes, FlatLights, FlatSamples, SphereLights};
use crate::light::{EnvironmentLight, Light, LightSet, LightShape, PointLight};
use crate::math::{Rgb, Vec2, Vec3};

/// One flat light: `origin + s·e1 + t·e2`.
#[derive(Clone, Copy, Debug)]
struct FlatLight {
    origin: Vec3,
    e1: Vec3,
    e2: Vec3,
    triangle: bool,
    normal: Vec3,
    area: f32,
    radiance: Rgb,
    two_sided: bool,
}

/// One sphere light.
#[derive(Clone, Copy, Debug)]
struct SphereLight {
    center: Vec3,
    radius: f32,
    inward: bool,
    radiance: Rgb,
    two_sided: bool,
}

/// A light with a lane-parallel form.
#[derive(Clone, Copy, Debug)]
enum WideLight {
    Flat(FlatLight),
    Sphere(SphereLight),
    /// The scene's environment ([`WideLights::environment`]).
    Environment,
    Point(PointLight),
}

/// The scene's lights, when all are flat or sphere area lights, point lights or the environment.
#[derive(Clone, Debug)]
pub struct WideLights {
    lights: Vec<WideLight>,
    /// Some light is flat; some is a sphere (each form is computed only if present).
    any_flat: bool,
    any_sphere: bool,
    any_point: bool,
    /// The environment, if the scene has one (a scene has at most one).
    environment: Option<EnvironmentLight>,
}

/// `N` light samples (meaningful in `valid` lanes).
#[derive(Clone, Copy, Debug)]
pub struct LightSamples<const N: usize> {
    pub point: Vec3s<N>,
    /// Unit direction from the reference point to `point`.
    pub wi: Vec3s<N>,
    /// Solid-angle density, light selection included (for delta lights: the selection pmf).
    pub pdf: F32s<N>,
    pub radiance: [F32s<N>; 3],
    /// A point was found, with a positive finite density, on a face that emits towards the
    /// reference point.
    pub valid: Ms<N>,
    /// The sample lies at a finite distance (not the environment, seen along `wi`).
    pub dist_finite: Ms<N>,
    /// The sample comes from a Dirac light (point, spot): no other strategy can find it.
    pub delta: Ms<N>,
}

/// One lane's light sample ([`LightSamples::lane`]), for the shading of a lane on its own.
#[derive(Clone, Copy, Debug)]
pub struct LaneLightSample {
    pub point: Vec3,
    /// Unit direction from the reference point to `point`.
    pub wi: Vec3,
    /// Solid-angle density, light selection included (for delta lights: the selection pmf).
    pub pdf: f32,
    pub radiance: Rgb,
    /// The light is at infinity (the environment, a directional light): seen along `wi`.
    pub at_infinity: bool,
    pub delta: bool,
}

impl<const N: usize> LightSamples<N> {
    /// No sample in any lane.
    #[inline(always)]
    pub fn none() -> Self {
        Self {
            point: Vec3s::default(),
            wi: Vec3s::default(),
            pdf: F32s::ONE,
            radiance: [F32s::ZERO; 3],
            valid: Ms::NONE,
            dist_finite: Ms::NONE,
            delta: Ms::NONE,
        }
    }

    /// Lane `i`'s sample, if it has one.
    #[inline(always)]
    pub fn lane(&self, i: usize) -> Option<LaneLightSample> {
        self.valid.lane(i).then(|| LaneLightSample {
            point: self.point.lane(i),
            wi: self.wi.lane(i),
            pdf: self.pdf.0[i],
            radiance: Rgb::new(self.radiance[0].0[i], self.radiance[1].0[i], self.radiance[2].0[i]),
            at_infinity: !self.dist_finite.lane(i),
            delta: self.delta.lane(i),
        })
    }

    /// One sample per lane of `active` from the scene's light set (`LightSet::sample`), for
    /// lights without a lane-parallel form (points, spots, spheres, disks, environments).
    #[inline(never)]
    pub fn from_set(
        set: &LightSet,
        p: &Vec3s<N>,
        active: Ms<N>,
        u_select: &F32s<N>,
        u1: &F32s<N>,
        u2: &F32s<N>,
    ) -> Self {
        let mut out = Self::none();
        for i in active.lanes() {
            let u = Vec2::new(u1.0[i], u2.0[i]);
            let Some(ls) = set.sample(p.lane(i), u_select.0[i], u) else { continue };
            // NaN-safe: a sample without a positive density cannot be weighted.
            if ls.pdf.is_nan() || ls.pdf <= 0.0 {
                continue;
            }
            out.point.set(i, ls.point);
            out.wi.set(i, ls.wi);
            out.pdf.0[i] = ls.pdf;
            [out.radiance[0].0[i], out.radiance[1].0[i], out.radiance[2].0[i]] = ls.radiance.to_array();
            out.valid.0[i] = u32::MAX;
            out.dist_finite.0[i] = if ls.dist.is_finite() { u32::MAX } else { 0 };
            out.delta.0[i] = if ls.delta { u32::MAX } else { 0 };
        }
        out
    }
}

impl WideLights {
    /// `None` unless every light is a quad, triangle or sphere area light of constant radiance,
    /// a point light or the environment (no spot, disk or directional light, no radiance
    /// texture).
    pub fn new(set: &LightSet) -> Option<Self> {
        let mut environment = None;
        let lights = set
            .lights()
            .iter()
            .map(|light| {
                let l = match light {
                    Light::Area(l) if l.texture().is_none() => l,
                    Light::Environment(e) => {
                        environment = Some(e.clone());
                        return Some(WideLight::Environment);
                    }
                    Light::Point(l) => return Some(WideLight::Point(*l)),
                    Light::Area(_) | Light::Spot(_) | Light::Directional(_) => return None,
                };
                let (radiance, two_sided) = (l.emission.radiance, l.emission.two_sided);
                let (origin, e1, e2, triangle) = match l.shape {
                    LightShape::Quad(q) => (q.q, q.u, q.v, false),
                    LightShape::Triangle(t) => (t.p0, t.e1, t.e2, true),
                    LightShape::Sphere(s) => {
                        let sphere =
                            SphereLight { center: s.center, radius: s.radius, inward: s.inward, radiance, two_sided };
                        return Some(WideLight::Sphere(sphere));
                    }
                    LightShape::Disk(_) => return None,
                };
                let normal = e1.cross(e2).normalize();
                let area = l.area();
                Some(WideLight::Flat(FlatLight { origin, e1, e2, triangle, normal, area, radiance, two_sided }))
            })
            .collect::<Option<Vec<_>>>()?;
        let any_flat = lights.iter().any(|l| matches!(l, WideLight::Flat(_)));
        let any_sphere = lights.iter().any(|l| matches!(l, WideLight::Sphere(_)));
        let any_point = lights.iter().any(|l| matches!(l, WideLight::Point(_)));
        Some(Self { lights, any_flat, any_sphere, any_point, environment })
    }

    /// Samples a light point for each lane of `active` from `p`, with the selection numbers
    /// `u_select` and the point numbers `(u1, u2)`.
    #[inline(always)]
    pub fn sample<const N: usize>(
        &self,
        set: &LightSet,
        p: &Vec3s<N>,
        active: Ms<N>,
        u_select: &F32s<N>,
        u1: F32s<N>,
        u2: F32s<N>,
    ) -> LightSamples<N> {
        // Gather each lane's light (scalar: one table lookup per lane).
        let mut f = FlatLights {
            origin: Vec3s::default(),
            e1: Vec3s::default(),
            e2: Vec3s::default(),
            normal: Vec3s::default(),
            triangle: Ms::NONE,
        };
        let mut spheres = SphereLights { center: Vec3s::default(), radius: F32s::ZERO, inward: Ms::NONE };
        let mut on_sphere = Ms::<N>::NONE;
        let mut on_environment = Ms::<N>::NONE;
        let (mut on_point, mut point_position, mut intensity) =
            (Ms::<N>::NONE, Vec3s::<N>::default(), [F32s::<N>::ZERO; 3]);
        // The selection pmf, divided by the area for flat lights (whose density is per area).
        let mut pmf_factor = F32s::<N>::ZERO;
        let mut radiance = [F32s::<N>::ZERO; 3];
        let mut two_sided = Ms::<N>::NONE;
        let mut picked = Ms::<N>::NONE;
        for i in active.lanes() {
            let Some((id, pmf)) = set.pick(u_select.0[i]) else { continue };
            let Some(light) = self.lights.get(id) else { continue };
            let (emitted, both_faces) = match light {
                WideLight::Flat(l) => {
                    f.origin.set(i, l.origin);
                    f.e1.set(i, l.e1);
                    f.e2.set(i, l.e2);
                    f.normal.set(i, l.normal);
                    f.triangle.0[i] = if l.triangle { u32::MAX } else { 0 };
                    pmf_factor.0[i] = pmf / l.area;
                    (l.radiance, l.two_sided)
                }
                WideLight::Sphere(l) => {
                    spheres.center.set(i, l.center);
                    spheres.radius.0[i] = l.radius;
                    spheres.inward.0[i] = u32::from(l.inward).wrapping_neg();
                    on_sphere.0[i] = u32::MAX;
                    pmf_factor.0[i] = pmf;
                    (l.radiance, l.two_sided)
                }
                // Its radiance depends on the direction (below); it faces every point.
                WideLight::Environment => {
                    on_environment.0[i] = u32::MAX;
                    pmf_factor.0[i] = pmf;
                    (Rgb::BLACK, true)
                }
                // I/r², below; a point has no facing.
                WideLight::Point(l) => {
                    on_point.0[i] = u32::MAX;
                    point_position.set(i, l.position);
                    [intensity[0].0[i], intensity[1].0[i], intensity[2].0[i]] = l.intensity.to_array();
                    pmf_factor.0[i] = pmf;
                    (Rgb::BLACK, true)
                }
            };
            [radiance[0].0[i], radiance[1].0[i], radiance[2].0[i]] = emitted.to_array();
            two_sided.0[i] = if both_faces { u32::MAX } else { 0 };
            picked.0[i] = u32::MAX;
        }
        let (mut point, mut wi, mut dist, mut cos_l, mut pdf) =
            (Vec3s::default(), Vec3s::default(), F32s::ZERO, F32s::ZERO, F32s::ZERO);
        if self.any_flat {
            let FlatSamples { point: p_f, wi: wi_f, dist: dist_f, cos_l: cos_f, pdf_area_one } =
                sample_flat_lanes(&f, p, u1, u2);
            (point, wi, dist, cos_l, pdf) = (p_f, wi_f, dist_f, cos_f, pdf_area_one * pmf_factor);
        }
        if self.any_sphere && on_sphere.any() {
            let s = sample_sphere_lanes(&spheres, p, u1, u2);
            point = Vec3s::select(on_sphere, &s.point, &point);
            wi = Vec3s::select(on_sphere, &s.wi, &wi);
            dist = F32s::select(on_sphere, s.dist, dist);
            cos_l = F32s::select(on_sphere, s.normal.dot(&s.wi), cos_l);
            pdf = F32s::select(on_sphere, s.pdf * pmf_factor, pdf);
        }
        if let Some(env) = self.environment.as_ref().filter(|_| on_environment.any()) {
            // At infinity along wi (the shadow ray is unoccluded if it leaves the scene); the
            // point is the scalar light set's p + wi.
            let e = env.sample_lanes(&u1, &u2, on_environment);
            point = Vec3s::select(on_environment, &p.add(&e.dir), &point);
            wi = Vec3s::select(on_environment, &e.dir, &wi);
            dist = F32s::select(on_environment, F32s::splat(f32::INFINITY), dist);
            pdf = F32s::select(on_environment, e.pdf * pmf_factor, pdf);
            for c in 0..3 {
                radiance[c] = F32s::select(on_environment, e.radiance[c], radiance[c]);
            }
        }
        let mut no_point = Ms::<N>::NONE;
        if self.any_point && on_point.any() {
            // A Dirac delta in direction: its "density" is the selection pmf alone.
            let (wi_p, dist_p, radiance_p, found) = PointLight::sample_lanes(&point_position, intensity, p);
            point = Vec3s::select(on_point, &point_position, &point);
            wi = Vec3s::select(on_point, &wi_p, &wi);
            dist = F32s::select(on_point, dist_p, dist);
            pdf = F32s::select(on_point, pmf_factor, pdf);
            for c in 0..3 {
                radiance[c] = F32s::select(on_point, radiance_p[c], radiance[c]);
            }
            no_point = on_point & !found;
        }
        // One-sided lights emit along their normal: towards p when cos θ_l = n·wi < 0.
        let faces_p = two_sided | cos_l.lt(F32s::<N>::ZERO);
        let valid = picked & !no_point & faces_p & pdf.gt(F32s::<N>::ZERO) & pdf.is_finite() & dist.gt(F32s::<N>::ZERO);
        LightSamples { point, wi, pdf, radiance, valid, dist_finite: !on_environment, delta: on_point }
    }
}
