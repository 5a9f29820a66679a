//! Light samples for a group of lanes, computed together for every kind of light: quad,
//! triangle, disk and sphere area lights (a radiance texture is looked up per lane at the
//! sampled point), point, spot and directional lights, and the environment.
//!
//! Each lane picks its light with the scene's own selection distribution
//! ([`LightSet::pick_lanes`]) and the lanes' lights are gathered per kind (`light_picks.rs`:
//! in scenes of a few lights, the lanes that drew one light together); then the point on it,
//! the direction and the density are computed for all lanes together by
//! `light::area::sample_flat_lanes`, `sample_disk_lanes`, `sample_sphere_lanes`,
//! `PointLight::sample_lanes`, `SpotLanes::sample` and `EnvironmentLight::sample_lanes`: the
//! formulas the scalar light set runs in one lane.

use super::light_picks::{Lane, Masked, Picks, GROUPED_LIGHTS};
use super::simd::{F32s, Ms, Vec3s};
use crate::light::area::{sample_disk_lanes, sample_flat_lanes, sample_sphere_lanes, FlatSamples};
use crate::light::{EnvSampling, EnvironmentLight, Light, LightSet, LightShape, PointLight, SpotLight};
use crate::math::{Rgb, Vec3};

/// One flat light: `origin + s·e1 + t·e2`.
#[derive(Clone, Copy, Debug)]
pub(super) struct FlatLight {
    pub(super) origin: Vec3,
    pub(super) e1: Vec3,
    pub(super) e2: Vec3,
    pub(super) triangle: bool,
    pub(super) normal: Vec3,
    pub(super) area: f32,
    pub(super) radiance: Rgb,
    pub(super) two_sided: bool,
    /// Its index in the light set when a texture scales its radiance.
    pub(super) textured: Option<usize>,
}

/// One disk light: `center + a·u + b·v` over the unit disk.
#[derive(Clone, Copy, Debug)]
pub(super) struct DiskLight {
    pub(super) center: Vec3,
    pub(super) u: Vec3,
    pub(super) v: Vec3,
    pub(super) normal: Vec3,
    pub(super) area: f32,
    pub(super) radiance: Rgb,
    pub(super) two_sided: bool,
}

/// One sphere light.
#[derive(Clone, Copy, Debug)]
pub(super) struct SphereLight {
    pub(super) center: Vec3,
    pub(super) radius: f32,
    pub(super) inward: bool,
    pub(super) radiance: Rgb,
    pub(super) two_sided: bool,
}

/// A light as the lanes sample it.
#[derive(Clone, Copy, Debug)]
pub(super) enum WideLight {
    Flat(FlatLight),
    Disk(DiskLight),
    Sphere(SphereLight),
    /// The scene's environment ([`WideLights::environment`]).
    Environment,
    Point(PointLight),
    Spot(SpotLight),
    /// Towards the light (−its direction of travel), and its irradiance.
    Directional {
        wi: Vec3,
        irradiance: Rgb,
    },
}

/// The scene's lights, in their lane-parallel forms.
#[derive(Clone, Debug)]
pub struct WideLights {
    /// Each kind's lanes are computed only when a lane of the group drew one.
    lights: Vec<WideLight>,
    /// The environment, if the scene has one (a scene has at most one).
    environment: Option<EnvironmentLight>,
    /// The density the environment is sampled with (and its escaped paths weighed by).
    env_sampling: EnvSampling,
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
}

impl WideLights {
    /// The lane-parallel form of every light of `set`, an environment map sampled with the
    /// density `env_sampling` asks for.
    pub fn new(set: &LightSet, env_sampling: EnvSampling) -> Self {
        let mut environment = None;
        let lights = set
            .lights()
            .iter()
            .enumerate()
            .map(|(id, light)| {
                let l = match light {
                    Light::Area(l) => l,
                    Light::Environment(e) => {
                        environment = Some(e.clone());
                        return WideLight::Environment;
                    }
                    Light::Point(l) => return WideLight::Point(*l),
                    Light::Spot(l) => return WideLight::Spot(*l),
                    Light::Directional(l) => {
                        return WideLight::Directional { wi: -l.direction(), irradiance: l.irradiance() }
                    }
                };
                let (radiance, two_sided) = (l.emission.radiance, l.emission.two_sided);
                let (origin, e1, e2, triangle) = match l.shape {
                    LightShape::Quad(q) => (q.q, q.u, q.v, false),
                    LightShape::Triangle(t) => (t.p0, t.e1, t.e2, true),
                    LightShape::Sphere(s) => {
                        let sphere =
                            SphereLight { center: s.center, radius: s.radius, inward: s.inward, radiance, two_sided };
                        return WideLight::Sphere(sphere);
                    }
                    LightShape::Disk(d) => {
                        let (center, u, v, normal, area) = (d.center, d.u, d.v, d.normal(), l.area());
                        return WideLight::Disk(DiskLight { center, u, v, normal, area, radiance, two_sided });
                    }
                };
                let normal = e1.cross(e2).normalize();
                let area = l.area();
                let textured = l.texture().is_some().then_some(id);
                WideLight::Flat(FlatLight { origin, e1, e2, triangle, normal, area, radiance, two_sided, textured })
            })
            .collect::<Vec<_>>();
        Self { lights, environment, env_sampling }
    }

