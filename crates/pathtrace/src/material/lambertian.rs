//! `lambertian`: ideal diffuse reflection obeying Lambert's cosine law, f = albedo / π, sampled
//! with the cosine-weighted hemisphere (pdf cos θ / π), so each sample's weight is `albedo`.

use super::BsdfSample;
use crate::math::{Rgb, Vec2, Vec3, INV_PI};
use crate::sampling::warp;

/// Lambertian reflection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lambertian {
    pub albedo: Rgb,
}

impl Lambertian {
    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let wi = warp::square_to_cosine_hemisphere(u);
        if wi.z <= 0.0 {
            return None;
        }
        Some(BsdfSample { wi, weight: self.albedo, pdf: wi.z * INV_PI, delta: false, eta: 1.0 })
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Rgb::BLACK;
        }
        self.albedo * (INV_PI * wi.z)
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 {
            return 0.0;
        }
        warp::cosine_hemisphere_pdf(wi)
    }
}
