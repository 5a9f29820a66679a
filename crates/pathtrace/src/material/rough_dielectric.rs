//! `rough_dielectric`: rough glass (Walter et al. 2007, "Microfacet Models for Refraction
//! through Rough Surfaces"). A microfacet normal m is drawn from the visible normals of wo; the
//! path reflects about m with probability F(wo·m) and refracts through m otherwise.
//!
//! - reflection: f·cos θi = F D G / (4 |cos θo|) (eq. 20);
//! - transmission: f·cos θi = (1 − F) D G |wi·m| |wo·m| / (|cos θo| (wo·m + η wi·m)²) with η the
//!   index on wi's side over wo's side and m the generalised half vector ∝ −(wo + η wi) (eqs. 16,
//!   21). That is Walter's eq. 21 with the 1/η² radiance scaling of the smooth `dielectric`
//!   included, so that a sample's weight is G1(wi, m)/η², the smooth model's 1/η² in the limit.
//! - G is the separable Smith G1(wo)·G1(wi) (as Mitsuba 3).
//!
//! As `dielectric`, it sees both sides: z > 0 is outside (index 1), z < 0 inside (index `ior`).

use super::dielectric::fresnel_dielectric;
use super::microfacet::{reflect_about, refract_about, Microfacet};
use super::BsdfSample;
use crate::math::{Rgb, Vec2, Vec3};

/// A rough dielectric interface with interior index `ior` (exterior 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughDielectric {
    pub distribution: Microfacet,
    pub ior: f32,
    /// Colour multiplied into both lobes (white for clear glass).
    pub tint: Rgb,
}

/// Directions and indices seen from wo's side: both flipped so that wo is above (z > 0);
/// `eta` = index below / index above.
struct Oriented {
    wo: Vec3,
    sign: f32,
    eta: f32,
}

impl RoughDielectric {
    fn orient(&self, wo: Vec3) -> Oriented {
        if wo.z >= 0.0 {
            Oriented { wo, sign: 1.0, eta: self.ior }
        } else {
            Oriented { wo: -wo, sign: -1.0, eta: 1.0 / self.ior }
        }
    }

    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let o = self.orient(wo);
        let m = self.distribution.sample_visible(o.wo, u);
        let cos_om = o.wo.dot(m);
        if cos_om <= 0.0 {
            return None;
        }
        let pdf_m = self.distribution.pdf_visible(o.wo, m);
        let (f, cos_t, eta) = fresnel_dielectric(cos_om, o.eta);
        if u_lobe < f {
            let wi = reflect_about(o.wo, m);
            if wi.z <= 0.0 {
                return None;
            }
            let pdf = f * pdf_m / (4.0 * cos_om);
            let weight = self.tint * self.distribution.g1(wi, m);
            return (pdf > 0.0).then_some(BsdfSample { wi: wi * o.sign, weight, pdf, delta: false, eta: 1.0 });
        }
        let wi = refract_about(o.wo, m, cos_om, cos_t, eta);
        if wi.z >= 0.0 {
            return None;
        }
        let cos_im = wi.dot(m);
        let denom = cos_om + eta * cos_im;
        let pdf = (1.0 - f) * pdf_m * eta * eta * cos_im.abs() / (denom * denom);
        let weight = self.tint * (self.distribution.g1(wi, m) / (eta * eta));
        (pdf > 0.0).then_some(BsdfSample { wi: wi * o.sign, weight, pdf, delta: false, eta })
    }

    /// The microfacet normal joining wo and wi (both oriented), with Fresnel and the
    /// reflection flag; `None` where no microfacet normal can connect them.
    fn half_vector(&self, o: &Oriented, wi: Vec3) -> Option<(Vec3, bool)> {
        let reflect = wi.z > 0.0;
        let h = if reflect { o.wo + wi } else { o.wo + o.eta * wi };
        let m = h.normalize() * h.z.signum();
        // Neither direction may see the back of m (Walter 2007 §5.3).
        let ok = m.is_finite() && m.z > 0.0 && o.wo.dot(m) > 0.0 && wi.dot(m) * wi.z > 0.0;
        ok.then_some((m, reflect))
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        if wo.z == 0.0 || wi.z == 0.0 {
            return Rgb::BLACK;
        }
        let o = self.orient(wo);
        let wi = wi * o.sign;
        let Some((m, reflect)) = self.half_vector(&o, wi) else { return Rgb::BLACK };
        let cos_om = o.wo.dot(m);
        let (f, _, _) = fresnel_dielectric(cos_om, o.eta);
        let dg = self.distribution.d(m) * self.distribution.g(o.wo, wi, m);
        let value = if reflect {
            f * dg / (4.0 * o.wo.z)
        } else {
            let cos_im = wi.dot(m);
            let denom = cos_om + o.eta * cos_im;
            (1.0 - f) * dg * (cos_im * cos_om).abs() / (o.wo.z * denom * denom)
        };
        self.tint * value.max(0.0)
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z == 0.0 || wi.z == 0.0 {
            return 0.0;
        }
        let o = self.orient(wo);
        let wi = wi * o.sign;
        let Some((m, reflect)) = self.half_vector(&o, wi) else { return 0.0 };
        let cos_om = o.wo.dot(m);
        let (f, _, _) = fresnel_dielectric(cos_om, o.eta);
        let pdf_m = self.distribution.pdf_visible(o.wo, m);
        if reflect {
            f * pdf_m / (4.0 * cos_om)
        } else {
            // Jacobian of refraction dωm/dωi = η² |wi·m| / (wo·m + η wi·m)² (Walter 2007 eq. 17).
            let cos_im = wi.dot(m);
            let denom = cos_om + o.eta * cos_im;
            (1.0 - f) * pdf_m * o.eta * o.eta * cos_im.abs() / (denom * denom)
        }
    }
}