    /// The density the environment's samples are drawn with: an escaped path's MIS weight
    /// must use the same.
    #[inline(always)]
    pub fn env_sampling(&self) -> EnvSampling {
        self.env_sampling
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
        let mut picks = Picks::none();
        if let Some((ids, pmf)) = set.pick_lanes(u_select, active) {
            if self.lights.len() <= GROUPED_LIGHTS {
                // Lanes that drew the same light take it together.
                let mut left = active.bitmask();
                while left != 0 {
                    let id = ids[left.trailing_zeros() as usize];
                    let on = active & Ms::from_fn(|j| ids[j] == id);
                    left &= !on.bitmask();
                    if let Some(light) = self.lights.get(id as usize) {
                        picks.take(Masked(on), light, &pmf);
                    }
                }
            } else {
                for i in active.lanes() {
                    if let Some(light) = self.lights.get(ids[i] as usize) {
                        picks.take(Lane(i), light, &pmf);
                    }
                }
            }
        }
        let Picks {
            flat,
            textured,
            on_textured,
            disks,
            on_disk,
            spheres,
            on_sphere,
            on_environment,
            points,
            on_point,
            spots,
            on_spot,
            directional_wi,
            on_directional,
            pmf_factor,
            radiance,
            two_sided,
            picked,
        } = &picks;
        let (on_disk, on_sphere, on_environment, on_point, on_spot, on_directional) =
            (*on_disk, *on_sphere, *on_environment, *on_point, *on_spot, *on_directional);
        let (pmf_factor, on_textured, two_sided, picked) = (*pmf_factor, *on_textured, *two_sided, *picked);
        let mut d = Drawn {
            point: Vec3s::default(),
            wi: Vec3s::default(),
            dist: F32s::ZERO,
            cos_l: F32s::ZERO,
            pdf: F32s::ZERO,
            radiance: *radiance,
            no_sample: Ms::NONE,
        };
        if let Some(f) = flat {
            let FlatSamples { point, wi, dist, cos_l, pdf_area_one } = sample_flat_lanes(f, p, u1, u2);
            (d.point, d.wi, d.dist, d.cos_l, d.pdf) = (point, wi, dist, cos_l, pdf_area_one * pmf_factor);
        }
        if let Some(disks) = disks {
            let s = sample_disk_lanes(disks, p, u1, u2);
            d.take(on_disk, &s.point, &s.wi, s.dist, s.pdf * pmf_factor);
            d.cos_l = F32s::select(on_disk, s.cos_l, d.cos_l);
            d.no_sample = d.no_sample | on_disk & !s.valid;
        }
        if let Some(spheres) = spheres {
            let s = sample_sphere_lanes(spheres, p, u1, u2);
            d.take(on_sphere, &s.point, &s.wi, s.dist, s.pdf * pmf_factor);
            d.cos_l = F32s::select(on_sphere, s.normal.dot(&s.wi), d.cos_l);
        }
        if let Some(env) = self.environment.as_ref().filter(|_| on_environment.any()) {
            // At infinity along wi (the shadow ray is unoccluded if it leaves the scene); the
            // point is the scalar light set's p + wi.
            let e = env.sample_lanes(&u1, &u2, on_environment, self.env_sampling);
            d.take(on_environment, &p.add(&e.dir), &e.dir, F32s::splat(f32::INFINITY), e.pdf * pmf_factor);
            d.take_radiance(on_environment, &e.radiance);
        }
        if let Some((position, intensity)) = points {
            let sample = PointLight::sample_lanes(position, *intensity, p);
            d.take_dirac(on_point, position, sample, pmf_factor);
        }
        if let Some(spots) = spots {
            d.take_dirac(on_spot, &spots.position, spots.sample(p), pmf_factor);
        }
        if let Some(directional_wi) = directional_wi {
            // At infinity, like the environment: the point is the scalar light set's p + wi.
            let at = p.add(directional_wi);
            d.take(on_directional, &at, directional_wi, F32s::splat(f32::INFINITY), pmf_factor);
        }
        let Drawn { point, wi, dist, cos_l, pdf, mut radiance, no_sample } = d;
        // One-sided lights emit along their normal: towards p when cos θ_l = n·wi < 0.
        let faces_p = two_sided | cos_l.lt(F32s::<N>::ZERO);
        let valid =
            picked & !no_sample & faces_p & pdf.gt(F32s::<N>::ZERO) & pdf.is_finite() & dist.gt(F32s::<N>::ZERO);
        // A radiance texture scales a flat light's radiance at the sampled point: looked up for the
        // valid samples only (the others' radiance is never used).
        if let (Some(textured), Some(f)) = (textured, flat) {
            for i in (on_textured & valid).lanes() {
                let Some(Light::Area(l)) = set.lights().get(textured[i]) else { continue };
                let Some(t) = l.texture() else { continue };
                let (origin, e1, e2) = (f.origin.lane(i), f.e1.lane(i), f.e2.lane(i));
                let r = l.emission.radiance * t.at_point(point.lane(i), origin, e1, e2);
                [radiance[0].0[i], radiance[1].0[i], radiance[2].0[i]] = r.to_array();
            }
        }
        let at_infinity = on_environment | on_directional;
        LightSamples {
            point,
            wi,
            pdf,
            radiance,
            valid,
            dist_finite: !at_infinity,
            delta: on_point | on_spot | on_directional,
        }
    }
}

