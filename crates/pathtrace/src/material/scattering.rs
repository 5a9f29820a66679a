//! What the estimator's shading asks of a surface model at a hit, whether one [`Material`] or a
//! blend's [`Mixture`] of two: `integrator::shade` and its shading frame are written once over
//! this trait and compiled for each.

use super::{BsdfSample, Material, Mixture};
use crate::math::{Rgb, Vec2, Vec3};

/// A surface model as shading sees it (see [`Material`] for the conventions).
pub trait Scattering {
    fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample>;
    fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb;
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32;
    fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Rgb, f32);
    /// Only Dirac lobes: light sampling is skipped.
    fn is_delta(&self) -> bool;
    /// Some Dirac lobe that light sampling cannot reach.
    fn has_delta_lobe(&self) -> bool;
    fn is_anisotropic(&self) -> bool;
    fn is_two_sided(&self) -> bool;
}

impl Scattering for Material {
    #[inline(always)]
    fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        Material::sample(self, wo, u_lobe, u)
    }
    #[inline(always)]
    fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        Material::eval(self, wo, wi)
    }
    #[inline(always)]
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        Material::pdf(self, wo, wi)
    }
    #[inline(always)]
    fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Rgb, f32) {
        Material::eval_pdf(self, wo, wi)
    }
    fn is_delta(&self) -> bool {
        Material::is_delta(self)
    }
    fn has_delta_lobe(&self) -> bool {
        Material::has_delta_lobe(self)
    }
    fn is_anisotropic(&self) -> bool {
        Material::is_anisotropic(self)
    }
    fn is_two_sided(&self) -> bool {
        Material::is_two_sided(self)
    }
}

/// A blend's models are opaque and continuous ([`super::Blend::accepts`]).
impl Scattering for Mixture {
    fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        Mixture::sample(self, wo, u_lobe, u)
    }
    fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        Mixture::eval(self, wo, wi)
    }
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        Mixture::pdf(self, wo, wi)
    }
    fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Rgb, f32) {
        Mixture::eval_pdf(self, wo, wi)
    }
    fn is_delta(&self) -> bool {
        false
    }
    fn has_delta_lobe(&self) -> bool {
        false
    }
    fn is_anisotropic(&self) -> bool {
        Mixture::is_anisotropic(self)
    }
    fn is_two_sided(&self) -> bool {
        true
    }
}
