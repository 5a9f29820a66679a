//! `glossy`: the energy-normalised modified Phong lobe (Lafortune & Willems, "Using the Modified
//! Phong Reflectance Model for Physically Based Rendering", 1994):
//! f(wo, wi) = albedo · (n + 2)/(2π) · cosⁿ α, with α the angle between wi and the mirror
//! direction of wo. Its directional albedo never exceeds `albedo` (equal at normal incidence).
//! Sampled by the power-cosine lobe around the mirror direction, pdf (n + 1)/(2π) cosⁿ α;
//! lobe directions below the surface are rejected (that probability is lost, and eval is 0
//! there, so the estimator stays unbiased).

use super::lanes::{LaneSamples, LaneScattering, SmoothModel};
use super::reflect_local_lanes;
use crate::math::{Rgb, INV_2PI};
use crate::wide::simd::{F32s, Ms, Vec3s};
use crate::wide::warp;

/// Phong glossy reflection with exponent `exponent` (higher = sharper).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Glossy {
    pub albedo: Rgb,
    pub exponent: f32,
}

impl SmoothModel for Glossy {
    type Lanes<'a, const N: usize> = GlossyLanes<N>;

    /// This model in every lane of a group (the scalar methods are the one-lane instances of
    /// [`GlossyLanes`]'s).
    #[inline(always)]
    fn lanes<const N: usize>(&self) -> Self::Lanes<'_, N> {
        GlossyLanes { albedo: self.albedo.to_array().map(F32s::splat), exponent: F32s::splat(self.exponent) }
    }
}

/// Phong lobes per lane, the albedo's channels as lane groups.
#[derive(Clone, Copy, Debug)]
pub(crate) struct GlossyLanes<const N: usize> {
    pub albedo: [F32s<N>; 3],
    pub exponent: F32s<N>,
}

impl<const N: usize> GlossyLanes<N> {
    /// Lane `i` holds `m`.
    #[inline(always)]
    pub fn set(&mut self, i: usize, m: &Glossy) {
        for (c, a) in m.albedo.to_array().into_iter().enumerate() {
            self.albedo[c].0[i] = a;
        }
        self.exponent.0[i] = m.exponent;
    }

    /// cosⁿ α, α between `wi` and the mirror direction of `wo` (`f32::max` and `powf` per
    /// lane of `lanes`, the scalar form's bits; the other lanes: 0).
    #[inline(always)]
    fn lobe(&self, wo: &Vec3s<N>, wi: &Vec3s<N>, lanes: Ms<N>) -> F32s<N> {
        let cos_alpha = reflect_local_lanes(wo).dot(wi);
        let mut out = F32s::ZERO;
        for i in lanes.lanes() {
            out.0[i] = cos_alpha.0[i].max(0.0).powf(self.exponent.0[i]);
        }
        out
    }
}

impl<const N: usize> LaneScattering<N> for GlossyLanes<N> {
    /// A power-cosine direction around the mirror direction; weight albedo (n+2)/(n+1) cos θi
    /// (f cos θi / pdf).
    #[inline(always)]
    fn sample(&self, wo: &Vec3s<N>, _u_lobe: F32s<N>, u1: F32s<N>, u2: F32s<N>, active: Ms<N>) -> LaneSamples<N> {
        let zero = F32s::ZERO;
        // `!(x <= 0)` keeps the scalar rule for NaN.
        let active = active & !wo.z.le(zero);
        let local = warp::square_to_power_cosine(u1, u2, self.exponent, active);
        let wi = warp::to_world(&reflect_local_lanes(wo), &local);
        let active = active & !wi.z.le(zero);
        let (_, pdf) = self.eval_pdf(wo, &wi);
        let n = self.exponent;
        let scale = (n + 2.0) / (n + 1.0) * wi.z;
        let a = &self.albedo;
        LaneSamples {
            valid: active & !pdf.le(zero),
            wi,
            weight: [a[0] * scale, a[1] * scale, a[2] * scale],
            pdf,
            specular: Ms::NONE,
            eta: F32s::ONE,
        }
    }

    /// f·cos θi = albedo (n+2)/(2π) cosⁿ α cos θi and the density (n+1)/(2π) cosⁿ α, where both
    /// directions are above the surface.
    #[inline(always)]
    fn eval_pdf(&self, wo: &Vec3s<N>, wi: &Vec3s<N>) -> ([F32s<N>; 3], F32s<N>) {
        let zero = F32s::ZERO;
        let below = wo.z.le(zero) | wi.z.le(zero);
        let c = self.lobe(wo, wi, !below);
        let n = self.exponent;
        let scale = (n + 2.0) * INV_2PI * c * wi.z;
        let a = &self.albedo;
        let value = [
            F32s::select(below, zero, a[0] * scale),
            F32s::select(below, zero, a[1] * scale),
            F32s::select(below, zero, a[2] * scale),
        ];
        (value, F32s::select(below, zero, (n + 1.0) * INV_2PI * c))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::lane_checks::assert_mixed_lanes_match;

    /// Each lane of a group of mixed models gives the bits of its own one-lane evaluation and
    /// sample, seen from the front and from behind.
    #[test]
    fn lanes_of_mixed_models_match_each_scalar_one() {
        const N: usize = 8;
        let model = |i: usize| Glossy {
            albedo: Rgb::new(0.2 + 0.1 * (i % 4) as f32, 0.5, 0.7),
            exponent: [1.0, 8.0, 50.0, 400.0][i % 4],
        };
        let mut lanes = model(0).lanes::<N>();
        for i in 0..N {
            lanes.set(i, &model(i));
        }
        assert_mixed_lanes_match(&lanes, model);
    }
}
