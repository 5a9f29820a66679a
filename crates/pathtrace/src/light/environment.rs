//! The environment: radiance arriving from infinitely far away along every direction that
//! leaves the scene — constant (Mitsuba's `constant` emitter) or an image ([`EnvMap`],
//! Mitsuba's `envmap`).
//!
//! Sampling: a constant environment samples directions uniformly over the whole sphere, pdf
//! 1/(4π) (Pharr et al., pbrt-v4 §12.5.1 `UniformInfiniteLight`): it covers transmission through
//! glass as well as reflection, and for a constant environment the bsdf-sampled direction is as
//! good, which MIS exploits. A map samples in proportion to its luminance (see envmap.rs).

use std::sync::Arc;

use super::envmap::{EnvMap, EnvSamples, EnvSampling};
use crate::math::{Rgb, Vec2, Vec3, INV_4PI};
use crate::sampling::warp;
use crate::wide::simd::{F32s, Ms, Vec3s};

/// Light arriving from infinity.
#[derive(Clone, Debug)]
pub struct EnvironmentLight {
    /// Radiance of every direction (W·sr⁻¹·m⁻² per channel) when there is no map.
    radiance: Rgb,
    /// The image, shared (cloning a scene's light set must not copy it).
    map: Option<Arc<EnvMap>>,
}

impl EnvironmentLight {
    /// The same radiance from every direction.
    pub fn constant(radiance: Rgb) -> Self {
        Self { radiance, map: None }
    }

    /// Radiance given by an environment map.
    pub fn map(map: EnvMap) -> Self {
        Self { radiance: Rgb::BLACK, map: Some(Arc::new(map)) }
    }

    /// The constant radiance, or `None` for a map.
    pub fn constant_radiance(&self) -> Option<Rgb> {
        self.map.is_none().then_some(self.radiance)
    }

    /// The environment map, if any.
    pub fn env_map(&self) -> Option<&EnvMap> {
        self.map.as_deref()
    }

    /// Radiance arriving along `-dir`, i.e. seen when looking along the unit direction `dir`.
    #[inline(always)]
    pub fn radiance(&self, dir: Vec3) -> Rgb {
        match &self.map {
            None => self.radiance,
            Some(map) => map.radiance(dir),
        }
    }

    /// [`EnvironmentLight::radiance`] and [`EnvironmentLight::pdf`] of one direction, which a map
    /// looks up once.
    #[inline(always)]
    pub fn radiance_and_pdf(&self, dir: Vec3) -> (Rgb, f32) {
        match &self.map {
            None => (self.radiance, INV_4PI),
            Some(map) => map.radiance_and_pdf(dir),
        }
    }

    /// Per lane of `active`, the radiance seen along the unit direction `dir`, and in the lanes
    /// of `with_pdf` (a subset) the density of [`EnvironmentLight::sample_lanes`] under `how`
    /// along it (0 elsewhere): the escaped paths of a lane group, looked up together.
    #[inline(always)]
    pub fn lookup_lanes<const N: usize>(
        &self,
        dir: &Vec3s<N>,
        active: Ms<N>,
        with_pdf: Ms<N>,
        how: EnvSampling,
    ) -> ([F32s<N>; 3], F32s<N>) {
        match &self.map {
            None => {
                (self.radiance.to_array().map(F32s::splat), F32s::select(with_pdf, F32s::splat(INV_4PI), F32s::ZERO))
            }
            Some(map) => map.lookup_lanes(dir, active, with_pdf, how),
        }
    }

    /// A direction towards the environment, its solid-angle density (0: discard the sample) and
    /// the radiance arriving along it.
    #[inline]
    pub fn sample(&self, u: Vec2) -> (Vec3, f32, Rgb) {
        match &self.map {
            None => (warp::square_to_uniform_sphere(u), INV_4PI, self.radiance),
            Some(map) => map.sample_with_radiance(u),
        }
    }

    /// [`EnvironmentLight::sample`] for the lanes of `active` (a map's directions computed
    /// together, a constant environment's lane by lane), a map's drawn with the density `how`
    /// asks for. A constant environment has nothing above its mean: [`EnvSampling`] leaves its
    /// uniform density as it is.
    #[inline(always)]
    pub fn sample_lanes<const N: usize>(
        &self,
        u1: &F32s<N>,
        u2: &F32s<N>,
        active: Ms<N>,
        how: EnvSampling,
    ) -> EnvSamples<N> {
        if let Some(map) = &self.map {
            return map.sample_lanes(u1, u2, active, how);
        }
        let mut out = EnvSamples { dir: Vec3s::default(), pdf: F32s::ZERO, radiance: [F32s::ZERO; 3] };
        for i in active.lanes() {
            let (dir, pdf, radiance) = self.sample(Vec2::new(u1.0[i], u2.0[i]));
            out.dir.set(i, dir);
            out.pdf.0[i] = pdf;
            [out.radiance[0].0[i], out.radiance[1].0[i], out.radiance[2].0[i]] = radiance.to_array();
        }
        out
    }

    /// Solid-angle density of [`EnvironmentLight::sample`].
    pub fn pdf(&self, dir: Vec3) -> f32 {
        match &self.map {
            None => INV_4PI,
            Some(map) => map.pdf(dir),
        }
    }

    /// Power reaching a scene bounded by a sphere of radius `scene_radius`, in luminance
    /// units: π r² · ∫ L dω (pbrt-v4 `UniformInfiniteLight::Phi` and `ImageInfiniteLight::Phi`),
    /// used to pick it among lights.
    pub fn power(&self, scene_radius: f32) -> f64 {
        let integral = match &self.map {
            None => 4.0 * std::f64::consts::PI * self.radiance.luminance_f64(),
            Some(map) => map.luminance_integral(),
        };
        std::f64::consts::PI * f64::from(scene_radius).powi(2) * integral
    }
}
