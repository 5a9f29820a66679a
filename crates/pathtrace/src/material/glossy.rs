//! `glossy`: the energy-normalised modified Phong lobe (Lafortune & Willems, "Using the Modified
//! Phong Reflectance Model for Physically Based Rendering", 1994):
//! f(wo, wi) = albedo · (n + 2)/(2π) · cosⁿ α, with α the angle between wi and the mirror
//! direction of wo. Its directional albedo never exceeds `albedo` (equal at normal incidence).
//! Sampled by the power-cosine lobe around the mirror direction, pdf (n + 1)/(2π) cosⁿ α;
//! lobe directions below the surface are rejected (that probability is lost, and eval is 0
//! there, so the estimator stays unbiased).

use super::{reflect_local, BsdfSample};
use crate::math::{Frame, Rgb, Vec2, Vec3, INV_2PI};
use crate::sampling::warp;

/// Phong glossy reflection with exponent `exponent` (higher = sharper).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Glossy {
    pub albedo: Rgb,
    pub exponent: f32,
}

impl Glossy {
    fn cos_alpha(wo: Vec3, wi: Vec3) -> f32 {
        reflect_local(wo).dot(wi).max(0.0)
    }

    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let lobe = Frame::from_normal(reflect_local(wo));
        let wi = lobe.to_world(warp::square_to_power_cosine(u, self.exponent));
        if wi.z <= 0.0 {
            return None;
        }
        let pdf = self.pdf(wo, wi);
        if pdf <= 0.0 {
            return None;
        }
        // weight = f cos θi / pdf = albedo (n+2)/(n+1) cos θi.
        let weight = self.albedo * ((self.exponent + 2.0) / (self.exponent + 1.0) * wi.z);
        Some(BsdfSample { wi, weight, pdf, delta: false, eta: 1.0 })
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Rgb::BLACK;
        }
        let c = Self::cos_alpha(wo, wi);
        self.albedo * ((self.exponent + 2.0) * INV_2PI * c.powf(self.exponent) * wi.z)
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let c = Self::cos_alpha(wo, wi);
        (self.exponent + 1.0) * INV_2PI * c.powf(self.exponent)
    }
}