/// A group's light sample as it is assembled from each kind of light's lane-parallel rule:
/// each rule's result is taken into its lanes only.
struct Drawn<const N: usize> {
    point: Vec3s<N>,
    wi: Vec3s<N>,
    dist: F32s<N>,
    cos_l: F32s<N>,
    pdf: F32s<N>,
    radiance: [F32s<N>; 3],
    /// Lanes whose light's own rule found no point (disks, points, spots).
    no_sample: Ms<N>,
}

impl<const N: usize> Drawn<N> {
    /// Sets the `on` lanes' point, direction, distance and density.
    #[inline(always)]
    fn take(&mut self, on: Ms<N>, point: &Vec3s<N>, wi: &Vec3s<N>, dist: F32s<N>, pdf: F32s<N>) {
        self.point = Vec3s::select(on, point, &self.point);
        self.wi = Vec3s::select(on, wi, &self.wi);
        self.dist = F32s::select(on, dist, self.dist);
        self.pdf = F32s::select(on, pdf, self.pdf);
    }

    /// Sets the `on` lanes' radiance (lights whose radiance depends on the sample).
    #[inline(always)]
    fn take_radiance(&mut self, on: Ms<N>, radiance: &[F32s<N>; 3]) {
        for c in 0..3 {
            self.radiance[c] = F32s::select(on, radiance[c], self.radiance[c]);
        }
    }

