//! `rough_plastic`: a diffuse base under a rough dielectric coating, as Mitsuba 3's
//! `roughplastic` (isotropic roughness only, as there).
//!
//! - Coating: microfacet reflection F(wo·m) D G / (4 cos θo cos θi) (Walter et al. 2007), times
//!   `specular`.
//! - Base: f = ρ' t(cos θo) t(cos θi) / (π η²), where t(μ) is the fraction of light the rough
//!   coating transmits at cos θ = μ: ∫ (1 − F(wo·m)) G1(wt, m) over the visible normals m of wo,
//!   wt being wo refracted through m (Mitsuba: `eval_transmittance`; light masked on its way
//!   through, or reflected, does not reach the base), tabulated at 64 values μ = i/63 and
//!   interpolated linearly; ρ' = ρ / (1 − R_int) (or ρ / (1 − ρ R_int) with `nonlinear`), R_int =
//!   2·mean over those μ of μ·R(μ), R(μ) = ∫ F G1(wr, m) the coating's directional albedo seen
//!   from inside (relative index 1/η; Mitsuba: `eval_reflectance`). Tables and constants follow
//!   Mitsuba's definitions; the integrals use Gauss–Legendre rules over the visible-normal sample
//!   square (32² points from outside, 128² from inside, as Mitsuba).
//! - Sampling: the coating (visible normals) with probability (1 − t(cos θo))·s, the base
//!   (cosine) with t(cos θo)(1 − s), normalised; s = Mitsuba's specular sampling weight. The
//!   weight is f·cos/pdf with the pdf of the whole mixture.
//! - A textured α: [`RoughPlastic::with_alpha`] with the tables interpolated over α
//!   (`rough_plastic_alpha.rs`).

use super::dielectric::fresnel_dielectric_lanes;
use super::lanes::{LaneSamples, LaneScattering, SmoothModel};
use super::microfacet::{reflect_about_lanes, refract_about_lanes, visible_density_lanes, Microfacet, MicrofacetLanes};
use super::plastic::{base_albedo, coating_pick_probability_lanes, specular_sampling_weight};
use super::rough_plastic_alpha::RoughPlasticAlphaTable;
use crate::math::special::gauss_legendre;
use crate::math::{Rgb, Vec3, INV_PI};
use crate::sampling::warp::cosine_hemisphere_pdf_lanes;
use crate::wide::simd::{map_rgb, F32s, Ms, Vec3s, LANES_256};
use crate::wide::warp as warp_lanes;
use rayon::prelude::*;

/// Entries of the transmittance table (Mitsuba's `MI_ROUGH_TRANSMITTANCE_RES`).
pub(crate) const TABLE_SIZE: usize = 64;

/// A rough plastic. Build it with [`RoughPlastic::new`], which precomputes the coating tables.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughPlastic {
    pub distribution: Microfacet,
    pub albedo: Rgb,
    pub specular: Rgb,
    pub ior: f32,
    pub nonlinear: bool,
    /// ρ' / (π η²).
    base: Rgb,
    /// The coating's internal diffuse reflectance F_dr (kept to rebuild `base` for a textured
    /// albedo).
    internal: f32,
    specular_weight: f32,
    /// t(μ) at μ = i/(TABLE_SIZE − 1).
    transmittance: [f32; TABLE_SIZE],
}

/// Points of a Gauss–Legendre rule on the sample square taken together: a row's points run in
/// lanes (the table integrals call the visible-normal sampler about 10⁶ times per plastic,
/// most of a scene's loading time when drawn one at a time).
const RULE_LANES: usize = LANES_256;

/// `f(wo, m)` at the points of the n×n Gauss–Legendre rule `rule` (nodes on [−1, 1])
/// mapped to the visible-normal sample square of `wo`, summed with the rule's weights (times
/// the square's Jacobian ¼) in f64, point by point in row order. `f` returns each lane's value
/// and the lanes that count.
fn integrate_visible_normals(
    distribution: &Microfacet,
    wo: Vec3,
    rule: &[(f64, f64)],
    f: impl Fn(&Vec3s<RULE_LANES>, &Vec3s<RULE_LANES>) -> (F32s<RULE_LANES>, Ms<RULE_LANES>),
) -> f32 {
    let lanes = distribution.lanes::<RULE_LANES>();
    let wo = Vec3s::splat(wo);
    let square = |x: f64| (0.5 * x + 0.5) as f32;
    let mut sum = 0.0f64;
    for &(x, wx) in rule {
        for row in rule.chunks(RULE_LANES) {
            let active = Ms::from_fn(|i| i < row.len());
            let u2 = F32s::from_fn(|i| row.get(i).map_or(0.5, |&(y, _)| square(y)));
            let m = lanes.sample_visible(&wo, F32s::splat(square(x)), u2, active);
            let (value, counts) = f(&wo, &m);
            for (i, &(_, wy)) in row.iter().enumerate() {
                if counts.lane(i) {
                    sum += 0.25 * wx * wy * f64::from(value.0[i]);
                }
            }
        }
    }
    sum as f32
}

