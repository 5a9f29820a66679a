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

use super::dielectric::{fresnel_dielectric, fresnel_dielectric_lanes};
use super::lanes::{LaneSamples, LaneScattering, SmoothModel};
use super::reflect_local_lanes;
use crate::math::special::gauss_legendre;
use crate::math::{Rgb, INV_PI};
use crate::sampling::warp::cosine_hemisphere_pdf_lanes;
use crate::wide::simd::{F32s, Ms, Vec3s};
use crate::wide::warp as warp_lanes;

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
}

impl SmoothModel for Plastic {
    type Lanes<'a, const N: usize> = PlasticLanes<N>;

    /// This plastic in every lane of a group (the scalar methods are the one-lane instances of
    /// [`PlasticLanes`]'s).
    #[inline(always)]
    fn lanes<const N: usize>(&self) -> Self::Lanes<'_, N> {
        PlasticLanes {
            specular: self.specular.to_array().map(F32s::splat),
            base: self.base.to_array().map(F32s::splat),
            ior: F32s::splat(self.ior),
            specular_weight: F32s::splat(self.specular_weight),
        }
    }
}

/// A smooth plastic per lane (lanes can hold different ones), RGB channels as lane groups.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PlasticLanes<const N: usize> {
    pub specular: [F32s<N>; 3],
    /// ρ' / (π η²).
    pub base: [F32s<N>; 3],
    pub ior: F32s<N>,
    pub specular_weight: F32s<N>,
}

impl<const N: usize> PlasticLanes<N> {
    /// Lane `i` holds `m`.
    #[inline(always)]
    pub fn set(&mut self, i: usize, m: &Plastic) {
        for c in 0..3 {
            self.specular[c].0[i] = m.specular.to_array()[c];
            self.base[c].0[i] = m.base.to_array()[c];
        }
        self.ior.0[i] = m.ior;
        self.specular_weight.0[i] = m.specular_weight;
    }

    /// The probability of sampling the coating for a viewer whose Fresnel reflectance is `f_o`.
    #[inline(always)]
    fn coating_probability(&self, f_o: F32s<N>) -> F32s<N> {
        coating_pick_probability_lanes(f_o, 1.0 - f_o, self.specular_weight)
    }
}

impl<const N: usize> LaneScattering<N> for PlasticLanes<N> {
    /// The coating's mirror direction (a Dirac lobe, flagged `specular`) or the base's
    /// cosine-weighted one, chosen by `u_lobe`.
    #[inline(always)]
    fn sample(&self, wo: &Vec3s<N>, u_lobe: F32s<N>, u1: F32s<N>, u2: F32s<N>, active: Ms<N>) -> LaneSamples<N> {
        let zero = F32s::ZERO;
        // `!(x <= 0)` keeps the scalar rule for NaN.
        let active = active & !wo.z.le(zero);
        let f_o = fresnel_dielectric_lanes(wo.z, self.ior).0;
        let p_coat = self.coating_probability(f_o);
        let coat = u_lobe.lt(p_coat);
        let base = active & !coat;
        let diffuse = if base.any() { warp_lanes::square_to_cosine_hemisphere(u1, u2) } else { Vec3s::default() };
        let f_i = fresnel_dielectric_lanes(diffuse.z, self.ior).0;
        // The base: f·cos θi / pdf with pdf = (1 − p) cos θi / π.
        let base_scale = std::f32::consts::PI * (1.0 - f_o) * (1.0 - f_i) / (1.0 - p_coat);
        let coat_scale = f_o / p_coat;
        let (ks, kd) = (&self.specular, &self.base);
        LaneSamples {
            valid: active & (coat | !diffuse.z.le(zero)),
            wi: Vec3s::select(coat, &reflect_local_lanes(wo), &diffuse),
            // Channels written out, as in `fresnel_conductor_rgb_lanes`.
            weight: [
                F32s::select(coat, ks[0] * coat_scale, kd[0] * base_scale),
                F32s::select(coat, ks[1] * coat_scale, kd[1] * base_scale),
                F32s::select(coat, ks[2] * coat_scale, kd[2] * base_scale),
            ],
            pdf: F32s::select(coat, p_coat, (1.0 - p_coat) * cosine_hemisphere_pdf_lanes(diffuse.z)),
            specular: active & coat,
            eta: F32s::ONE,
        }
    }

    /// The base's f·cos θi and density (the coating, a Dirac lobe, has neither).
    #[inline(always)]
    fn eval_pdf(&self, wo: &Vec3s<N>, wi: &Vec3s<N>) -> ([F32s<N>; 3], F32s<N>) {
        let zero = F32s::ZERO;
        let below = wo.z.le(zero) | wi.z.le(zero);
        let f_o = fresnel_dielectric_lanes(wo.z, self.ior).0;
        let f_i = fresnel_dielectric_lanes(wi.z, self.ior).0;
        let scale = (1.0 - f_o) * (1.0 - f_i) * wi.z;
        let kd = &self.base;
        let value = [
            F32s::select(below, zero, kd[0] * scale),
            F32s::select(below, zero, kd[1] * scale),
            F32s::select(below, zero, kd[2] * scale),
        ];
        let pdf = (1.0 - self.coating_probability(f_o)) * cosine_hemisphere_pdf_lanes(wi.z);
        (value, F32s::select(below, zero, pdf))
    }
}

/// Mitsuba's lobe choice for both plastics, per lane: the coating's reflected fraction weighted
/// by the specular sampling weight, against the transmitted (diffuse) fraction weighted by its
/// complement; 0 when both vanish.
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
    use crate::material::lane_checks::{assert_smooth_lanes_match, Numbers};

    /// Each lane of a group of mixed plastics gives the bits of its own one-lane evaluation and
    /// sample (both lobes, seen from the front and from behind): the lanes stay apart.
    #[test]
    fn lanes_of_mixed_plastics_match_each_scalar_one() {
        const N: usize = 8;
        let plastic = |i: usize| {
            let k = (i % 4) as f32;
            Plastic::new(Rgb::new(0.2, 0.5, 0.8 - 0.1 * k), Rgb::splat(1.0 - 0.2 * k), 1.3 + 0.2 * k, i % 4 == 3)
        };
        let mut lanes = plastic(0).lanes::<N>();
        for i in 0..N {
            lanes.set(i, &plastic(i));
        }
        let (mut coat, mut base, mut none) = (0, 0, 0);
        let mut numbers = Numbers::new(0x2545_f491);
        assert_smooth_lanes_match(
            &lanes,
            plastic,
            &mut numbers,
            300,
            |n| n.direction(-0.05, 0.7),
            |_, _, one| match one {
                Some(one) if one.delta => coat += 1,
                Some(_) => base += 1,
                None => none += 1,
            },
        );
        assert!(coat > 100 && base > 1000 && none > 50, "{coat} {base} {none}");
    }

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
