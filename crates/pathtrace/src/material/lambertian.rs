//! `lambertian`: ideal diffuse reflection obeying Lambert's cosine law, f = albedo / π, sampled
//! with the cosine-weighted hemisphere (pdf cos θ / π), so each sample's weight is `albedo`.

use super::lanes::{LaneSamples, LaneScattering, SmoothModel};
use crate::math::{Rgb, INV_PI};
use crate::wide::simd::{F32s, Ms, Vec3s};
use crate::wide::warp;

/// Lambertian reflection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lambertian {
    pub albedo: Rgb,
}

impl SmoothModel for Lambertian {
    type Lanes<'a, const N: usize> = LambertianLanes<N>;

    /// This model in every lane of a group (the scalar methods are the one-lane instances of
    /// [`LambertianLanes`]'s).
    #[inline(always)]
    fn lanes<const N: usize>(&self) -> Self::Lanes<'_, N> {
        LambertianLanes { albedo: self.albedo.to_array().map(F32s::splat) }
    }
}

/// Lambertian models per lane, the albedo's channels as lane groups: the lane form for surfaces
/// whose frame a normal or bump map tilts per hit (the estimator's own Lambertian lanes, which
/// serve the others, call [`cosine_over_pi`] and [`sample_lanes`] directly).
#[derive(Clone, Copy, Debug)]
pub(crate) struct LambertianLanes<const N: usize> {
    pub albedo: [F32s<N>; 3],
}

impl<const N: usize> LambertianLanes<N> {
    /// Lane `i` holds `m`.
    #[inline(always)]
    pub fn set(&mut self, i: usize, m: &Lambertian) {
        for (c, a) in m.albedo.to_array().into_iter().enumerate() {
            self.albedo[c].0[i] = a;
        }
    }
}

impl<const N: usize> LaneScattering<N> for LambertianLanes<N> {
    /// A cosine-weighted direction; its weight is the albedo.
    #[inline(always)]
    fn sample(&self, wo: &Vec3s<N>, _u_lobe: F32s<N>, u1: F32s<N>, u2: F32s<N>, active: Ms<N>) -> LaneSamples<N> {
        let (wi, valid, pdf) = sample_lanes(wo.z, u1, u2);
        LaneSamples { valid: active & valid, wi, weight: self.albedo, pdf, specular: Ms::NONE, eta: F32s::ONE }
    }

    /// albedo·cos θᵢ/π and the density cos θᵢ/π where both directions are above the surface.
    #[inline(always)]
    fn eval_pdf(&self, wo: &Vec3s<N>, wi: &Vec3s<N>) -> ([F32s<N>; 3], F32s<N>) {
        let pdf = cosine_over_pi(wo.z, wi.z);
        (self.albedo.map(|a| a * pdf), pdf)
    }
}

/// cos θᵢ / π where both directions lie above the surface (local z > 0), else 0, per lane: both
/// f·cos θᵢ / albedo and the density of [`sample_lanes`]. The methods above are its one-lane
/// instance; the estimator's Lambertian lanes call it directly.
#[inline(always)]
pub fn cosine_over_pi<const N: usize>(wo_z: F32s<N>, wi_z: F32s<N>) -> F32s<N> {
    let above = wo_z.gt(F32s::ZERO) & wi_z.gt(F32s::ZERO);
    F32s::select(above, wi_z * INV_PI, F32s::ZERO)
}

/// Cosine-weighted directions (local frame) for the lanes whose `wo` lies above the surface:
/// `(wi, valid, pdf)`; each valid sample's weight f·cos/pdf is the albedo.
#[inline(always)]
pub fn sample_lanes<const N: usize>(wo_z: F32s<N>, u1: F32s<N>, u2: F32s<N>) -> (Vec3s<N>, Ms<N>, F32s<N>) {
    let wi = warp::square_to_cosine_hemisphere(u1, u2);
    let pdf = cosine_over_pi(wo_z, wi.z);
    (wi, pdf.gt(F32s::ZERO), pdf)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::lane_checks::assert_mixed_lanes_match;

    /// Each lane of a group of mixed models gives the bits of its own one-lane evaluation and
    /// sample, seen from the front and from behind.
    #[test]
    fn lanes_of_mixed_models_match_each_scalar_one() {
        const N: usize = 8;
        let model = |i: usize| Lambertian { albedo: Rgb::new(0.1 + 0.2 * (i % 4) as f32, 0.5, 0.9) };
        let mut lanes = model(0).lanes::<N>();
        for i in 0..N {
            lanes.set(i, &model(i));
        }
        assert_mixed_lanes_match(&lanes, model);
    }
}
