//! `plastic`: a diffuse base under a smooth dielectric coating, as Mitsuba 3's `plastic`.
//!
//! - Coating: specular reflection with the dielectric Fresnel reflectance F(cos θo) (a Dirac
//!   lobe), times `specular` (1 for physical realism).
//! - Base: f·cos θi = ρ' (1 − F(cos θo)) (1 − F(cos θi)) cos θi / (π η²), where light crosses
//!   the coating twice and radiance is compressed by 1/η²; internal reflections at the coating
//!   are summed as a geometric series: ρ' = ρ / (1 − F_dr) by default, or ρ / (1 − ρ F_dr) with
//!   `nonlinear` (colour shift from repeated bounces on the base), F_dr being the coating's
//!   internal diffuse Fresnel reflectance 2∫ F(μ, 1/η) μ dμ (Mitsuba approximates it by the
//!   d'Eon–Irving polynomial fit, accurate to 0.1%; we integrate it).
//! - Sampling: the coating with probability F·s / (F·s + (1 − F)(1 − s)), the base otherwise
//!   (cosine-weighted), with s = mean(specular) / (mean(albedo) + mean(specular)) — Mitsuba's
//!   specular sampling weight.
//!
//! The model mixes a Dirac lobe with a smooth one: `eval`/`pdf` cover only the base, which takes
//! part in light sampling; a coating sample is flagged `delta`.

use super::dielectric::fresnel_dielectric;
use super::{reflect_local, BsdfSample};
use crate::math::special::gauss_legendre;
use crate::math::{Rgb, Vec2, Vec3, INV_PI};
use crate::sampling::warp;
use crate::wide::simd::F32s;

/// A smooth plastic. Build it with [`Plastic::new`], which precomputes the coating terms.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plastic {
    pub albedo: Rgb,
    pub specular: Rgb,
    pub ior: f32,
    pub nonlinear: bool,
    /// ρ' / (π η²): the base's constant factor.
    base: Rgb,
    /// The coating's internal diffuse reflectance F_dr (kept to rebuild `base` for a textured
    /// albedo).
    internal: f32,
    specular_weight: f32,
}

/// Internal diffuse Fresnel reflectance of an interface of relative index `eta` seen from the
/// side of index 1: F_dr = 2∫₀¹ F(μ, η) μ dμ, by 64-point Gauss–Legendre on each side of the
/// critical cosine (where F has a kink).
pub(crate) fn diffuse_fresnel_reflectance(eta: f32) -> f32 {
    let f = |mu: f64| f64::from(fresnel_dielectric(mu as f32, eta).0) * mu;
    let critical = if eta < 1.0 { (1.0 - f64::from(eta * eta)).max(0.0).sqrt() } else { 0.0 };
    let rule = gauss_legendre(64);
    let integrate = |a: f64, b: f64| -> f64 {
        rule.iter().map(|(x, w)| w * f(0.5 * (a + b) + 0.5 * (b - a) * x)).sum::<f64>() * 0.5 * (b - a)
    };
    (2.0 * (integrate(0.0, critical) + integrate(critical, 1.0))) as f32
}

/// Mitsuba's specular sampling weight mean(s) / (mean(ρ) + mean(s)).
pub(crate) fn specular_sampling_weight(albedo: Rgb, specular: Rgb) -> f32 {
    let (d, s) = (albedo.average(), specular.average());
    if d + s > 0.0 {
        s / (d + s)
    } else {
        0.5
    }
}

/// ρ / (1 − F_dr) or, nonlinear, ρ / (1 − ρ F_dr), per channel.
pub(crate) fn base_albedo(albedo: Rgb, internal: f32, nonlinear: bool) -> Rgb {
    albedo.map(|a| a / (1.0 - if nonlinear { a * internal } else { internal }))
}

impl Plastic {
    pub fn new(albedo: Rgb, specular: Rgb, ior: f32, nonlinear: bool) -> Self {
        let internal = diffuse_fresnel_reflectance(1.0 / ior);
        let base = base_albedo(albedo, internal, nonlinear) * (INV_PI / (ior * ior));
        let specular_weight = specular_sampling_weight(albedo, specular);
        Self { albedo, specular, ior, nonlinear, base, internal, specular_weight }
    }

