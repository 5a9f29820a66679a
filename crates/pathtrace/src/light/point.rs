//! Point lights: all power from one point, `intensity` I in W·sr⁻¹ per channel, equal in every
//! direction. Irradiance at distance r falls off as I·cos θ/r². A point has no area, so no ray
//! can hit it: only next-event estimation (the `mis` strategy) sees point lights.

use crate::math::{Rgb, Vec3};

/// An isotropic point light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight {
    pub position: Vec3,
    /// Radiant intensity (W·sr⁻¹ per channel).
    pub intensity: Rgb,
}

impl PointLight {
    /// Total emitted power in luminance units: 4π·I (in f64: finite for any finite intensity).
    pub fn power(&self) -> f64 {
        4.0 * std::f64::consts::PI * self.intensity.luminance_f64()
    }

    /// The unit direction and distance from `ref_p` to the light, and the radiance-like term
    /// I/r² that the integrator treats as a Dirac delta in direction.
    pub(super) fn sample(&self, ref_p: Vec3) -> Option<(Vec3, f32, Rgb)> {
        let (wi, dist, dist2) = towards(self.position, ref_p)?;
        Some((wi, dist, self.intensity * (1.0 / dist2)))
    }
}

/// The unit direction, distance and squared distance from `ref_p` to a light at `position`
/// (point and spot lights); `None` when the two coincide or are not finitely apart.
#[inline]
pub(super) fn towards(position: Vec3, ref_p: Vec3) -> Option<(Vec3, f32, f32)> {
    let d = position - ref_p;
    let dist2 = d.length_squared();
    if !(dist2 > 0.0 && dist2.is_finite()) {
        return None;
    }
    let dist = dist2.sqrt();
    Some((d / dist, dist, dist2))
}
