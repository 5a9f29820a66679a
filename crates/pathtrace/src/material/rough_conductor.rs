//! `rough_conductor`: a rough metal (Cook–Torrance microfacet reflection; Walter et al. 2007
//! eq. 20): f(wo, wi) = F(wo·m) D(m) G(wo, wi, m) / (4 cos θo cos θi), m = (wo + wi)/|wo + wi|,
//! with the conductor Fresnel term per RGB channel. Sampled through the visible normals of
//! wo, so the weight is F(wo·m) G1(wi, m) (Heitz & d'Eon 2014 eq. 4).
//!
//! With F = 1 it loses exactly the energy of light that would scatter more than once between
//! microfacets: e.g. for GGX α = 1 at normal incidence its albedo is ≈ 0.77 (tests/microfacet_bsdfs.rs).

use super::fresnel::fresnel_conductor_rgb;
use super::microfacet::{reflect_about, visible_density, Microfacet};
use super::BsdfSample;
use crate::math::{Rgb, Vec2, Vec3};

/// A rough conductor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughConductor {
    pub distribution: Microfacet,
    /// Real part of the relative index of refraction, per channel.
    pub eta: Rgb,
    /// Imaginary part (absorption), per channel.
    pub k: Rgb,
    /// Multiplies the Fresnel reflectance (1 for a physical metal).
    pub reflectance: Rgb,
}

impl RoughConductor {
    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let m = self.distribution.sample_visible(wo, u);
        let wi = reflect_about(wo, m);
        let cos_om = wo.dot(m);
        if wi.z <= 0.0 || cos_om <= 0.0 {
            return None;
        }
        let pdf = self.distribution.pdf_visible(wo, m) / (4.0 * cos_om);
        if !pdf.is_finite() || pdf <= 0.0 {
            return None;
        }
        let f = fresnel_conductor_rgb(cos_om, self.eta, self.k);
        let weight = self.reflectance * f * self.distribution.g1(wi, m);
        Some(BsdfSample { wi, weight, pdf, delta: false, eta: 1.0 })
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        self.eval_pdf(wo, wi).0
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.eval_pdf(wo, wi).1
    }

    /// `eval` and `pdf` together: the half vector, D(m) and G1(wo, m) (Beckmann's is an erf and
    /// an exp) are computed once when MIS needs both.
    #[inline]
    pub fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Rgb, f32) {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return (Rgb::BLACK, 0.0);
        }
        let m = (wo + wi).normalize();
        let cos_om = wo.dot(m);
        let d = self.distribution.d(m);
        let g1_o = self.distribution.g1(wo, m);
        let dg = d * (g1_o * self.distribution.g1(wi, m));
        // f·cos θi: the cos θi of the denominator cancels.
        let f = if dg <= 0.0 {
            Rgb::BLACK
        } else {
            self.reflectance * fresnel_conductor_rgb(cos_om, self.eta, self.k) * (dg / (4.0 * wo.z))
        };
        // Jacobian of the reflection map dωm/dωi = 1/(4 wo·m) (Walter 2007 eq. 14).
        let pdf = if cos_om <= 0.0 { 0.0 } else { visible_density(g1_o, cos_om, d, wo.z) / (4.0 * cos_om) };
        (f, pdf)
    }
}