    /// The same coating over another base albedo (a textured `albedo` at one hit). The lobe
    /// sampling weight stays the one computed from the mean albedo, as in Mitsuba.
    #[inline]
    pub fn with_albedo(&self, albedo: Rgb) -> Self {
        let base = base_albedo(albedo, self.internal, self.nonlinear) * (INV_PI / (self.ior * self.ior));
        Self { albedo, base, ..*self }
    }

    /// Probability of sampling the coating for a viewer at cos θo.
    fn coating_probability(&self, f_o: f32) -> f32 {
        coating_pick_probability(f_o, 1.0 - f_o, self.specular_weight)
    }

    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let f_o = fresnel_dielectric(wo.z, self.ior).0;
        let p_coat = self.coating_probability(f_o);
        if u_lobe < p_coat {
            let weight = self.specular * (f_o / p_coat);
            return Some(BsdfSample { wi: reflect_local(wo), weight, pdf: p_coat, delta: true, eta: 1.0 });
        }
        let wi = warp::square_to_cosine_hemisphere(u);
        if wi.z <= 0.0 {
            return None;
        }
        let pdf = (1.0 - p_coat) * warp::cosine_hemisphere_pdf(wi);
        let f_i = fresnel_dielectric(wi.z, self.ior).0;
        // f cos θi / pdf with pdf = (1 − p) cos θi / π.
        let weight = self.base * (std::f32::consts::PI * (1.0 - f_o) * (1.0 - f_i) / (1.0 - p_coat));
        Some(BsdfSample { wi, weight, pdf, delta: false, eta: 1.0 })
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        self.eval_pdf(wo, wi).0
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.eval_pdf(wo, wi).1
    }

    /// `eval` and `pdf` together, sharing F(cos θo).
    #[inline]
    pub fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Rgb, f32) {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return (Rgb::BLACK, 0.0);
        }
        let f_o = fresnel_dielectric(wo.z, self.ior).0;
        let f_i = fresnel_dielectric(wi.z, self.ior).0;
        let f = self.base * ((1.0 - f_o) * (1.0 - f_i) * wi.z);
        (f, (1.0 - self.coating_probability(f_o)) * warp::cosine_hemisphere_pdf(wi))
    }
}

/// Mitsuba's lobe choice for both plastics: the coating's reflected fraction weighted by the
/// specular sampling weight, against the transmitted (diffuse) fraction weighted by its
/// complement; 0 when both vanish.
pub(super) fn coating_pick_probability(reflected: f32, transmitted: f32, specular_weight: f32) -> f32 {
    coating_pick_probability_lanes(F32s([reflected]), F32s([transmitted]), F32s([specular_weight])).0[0]
}

/// [`coating_pick_probability`] in every lane.
#[inline(always)]
pub(super) fn coating_pick_probability_lanes<const N: usize>(
    reflected: F32s<N>,
    transmitted: F32s<N>,
    specular_weight: F32s<N>,
) -> F32s<N> {
    let s = reflected * specular_weight;
    let d = transmitted * (1.0 - specular_weight);
    F32s::select((s + d).gt(F32s::ZERO), s / (s + d), F32s::ZERO)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diffuse_fresnel_reflectance_matches_published_fits() {
        for eta in [1.33f32, 1.49, 1.7] {
            // From outside: d'Eon & Irving 2011's fit in 1/η (0.1% accurate for η in [1, 2]).
            let x = 1.0 / eta;
            let external_fit = 0.919317 - 3.4793 * x + 6.75335 * x.powi(2) - 7.80989 * x.powi(3) + 4.98554 * x.powi(4)
                - 1.36881 * x.powi(5);
            let external = diffuse_fresnel_reflectance(eta);
            assert!((external - external_fit).abs() < 2e-3, "η {eta}: {external} vs {external_fit}");
            // From inside (relative index 1/η): Egan & Hilgeman 1973's fit (0.6% for η ≤ 2).
            let internal_fit = 0.0636 / x + x * (x * -1.4399 + 0.7099) + 0.6681;
            let internal = diffuse_fresnel_reflectance(x);
            assert!((internal - internal_fit).abs() < 6e-3 * internal_fit, "η {eta}: {internal} vs {internal_fit}");
        }
    }
}
