//! `diffuse`: the naive "uniform diffuse" model of early path tracers — a ray scatters uniformly
//! over the hemisphere and keeps `albedo` of its energy. As a BRDF that is
//! f(wo, wi) = albedo / (2π cos θi), so f·cos θi = albedo / 2π: the surface reflects `albedo`
//! times the *unweighted* hemispherical average of incident radiance. Unlike Lambertian it
//! ignores the cosine law (grazing light counts as much as overhead light), which is why
//! a Cornell box looks flatter with it. Sampled uniformly (pdf 1/2π), so every sample's weight is
//! exactly `albedo`.

use super::BsdfSample;
use crate::math::{Rgb, Vec2, Vec3, INV_2PI};
use crate::sampling::warp;

/// Uniform-hemisphere diffuse reflection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Diffuse {
    pub albedo: Rgb,
}

impl Diffuse {
    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let wi = warp::square_to_uniform_hemisphere(u);
        (wi.z > 0.0).then_some(BsdfSample { wi, weight: self.albedo, pdf: INV_2PI, delta: false, eta: 1.0 })
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Rgb::BLACK;
        }
        self.albedo * INV_2PI
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        INV_2PI
    }
}
