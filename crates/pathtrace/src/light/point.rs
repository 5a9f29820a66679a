//! Point lights: all power from one point, `intensity` I in W·sr⁻¹ per channel, equal in every
//! direction. Irradiance at distance r falls off as I·cos θ/r². A point has no area, so no ray
//! can hit it: only next-event estimation (the `mis` strategy) sees point lights.

use crate::math::{Rgb, Vec3};
use crate::wide::simd::{F32s, Ms, Vec3s};

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
    /// I/r² that the integrator treats as a Dirac delta in direction: the one-lane instance of
    /// [`PointLight::sample_lanes`].
    pub(super) fn sample(&self, ref_p: Vec3) -> Option<(Vec3, f32, Rgb)> {
        let (wi, dist, radiance, valid) = Self::sample_lanes(
            &Vec3s::splat(self.position),
            self.intensity.to_array().map(F32s::splat),
            &Vec3s::<1>::splat(ref_p),
        );
        valid.lane(0).then(|| (wi.lane(0), dist.0[0], Rgb::new(radiance[0].0[0], radiance[1].0[0], radiance[2].0[0])))
    }

    /// Per lane, the unit direction, distance and I/r² from `ref_p` to a light at `position`
    /// of intensity `intensity` (the lanes' lights may differ in position), and whether the lane
    /// has a sample.
    #[inline(always)]
    pub(crate) fn sample_lanes<const N: usize>(
        position: &Vec3s<N>,
        intensity: [F32s<N>; 3],
        ref_p: &Vec3s<N>,
    ) -> (Vec3s<N>, F32s<N>, [F32s<N>; 3], Ms<N>) {
        let (wi, dist, dist2, valid) = towards_lanes(position, ref_p);
        let inv = 1.0 / dist2;
        (wi, dist, intensity.map(|i| i * inv), valid)
    }
}

/// The unit direction, distance and squared distance from `ref_p` to a light at `position`
/// per lane (point and spot lights), with the lanes that have them: the two points differ and
/// are finitely apart.
#[inline(always)]
pub(super) fn towards_lanes<const N: usize>(
    position: &Vec3s<N>,
    ref_p: &Vec3s<N>,
) -> (Vec3s<N>, F32s<N>, F32s<N>, Ms<N>) {
    let d = position.sub(ref_p);
    let dist2 = d.dot(&d);
    let valid = dist2.gt(F32s::ZERO) & dist2.is_finite();
    let dist = dist2.sqrt();
    let wi = Vec3s { x: d.x / dist, y: d.y / dist, z: d.z / dist };
    (wi, dist, dist2, valid)
}
