//! The environment: radiance arriving from infinitely far away along every direction that
//! leaves the scene. Today it is constant (Mitsuba's `constant` emitter); an environment map
//! only has to change [`EnvironmentLight::radiance`], [`EnvironmentLight::sample`] and
//! [`EnvironmentLight::pdf`].
//!
//! Sampling: directions uniform over the whole sphere, pdf 1/(4π) (Pharr et al., pbrt-v4
//! §12.5.1 `UniformInfiniteLight`): it covers transmission through glass as well as reflection,
//! and for a constant environment the bsdf-sampled direction is as good, which MIS exploits.

use crate::math::{Rgb, Vec2, Vec3, INV_4PI, PI};
use crate::sampling::warp;

/// Light arriving from infinity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnvironmentLight {
    /// Radiance of every direction (W·sr⁻¹·m⁻² per channel).
    pub radiance: Rgb,
}

impl EnvironmentLight {
    /// Radiance arriving along `-dir`, i.e. seen when looking along the unit direction `dir`.
    #[inline(always)]
    pub fn radiance(&self, _dir: Vec3) -> Rgb {
        self.radiance
    }

    /// A direction towards the environment, uniform over the sphere.
    pub fn sample(&self, u: Vec2) -> Vec3 {
        warp::square_to_uniform_sphere(u)
    }

    /// Solid-angle density of [`EnvironmentLight::sample`].
    pub fn pdf(&self, _dir: Vec3) -> f32 {
        INV_4PI
    }

    /// Power reaching a scene bounded by a sphere of radius `scene_radius`, in luminance
    /// units: π r² · 4π · L (pbrt-v4 `UniformInfiniteLight::Phi`), used to pick it among lights.
    pub fn power(&self, scene_radius: f32) -> f32 {
        PI * scene_radius * scene_radius * 4.0 * PI * self.radiance.luminance()
    }
}
