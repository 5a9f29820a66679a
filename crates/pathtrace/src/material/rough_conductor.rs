//! `rough_conductor`: a rough metal (Cook–Torrance microfacet reflection; Walter et al. 2007
//! eq. 20): f(wo, wi) = F(wo·m) D(m) G(wo, wi, m) / (4 cos θo cos θi), m = (wo + wi)/|wo + wi|,
//! with the conductor Fresnel term per RGB channel. Sampled through the visible normals of
//! wo, so the weight is F(wo·m) G1(wi, m) (Heitz & d'Eon 2014 eq. 4).
//!
//! With F = 1 it loses exactly the energy of light that would scatter more than once between
//! microfacets: e.g. for GGX α = 1 at normal incidence its albedo is ≈ 0.77 (tests/microfacet_bsdfs.rs).

use super::fresnel::fresnel_conductor_rgb_lanes;
use super::lanes::{LaneSamples, LaneScattering, SmoothModel};
use super::microfacet::{reflect_about_lanes, visible_density_lanes, Microfacet, MicrofacetLanes};
use crate::math::Rgb;
use crate::wide::simd::{F32s, Ms, Vec3s};

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

impl SmoothModel for RoughConductor {
    type Lanes<'a, const N: usize> = RoughConductorLanes<N>;

    /// This material in every lane of a group (the scalar methods are the one-lane instances of
    /// [`RoughConductorLanes`]'s).
    #[inline(always)]
    fn lanes<const N: usize>(&self) -> Self::Lanes<'_, N> {
        let splat = |c: Rgb| c.to_array().map(F32s::splat);
        RoughConductorLanes {
            distribution: self.distribution.lanes(),
            eta: splat(self.eta),
            k: splat(self.k),
            reflectance: splat(self.reflectance),
        }
    }
}

/// A rough conductor per lane (lanes can hold different ones), RGB channels as lane groups.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RoughConductorLanes<const N: usize> {
    pub distribution: MicrofacetLanes<N>,
    pub eta: [F32s<N>; 3],
    pub k: [F32s<N>; 3],
    pub reflectance: [F32s<N>; 3],
}

// Always inlined, as the lane loop's helpers (see `MicrofacetLanes`).
impl<const N: usize> RoughConductorLanes<N> {
    /// Lane `i` holds `m`.
    #[inline(always)]
    pub fn set(&mut self, i: usize, m: &RoughConductor) {
        self.distribution.set(i, &m.distribution);
        for (c, ((eta, k), reflectance)) in
            m.eta.to_array().into_iter().zip(m.k.to_array()).zip(m.reflectance.to_array()).enumerate()
        {
            self.eta[c].0[i] = eta;
            self.k[c].0[i] = k;
            self.reflectance[c].0[i] = reflectance;
        }
    }
}

impl<const N: usize> LaneScattering<N> for RoughConductorLanes<N> {
    /// A reflection about a visible normal of `wo` per lane of `active`, from `u1`, `u2` (one
    /// lobe: `u_lobe` is not used).
    #[inline(always)]
    fn sample(&self, wo: &Vec3s<N>, _u_lobe: F32s<N>, u1: F32s<N>, u2: F32s<N>, active: Ms<N>) -> LaneSamples<N> {
        let zero = F32s::ZERO;
        // Directions below the surface are answered nothing (`!(x <= 0)` keeps the scalar
        // form's rule for NaN).
        let active = active & !wo.z.le(zero);
        let m = self.distribution.sample_visible(wo, u1, u2, active);
        let wi = reflect_about_lanes(wo, &m);
        let cos_om = wo.dot(&m);
        let pdf = self.distribution.pdf_visible(wo, &m) / (4.0 * cos_om);
        let valid = active & !wi.z.le(zero) & !cos_om.le(zero) & pdf.is_finite() & pdf.gt(zero);
        let f = fresnel_conductor_rgb_lanes(cos_om, self.eta, self.k);
        let g1 = self.distribution.g1(&wi, &m);
        // Channels written out, as in `fresnel_conductor_rgb_lanes`.
        let r = &self.reflectance;
        let weight = [r[0] * f[0] * g1, r[1] * f[1] * g1, r[2] * f[2] * g1];
        LaneSamples { valid, wi, weight, pdf, specular: Ms::NONE, eta: F32s::ONE }
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
        let dg = d * (g1_o * self.distribution.g1(wi, &m));
        // f·cos θi: the cos θi of the denominator cancels.
        let fresnel = fresnel_conductor_rgb_lanes(cos_om, self.eta, self.k);
        let scale = dg / (4.0 * wo.z);
        let black = below | dg.le(zero);
        let r = &self.reflectance;
        let f = [
            F32s::select(black, zero, r[0] * fresnel[0] * scale),
            F32s::select(black, zero, r[1] * fresnel[1] * scale),
            F32s::select(black, zero, r[2] * fresnel[2] * scale),
        ];
        // Jacobian of the reflection map dωm/dωi = 1/(4 wo·m) (Walter 2007 eq. 14).
        let pdf = visible_density_lanes(g1_o, cos_om, d, wo.z) / (4.0 * cos_om);
        let pdf = F32s::select(below | cos_om.le(zero), zero, pdf);
        (f, pdf)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::lane_checks::{assert_smooth_lanes_match, Numbers};
    use crate::material::{Microfacet, MicrofacetKind};
    use crate::math::Vec3;
    use crate::wide::simd::LANES_512 as N;

    /// A different conductor in every lane (both distributions, several roughnesses).
    fn conductor(i: usize) -> RoughConductor {
        let kind = if i.is_multiple_of(2) { MicrofacetKind::Beckmann } else { MicrofacetKind::Ggx };
        RoughConductor {
            distribution: Microfacet::isotropic(kind, [0.005, 0.05, 0.2, 0.7][i % 4]),
            eta: Rgb::new(0.2 + 0.1 * i as f32, 0.9, 1.1),
            k: Rgb::new(3.9, 2.4 + 0.05 * i as f32, 2.2),
            reflectance: Rgb::new(1.0, 0.8, 0.9),
        }
    }

    fn direction(a: f32, b: f32) -> Vec3 {
        Vec3::new(a - 0.5, b - 0.5, 0.7 * a * b - 0.05).normalize()
    }

    /// Each lane of a group of mixed conductors gives the bits of its own scalar evaluation and
    /// sample (the scalar forms are the one-lane instance: this checks that lanes stay apart).
    #[test]
    fn lanes_of_mixed_conductors_match_each_scalar_one() {
        let mut lanes = conductor(0).lanes::<N>();
        for i in 0..N {
            lanes.set(i, &conductor(i));
        }
        let (mut sampled, mut evaluated) = (0, 0);
        let mut numbers = Numbers::new(0x2545_f491);
        let direction = |n: &mut Numbers| direction(n.next(), n.next());
        assert_smooth_lanes_match(&lanes, conductor, &mut numbers, 200, direction, |_, pdf, one| {
            evaluated += usize::from(pdf > 0.0);
            sampled += usize::from(one.is_some());
        });
        assert!(sampled > 1000 && evaluated > 1000, "{sampled} {evaluated}");
    }
}