/// Directional albedo of microfacet reflection off an interface of relative index `eta` seen
/// at cos θ = `mu`: ∫ F(wo·m) G1(wi, m) over the visible normals of wo, by the n×n
/// Gauss–Legendre rule `rule` on the sample square.
fn coating_reflectance(distribution: &Microfacet, mu: f32, eta: f32, rule: &[(f64, f64)]) -> f32 {
    let lanes = distribution.lanes::<RULE_LANES>();
    integrate_visible_normals(distribution, direction_at(mu), rule, |wo, m| {
        let wi = reflect_about_lanes(wo, m);
        let f = fresnel_dielectric_lanes(wo.dot(m), F32s::splat(eta)).0 * lanes.g1(&wi, m);
        (f, !wi.z.le(F32s::ZERO))
    })
}

/// Directional transmittance of the same interface: ∫ (1 − F(wo·m)) G1(wt, m) over the visible
/// normals of wo, wt = wo refracted through m (counted only if it crosses the surface).
fn coating_transmittance(distribution: &Microfacet, mu: f32, eta: f32, rule: &[(f64, f64)]) -> f32 {
    let lanes = distribution.lanes::<RULE_LANES>();
    integrate_visible_normals(distribution, direction_at(mu), rule, |wo, m| {
        let cos_om = wo.dot(m);
        let (f, cos_t, eta_t) = fresnel_dielectric_lanes(cos_om, F32s::splat(eta));
        let crosses = !cos_om.le(F32s::ZERO) & !cos_t.eq(F32s::ZERO);
        let wt = refract_about_lanes(wo, m, cos_om, cos_t, eta_t);
        ((1.0 - f) * lanes.g1(&wt, m), crosses & !wt.z.ge(F32s::ZERO))
    })
}

/// The direction at cos θ = `mu` in the xz-plane.
fn direction_at(mu: f32) -> Vec3 {
    Vec3::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu)
}

impl RoughPlastic {
    pub fn new(distribution: Microfacet, albedo: Rgb, specular: Rgb, ior: f32, nonlinear: bool) -> Self {
        // The table's entries are independent (and about 0.3 s per plastic serially, most of
        // the loading time of a scene with a few plastics): computed on the thread pool, then
        // summed in order, so the tables do not depend on the thread count.
        let (outside, inside) = (gauss_legendre(32), gauss_legendre(128));
        let entries: Vec<(f32, f32)> = (0..TABLE_SIZE)
            .into_par_iter()
            .map(|i| {
                let mu = (i as f32 / (TABLE_SIZE - 1) as f32).max(1e-6);
                let t = coating_transmittance(&distribution, mu, ior, &outside);
                (t, coating_reflectance(&distribution, mu, 1.0 / ior, &inside) * mu)
            })
            .collect();
        let mut transmittance = [0.0; TABLE_SIZE];
        let mut internal = 0.0f32;
        for (i, &(t, r)) in entries.iter().enumerate() {
            transmittance[i] = t;
            internal += r;
        }
        internal *= 2.0 / TABLE_SIZE as f32;
        let base = base_albedo(albedo, internal, nonlinear) * (INV_PI / (ior * ior));
        let specular_weight = specular_sampling_weight(albedo, specular);
        Self { distribution, albedo, specular, ior, nonlinear, base, internal, specular_weight, transmittance }
    }

    /// The same coating over another base albedo (a textured `albedo` at one hit). The lobe
    /// sampling weight stays the one computed from the mean albedo, as in Mitsuba.
    #[inline]
    pub fn with_albedo(&self, albedo: Rgb) -> Self {
        let base = base_albedo(albedo, self.internal, self.nonlinear) * (INV_PI / (self.ior * self.ior));
        Self { albedo, base, ..*self }
    }