    /// Sets the `on` lanes to the sample of a Dirac light at `position` (point and spot
    /// lights: the direction, distance, radiance and the lanes that have them): their
    /// "density" is the selection pmf alone.
    #[inline(always)]
    fn take_dirac(
        &mut self,
        on: Ms<N>,
        position: &Vec3s<N>,
        (wi, dist, radiance, found): (Vec3s<N>, F32s<N>, [F32s<N>; 3], Ms<N>),
        pmf: F32s<N>,
    ) {
        self.take(on, position, &wi, dist, pmf);
        self.take_radiance(on, &radiance);
        self.no_sample = self.no_sample | on & !found;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::light::{AreaLight, DirectionalLight, Emission, RadianceTexture};
    use crate::math::{Transform, Vec2};
    use crate::shape::{Disk, Quad, Sphere, Triangle};
    use crate::texture::{Checkerboard, Texture, UvTransform};
    use std::sync::Arc;

    /// One light of every kind, and one-sided ones seen from both sides.
    fn every_kind() -> Vec<Light> {
        let lamp = |r: f32, two_sided: bool| Emission { radiance: Rgb::new(r, 0.5 * r, 0.2 * r), two_sided };
        let quad = Quad::new(Vec3::new(-0.5, 1.0, -0.8), Vec3::new(1.5, 0.2, 0.0), Vec3::new(0.0, 0.3, 1.2)).unwrap();
        let board = Checkerboard {
            color0: Rgb::new(1.0, 0.2, 0.1),
            color1: Rgb::new(0.1, 0.4, 1.0),
            to_uv: UvTransform::IDENTITY,
        };
        let texture = RadianceTexture::on_quad(Arc::new(Texture::Checkerboard(board)));
        let textured =
            Quad::new(Vec3::new(1.0, -1.0, 0.5), Vec3::new(0.0, 0.8, 0.1), Vec3::new(0.3, 0.0, 0.9)).unwrap();
        let triangle = Triangle::new(
            Vec3::new(0.0, -1.0, -1.0),
            Vec3::new(1.0, -1.2, -0.5),
            Vec3::new(0.2, -0.6, 0.8),
            Triangle::FLAT,
        )
        .unwrap();
        let disk = Disk::new(Vec3::new(-1.0, 0.3, 0.2), Vec3::new(0.0, 0.4, 0.1), Vec3::new(0.0, -0.1, 0.4)).unwrap();
        let sphere = Sphere::new(Vec3::new(0.6, 0.4, -1.1), 0.3).unwrap();
        let area = [
            AreaLight::new(LightShape::Quad(quad), lamp(2.0, false)),
            AreaLight::new(LightShape::Quad(textured), lamp(1.5, true)).with_texture(texture).unwrap(),
            AreaLight::new(LightShape::Triangle(triangle), lamp(3.0, false)),
            AreaLight::new(LightShape::Disk(disk), lamp(4.0, false)),
            AreaLight::new(LightShape::Disk(disk), lamp(1.0, true)),
            AreaLight::new(LightShape::Sphere(sphere), lamp(5.0, false)),
        ];
        let point = PointLight { position: Vec3::new(0.3, 2.0, 0.1), intensity: Rgb::new(3.0, 2.0, 1.0) };
        let spot = SpotLight::new(&Transform::rotate_x(60.0), Rgb::splat(9.0), 50.0, 20.0).unwrap();
        let sun = DirectionalLight::new(Vec3::new(0.2, -1.0, 0.3), Rgb::new(1.0, 0.9, 0.7)).unwrap();
        let env = EnvironmentLight::constant(Rgb::new(0.1, 0.2, 0.3));
        let others = [Light::Point(point), Light::Spot(spot), Light::Directional(sun), Light::Environment(env)];
        area.into_iter().map(Light::Area).chain(others).collect()
    }

    /// Every lane of a group gets the scalar light set's sample from its own numbers: the same
    /// light, point, direction, radiance and flags, bit for bit, and the same density up to
    /// the order of one product (a flat light's density is r²/|cos θ_l| · (pmf / A) here and
    /// (r²/|cos θ_l| / A) · pmf in the set).
    ///
    /// Ten lights, picked lane by lane through the selection's search, and two sets of eight
    /// that cover every kind between them, picked in SIMD (`Distribution1D::sample_lanes`).
    #[test]
    fn lanes_of_every_light_kind_match_the_scalar_light_set() {
        let all = every_kind();
        let n = all.len();
        assert!(n > 8, "the whole set must take the per-lane search");
        for lights in [all.clone(), all[..8].to_vec(), all[n - 8..].to_vec()] {
            lanes_match_the_scalar_light_set(&LightSet::new(lights, 3.0));
        }
    }

    fn lanes_match_the_scalar_light_set(set: &LightSet) {
        const N: usize = 16;
        let wide = WideLights::new(set, EnvSampling::Complete);
        let mut x = 0x2545_f491u32;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            (x >> 8) as f32 / (1u32 << 24) as f32
        };
        let mut kinds = [0usize; 2];
        for _ in 0..2000 {
            let p: [Vec3; N] =
                std::array::from_fn(|_| Vec3::new(4.0 * next() - 2.0, 4.0 * next() - 2.0, 4.0 * next() - 2.0));
            let p = Vec3s::from_fn(|i| p[i]);
            let [u_select, u1, u2] = [0; 3].map(|_| {
                let u: [f32; N] = std::array::from_fn(|_| next());
                F32s(u)
            });
            let s = wide.sample(set, &p, Ms::ALL, &u_select, u1, u2);
            for i in 0..N {
                let one = set.sample(p.lane(i), u_select.0[i], Vec2::new(u1.0[i], u2.0[i]));
                // The set's sample of a light facing away has radiance 0; the lanes drop it.
                let one = one.filter(|l| l.pdf > 0.0 && !l.radiance.is_black());
                let lane = s.lane(i).filter(|l| !l.radiance.is_black());
                assert_eq!(lane.is_some(), one.is_some(), "lane {i}: {lane:?} vs {one:?}");
                let (Some(lane), Some(one)) = (lane, one) else { continue };
                kinds[usize::from(one.delta)] += 1;
                let bits = |v: Vec3| v.to_array().map(f32::to_bits);
                assert_eq!(bits(lane.point), bits(one.point), "lane {i}");
                assert_eq!(bits(lane.wi), bits(one.wi), "lane {i}");
                assert_eq!(lane.radiance.to_array().map(f32::to_bits), one.radiance.to_array().map(f32::to_bits));
                assert_eq!((lane.delta, lane.at_infinity), (one.delta, one.dist.is_infinite()), "lane {i}");
                assert!((lane.pdf - one.pdf).abs() <= 1e-6 * one.pdf, "lane {i}: {} vs {}", lane.pdf, one.pdf);
            }
        }
        assert!(kinds.iter().all(|&n| n > 3000), "{kinds:?}");
    }
}
