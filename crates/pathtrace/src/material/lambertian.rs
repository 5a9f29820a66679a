//! `lambertian`: ideal diffuse reflection obeying Lambert's cosine law, f = albedo / π, sampled
//! with the cosine-weighted hemisphere (pdf cos θ / π), so each sample's weight is `albedo`.

use super::BsdfSample;
use crate::math::{Rgb, Vec2, Vec3, INV_PI};
use crate::wide::simd::{F32s, Ms, Vec3s};
use crate::wide::warp;

/// Lambertian reflection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lambertian {
    pub albedo: Rgb,
}

impl Lambertian {
    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
        let (wi, valid, pdf) = sample_lanes(F32s([wo.z]), F32s([u.x]), F32s([u.y]));
        valid.lane(0).then(|| BsdfSample { wi: wi.lane(0), weight: self.albedo, pdf: pdf.0[0], delta: false, eta: 1.0 })
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        self.albedo * cosine_over_pi(F32s([wo.z]), F32s([wi.z])).0[0]
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        cosine_over_pi(F32s([wo.z]), F32s([wi.z])).0[0]
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
