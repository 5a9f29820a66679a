//! `blend`: a linear mix of two models, f = (1 − w)·f₀ + w·f₁ (Mitsuba 3's `blendbsdf`; glTF's
//! metallic-roughness BRDF mixes its dielectric and metal this way by `metallic`, glTF 2.0
//! Appendix B). The weight w ∈ [0, 1] is a number or a texture's value at the hit.
//!
//! Sampling follows Mitsuba 3.9's `blendbsdf` (checked with `mi.load_dict` in `scalar_rgb`: for
//! `weight` 0.3, `sample1` ≤ 0.3 draws from `bsdf_1`, and the returned pdf and weight are the
//! blend's, not the chosen model's): one number picks model 1 with probability w (else model 0)
//! and is stretched back over [0, 1) for that model's own lobe choice; the direction drawn is
//! then weighted by the whole mixture, f(wi)/p(wi) with p = (1 − w)·p₀ + w·p₁ — the one-sample
//! mixture estimator (Veach's balance heuristic over the two models), so the density the
//! estimator's MIS sees is the same whichever model drew the direction.
//!
//! The scene stores a blend as [`Blend`] (the two models are other entries of its material
//! table); at a hit it becomes a [`Mixture`] holding both models with their textures applied.
//! Its models are opaque, continuous ones (no Dirac lobes, no dielectrics, no nested blend):
//! the scene builder refuses others.

use super::{BsdfSample, Material};
use crate::math::{Rgb, Vec2, Vec3};

/// A blend in the scene's material table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Blend {
    /// w: how much of model 1 (the rest is model 0); replaced by a texture's luminance at the
    /// hit when the blend's base slot is textured.
    pub weight: f32,
    /// The material ids of model 0 and model 1.
    pub bsdfs: [u32; 2],
}

impl Blend {
    /// True if `m` may be one of a blend's two models: an opaque model without Dirac lobes.
    pub fn accepts(m: &Material) -> bool {
        match m {
            Material::Black
            | Material::Diffuse(_)
            | Material::Lambertian(_)
            | Material::Glossy(_)
            | Material::RoughConductor(_)
            | Material::RoughPlastic(_) => true,
            Material::Null
            | Material::Mirror(_)
            | Material::Dielectric(_)
            | Material::Conductor(_)
            | Material::RoughDielectric(_)
            | Material::Plastic(_)
            | Material::ThinDielectric(_)
            | Material::Blend(_) => false,
        }
    }
}

/// A blend at one hit: its weight and both models, textures applied.
#[derive(Clone, Copy, Debug)]
pub struct Mixture {
    pub weight: f32,
    pub bsdfs: [Material; 2],
}

impl Mixture {
    /// One model chosen by `u_lobe` (model 1 with probability w), its direction weighted by the
    /// whole mixture.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let w = self.weight;
        let (chosen, u_child) = if u_lobe < w { (1, u_lobe / w) } else { (0, (u_lobe - w) / (1.0 - w)) };
        let s = self.bsdfs[chosen].sample(wo, u_child.min(ONE_MINUS_EPSILON), u)?;
        let (f, pdf) = self.eval_pdf(wo, s.wi);
        // (Also rejects a NaN density.)
        (pdf > 0.0).then(|| BsdfSample { wi: s.wi, weight: f * (1.0 / pdf), pdf, delta: false, eta: s.eta })
    }

    /// (1 − w)·f₀ + w·f₁ (times |cos θi|, as every model's `eval`).
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        self.eval_pdf(wo, wi).0
    }

    /// (1 − w)·p₀ + w·p₁.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let w = self.weight;
        let p = |k: usize| self.bsdfs[k].pdf(wo, wi);
        match (w > 0.0, w < 1.0) {
            (false, _) => p(0),
            (_, false) => p(1),
            _ => (1.0 - w) * p(0) + w * p(1),
        }
    }

    /// [`Mixture::eval`] and [`Mixture::pdf`] together; a model of weight zero is not
    /// evaluated (a weight of exactly 0 or 1 is one model, to the bit).
    pub fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Rgb, f32) {
        let w = self.weight;
        if w <= 0.0 {
            return self.bsdfs[0].eval_pdf(wo, wi);
        }
        if w >= 1.0 {
            return self.bsdfs[1].eval_pdf(wo, wi);
        }
        let (f0, p0) = self.bsdfs[0].eval_pdf(wo, wi);
        let (f1, p1) = self.bsdfs[1].eval_pdf(wo, wi);
        (f0 * (1.0 - w) + f1 * w, (1.0 - w) * p0 + w * p1)
    }

    /// True if either model's roughness is anisotropic (the frame then follows the tangent).
    pub fn is_anisotropic(&self) -> bool {
        self.bsdfs.iter().any(Material::is_anisotropic)
    }
}

/// The largest f32 below 1: a stretched lobe number stays in [0, 1).
const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::{Lambertian, Microfacet, MicrofacetKind, RoughConductor};

    fn max_abs(c: Rgb) -> f32 {
        c.map(f32::abs).max_component()
    }

    fn mixture(weight: f32) -> Mixture {
        let metal = Material::RoughConductor(RoughConductor {
            distribution: Microfacet::isotropic(MicrofacetKind::Ggx, 0.2),
            eta: Rgb::splat(0.0),
            k: Rgb::splat(1.0),
            reflectance: Rgb::new(0.9, 0.6, 0.3),
        });
        let base = Material::Lambertian(Lambertian { albedo: Rgb::new(0.2, 0.5, 0.7) });
        Mixture { weight, bsdfs: [base, metal] }
    }

    /// Mitsuba's convention: w picks model 1, 1 − w model 0; the ends are one model exactly.
    #[test]
    fn the_ends_are_one_model_and_the_middle_mixes_linearly() {
        let (wo, wi) = (Vec3::new(0.3, 0.1, 0.9).normalize(), Vec3::new(-0.3, -0.1, 0.9).normalize());
        let m = mixture(0.25);
        let (f0, p0) = m.bsdfs[0].eval_pdf(wo, wi);
        let (f1, p1) = m.bsdfs[1].eval_pdf(wo, wi);
        assert_eq!(mixture(0.0).eval_pdf(wo, wi), (f0, p0));
        assert_eq!(mixture(1.0).eval_pdf(wo, wi), (f1, p1));
        let (f, p) = m.eval_pdf(wo, wi);
        assert!(max_abs(f - (f0 * 0.75 + f1 * 0.25)) < 1e-6 && (p - (0.75 * p0 + 0.25 * p1)).abs() < 1e-5);
        // u_lobe below w draws from the metal (a narrow lobe around the mirror direction).
        let s = m.sample(wo, 0.1, Vec2::new(0.4, 0.6)).unwrap();
        assert!(s.wi.dot(Vec3::new(-wo.x, -wo.y, wo.z)) > 0.9, "{:?}", s.wi);
        assert!(max_abs(s.weight - m.eval(wo, s.wi) * (1.0 / m.pdf(wo, s.wi))) < 1e-5);
    }
}