    /// The same plastic at isotropic roughness `alpha` (a roughness texture's value at one
    /// hit), its coating tables blended from `table` (built from this plastic). The lobe
    /// sampling weight does not depend on α.
    #[inline]
    pub fn with_alpha(&self, alpha: f32, table: &RoughPlasticAlphaTable) -> Self {
        let alpha = alpha.clamp(0.0, 1.0);
        let (transmittance, internal) = table.at(alpha);
        let base = base_albedo(self.albedo, internal, self.nonlinear) * (INV_PI / (self.ior * self.ior));
        let distribution = Microfacet::isotropic(self.distribution.kind, alpha);
        Self { distribution, base, internal, transmittance, ..*self }
    }

    /// t(μ) at μ = i/(TABLE_SIZE − 1).
    pub(crate) fn transmittance_table(&self) -> &[f32; TABLE_SIZE] {
        &self.transmittance
    }

    /// The coating's internal diffuse reflectance F_dr.
    pub(crate) fn internal_reflectance(&self) -> f32 {
        self.internal
    }
}

impl SmoothModel for RoughPlastic {
    type Lanes<'a, const N: usize> = RoughPlasticLanes<'a, N>;

    /// This plastic in every lane of a group (the scalar methods are the one-lane instances of
    /// [`RoughPlasticLanes`]'s).
    #[inline(always)]
    fn lanes<const N: usize>(&self) -> Self::Lanes<'_, N> {
        RoughPlasticLanes {
            distribution: self.distribution.lanes(),
            specular: self.specular.to_array().map(F32s::splat),
            base: self.base.to_array().map(F32s::splat),
            ior: F32s::splat(self.ior),
            specular_weight: F32s::splat(self.specular_weight),
            transmittance: [&self.transmittance; N],
        }
    }
}

/// t(μ) by linear interpolation in a transmittance table.
#[inline(always)]
fn interpolate(table: &[f32; TABLE_SIZE], mu: f32) -> f32 {
    let x = mu.clamp(0.0, 1.0) * (TABLE_SIZE - 1) as f32;
    let i = (x as usize).min(TABLE_SIZE - 2);
    let w = x - i as f32;
    (1.0 - w) * table[i] + w * table[i + 1]
}

/// A rough plastic per lane (lanes can hold different ones), RGB channels as lane groups.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RoughPlasticLanes<'a, const N: usize> {
    pub distribution: MicrofacetLanes<N>,
    pub specular: [F32s<N>; 3],
    /// ρ' / (π η²).
    pub base: [F32s<N>; 3],
    pub ior: F32s<N>,
    pub specular_weight: F32s<N>,
    /// Each lane's t(μ) table.
    pub transmittance: [&'a [f32; TABLE_SIZE]; N],
}

// Always inlined, as the lane loop's helpers (see `MicrofacetLanes`).
impl<'a, const N: usize> RoughPlasticLanes<'a, N> {
    /// Lane `i` holds `m`.
    #[inline(always)]
    pub fn set(&mut self, i: usize, m: &'a RoughPlastic) {
        self.distribution.set(i, &m.distribution);
        for c in 0..3 {
            self.specular[c].0[i] = m.specular.to_array()[c];
            self.base[c].0[i] = m.base.to_array()[c];
        }
        self.ior.0[i] = m.ior;
        self.specular_weight.0[i] = m.specular_weight;
        self.transmittance[i] = &m.transmittance;
    }

    /// t(μ) per lane, from each lane's table (a lookup per lane).
    #[inline(always)]
    fn transmittance(&self, mu: F32s<N>) -> F32s<N> {
        F32s::from_fn(|i| interpolate(self.transmittance[i], mu.0[i]))
    }

    /// The probability of sampling the coating, seen along `wo`.
    #[inline(always)]
    fn coating_probability(&self, wo: &Vec3s<N>) -> F32s<N> {
        let t = self.transmittance(wo.z);
        coating_pick_probability_lanes(1.0 - t, t, self.specular_weight)
    }
}

impl<const N: usize> LaneScattering<N> for RoughPlasticLanes<'_, N> {
    /// The coating (visible normals) or the base (cosine-weighted), chosen by `u_lobe`; the
    /// weight is f·cos/pdf with the pdf of the whole mixture.
    #[inline(always)]
    fn sample(&self, wo: &Vec3s<N>, u_lobe: F32s<N>, u1: F32s<N>, u2: F32s<N>, active: Ms<N>) -> LaneSamples<N> {
        let zero = F32s::ZERO;
        // `!(x <= 0)` keeps the scalar form's rule for NaN.
        let active = active & !wo.z.le(zero);
        let coat = u_lobe.lt(self.coating_probability(wo));
        let m = self.distribution.sample_visible(wo, u1, u2, active & coat);
        let reflected = reflect_about_lanes(wo, &m);
        let diffuse =
            if (active & !coat).any() { warp_lanes::square_to_cosine_hemisphere(u1, u2) } else { Vec3s::default() };
        let wi = Vec3s::select(coat, &reflected, &diffuse);
        let (f, pdf) = self.eval_pdf(wo, &wi);
        let valid = active & !wi.z.le(zero) & pdf.is_finite() & pdf.gt(zero);
        let inv_pdf = 1.0 / pdf;
        LaneSamples { valid, wi, weight: map_rgb(f, |c| c * inv_pdf), pdf, specular: Ms::NONE, eta: F32s::ONE }
    }

    /// f·cos θi and the density of `wi` per lane.
    #[inline(always)]
    fn eval_pdf(&self, wo: &Vec3s<N>, wi: &Vec3s<N>) -> ([F32s<N>; 3], F32s<N>) {
        let zero = F32s::ZERO;
        let below = wo.z.le(zero) | wi.z.le(zero);
        let m = wo.add(wi).normalize();
        let cos_om = wo.dot(&m);
        let d = self.distribution.d(&m);
        let g1_o = self.distribution.g1(wo, &m);
        let fresnel = fresnel_dielectric_lanes(cos_om, self.ior).0;
        let coat = fresnel * d * (g1_o * self.distribution.g1(wi, &m)) / (4.0 * wo.z);
        let base = self.transmittance(wo.z) * self.transmittance(wi.z) * wi.z;
        // Channels written out, as in `fresnel_conductor_rgb_lanes`.
        let (ks, kd) = (&self.specular, &self.base);
        let value = [
            F32s::select(below, zero, ks[0] * coat + kd[0] * base),
            F32s::select(below, zero, ks[1] * coat + kd[1] * base),
            F32s::select(below, zero, ks[2] * coat + kd[2] * base),
        ];
        let p_coat = self.coating_probability(wo);
        // Jacobian of the reflection map dωm/dωi = 1/(4 wo·m) (Walter 2007 eq. 14).
        let coat_pdf = visible_density_lanes(g1_o, cos_om, d, wo.z) / (4.0 * cos_om);
        let coat_pdf = F32s::select(cos_om.gt(zero), coat_pdf, zero);
        let pdf = p_coat * coat_pdf + (1.0 - p_coat) * cosine_hemisphere_pdf_lanes(wi.z);
        (value, F32s::select(below, zero, pdf))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::lane_checks::{assert_smooth_lanes_match, Numbers};
    use crate::material::MicrofacetKind;
    use crate::math::Vec2;
    use crate::wide::simd::LANES_512 as N;

    /// Each lane of a group of mixed plastics (both distributions, several roughnesses, indices
    /// and colours) gives the bits of its own scalar evaluation and sample: the scalar forms are
    /// the one-lane instance, so this checks that lanes and their tables stay apart.
    #[test]
    fn lanes_of_mixed_plastics_match_each_scalar_one() {
        let plastics: Vec<RoughPlastic> = (0..4)
            .map(|k| {
                let kind = if k % 2 == 0 { MicrofacetKind::Beckmann } else { MicrofacetKind::Ggx };
                let d = Microfacet::isotropic(kind, [0.01, 0.08, 0.3, 0.6][k]);
                RoughPlastic::new(d, Rgb::new(0.2, 0.5, 0.8 - 0.1 * k as f32), Rgb::WHITE, 1.3 + 0.2 * k as f32, k == 3)
            })
            .collect();
        let mut lanes = plastics[0].lanes::<N>();
        for i in 0..N {
            lanes.set(i, &plastics[i % 4]);
        }
        let (mut sampled, mut evaluated) = (0, 0);
        let mut numbers = Numbers::new(0x2545_f491);
        let model = |i: usize| plastics[i % 4];
        assert_smooth_lanes_match(
            &lanes,
            model,
            &mut numbers,
            200,
            |n| n.direction(-0.05, 0.7),
            |_, pdf, one| {
                evaluated += usize::from(pdf > 0.0);
                sampled += usize::from(one.is_some());
            },
        );
        assert!(sampled > 1000 && evaluated > 1000, "{sampled} {evaluated}");
    }

    fn dir(theta: f32, phi: f32) -> Vec3 {
        Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos())
    }

    #[test]
    fn values_and_densities_match_mitsuba() {
        // Mitsuba 3.9.1 scalar_rgb `roughplastic` (ggx, alpha 0.15, int_ior 1.5, ext_ior 1,
        // diffuse_reflectance 0.5): bsdf.eval and bsdf.pdf with si.wi = dir(θo, 0) and
        // wo = dir(θi, φ) (Mitsuba's eval includes cos θi, as ours).
        let d = Microfacet::new(MicrofacetKind::Ggx, 0.15, 0.15);
        let m = RoughPlastic::new(d, Rgb::splat(0.5), Rgb::WHITE, 1.5, false);
        for (to, ti, phi, value, pdf) in [
            (0.3, 0.5, 2.0, 0.131_170_96, 0.282_154_4),
            (1.2, 0.4, 1.0, 0.111_359_15, 0.221_844_58),
            (0.6, 1.3, 3.0, 0.036_425_32, 0.086_840_35),
            (0.2, 0.25, 3.0, 0.265_285_37, 0.551_587_4),
        ] {
            let (wo, wi) = (dir(to, 0.0), dir(ti, phi));
            let (f, p) = (m.eval(wo, wi).r, m.pdf(wo, wi));
            assert!((f / value - 1.0).abs() < 2e-3, "θo {to} θi {ti}: {f} vs Mitsuba {value}");
            // The coating's pick probability is ∝ 1 − t(cos θo), which near normal incidence is
            // ~0.04: the tables' ~1e-4 quadrature differences show there as 0.3% (seen: 0.31%
            // at θo = 0.2 next to the mirror direction; the other cases agree within 0.02%).
            assert!((p / pdf - 1.0).abs() < 5e-3, "θo {to} θi {ti}: pdf {p} vs Mitsuba {pdf}");
        }
    }

    /// The tables' integrals taken a row of points at a time in lanes equal, bit for bit, the
    /// same sums taken one point at a time through the one-lane forms, in the rule's order:
    /// rules whose rows fill the lanes (32, 128) and one that leaves lanes empty (5).
    #[test]
    fn lane_rows_sum_what_one_point_at_a_time_sums() {
        use crate::material::dielectric::fresnel_dielectric;
        use crate::material::microfacet::{reflect_about, refract_about};
        fn one_at_a_time(d: &Microfacet, mu: f32, rule: &[(f64, f64)], f: impl Fn(Vec3, Vec3) -> Option<f32>) -> f32 {
            let wo = direction_at(mu);
            let mut sum = 0.0f64;
            for &(x, wx) in rule {
                for &(y, wy) in rule {
                    let m = d.sample_visible(wo, Vec2::new((0.5 * x + 0.5) as f32, (0.5 * y + 0.5) as f32));
                    if let Some(value) = f(wo, m) {
                        sum += 0.25 * wx * wy * f64::from(value);
                    }
                }
            }
            sum as f32
        }
        for kind in [MicrofacetKind::Beckmann, MicrofacetKind::Ggx] {
            for alpha in [0.05, 0.3, 0.9] {
                let d = Microfacet::isotropic(kind, alpha);
                for n in [5, 32, 128] {
                    let rule = gauss_legendre(n);
                    for mu in [1e-6, 0.1, 0.5, 0.9, 1.0] {
                        let (eta, inside) = (1.5, 1.0 / 1.5);
                        let reflectance = one_at_a_time(&d, mu, &rule, |wo, m| {
                            let wi = reflect_about(wo, m);
                            if wi.z <= 0.0 {
                                return None;
                            }
                            Some(fresnel_dielectric(wo.dot(m), inside).0 * d.g1(wi, m))
                        });
                        assert_eq!(coating_reflectance(&d, mu, inside, &rule).to_bits(), reflectance.to_bits());
                        let transmittance = one_at_a_time(&d, mu, &rule, |wo, m| {
                            let cos_om = wo.dot(m);
                            let (f, cos_t, eta_t) = fresnel_dielectric(cos_om, eta);
                            if cos_om <= 0.0 || cos_t == 0.0 {
                                return None;
                            }
                            let wt = refract_about(wo, m, cos_om, cos_t, eta_t);
                            if wt.z >= 0.0 {
                                return None;
                            }
                            Some((1.0 - f) * d.g1(wt, m))
                        });
                        assert_eq!(coating_transmittance(&d, mu, eta, &rule).to_bits(), transmittance.to_bits());
                    }
                }
            }
        }
    }
}
