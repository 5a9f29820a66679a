//! `glossy`: the energy-normalised modified Phong lobe (Lafortune & Willems, "Using the Modified
//! Phong Reflectance Model for Physically Based Rendering", 1994):
//! f(wo, wi) = albedo · (n + 2)/(2π) · cosⁿ α, with α the angle between wi and the mirror
//! direction of wo. Its directional albedo never exceeds `albedo` (equal at normal incidence).
//! Sampled by the power-cosine lobe around the mirror direction, pdf (n + 1)/(2π) cosⁿ α;
//! lobe directions below the surface are rejected (that probability is lost, and eval is 0
//! there, so the estimator stays unbiased).

use super::lanes::{rgb_lane, LaneSamples, LaneScattering};
use super::{reflect_local_lanes, BsdfSample};
use crate::math::{Rgb, Vec2, Vec3, INV_2PI};
use crate::wide::simd::{F32s, Ms, Vec3s};
use crate::wide::warp;

/// Phong glossy reflection with exponent `exponent` (higher = sharper).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Glossy {
    pub albedo: Rgb,
    pub exponent: f32,
}

impl Glossy {
    /// This model in every lane of a group (the scalar methods are the one-lane instances of
    /// [`GlossyLanes`]'s).
    #[inline(always)]
    pub(crate) fn lanes<const N: usize>(&self) -> GlossyLanes<N> {
        GlossyLanes { albedo: self.albedo.to_array().map(F32s::splat), exponent: F32s::splat(self.exponent) }
    }

    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
        self.lanes::<1>().sample(&Vec3s::splat(wo), F32s::ZERO, F32s([u.x]), F32s([u.y]), Ms::ALL).lane(0)
    }

    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        self.eval_pdf(wo, wi).0
    }

    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.eval_pdf(wo, wi).1
    }

    /// `eval` and `pdf` together, sharing cosⁿ α.
    #[inline]
    pub fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Rgb, f32) {
        let (f, pdf) = self.lanes::<1>().eval_pdf(&Vec3s::splat(wo), &Vec3s::splat(wi));
        (rgb_lane(&f, 0), pdf.0[0])
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
        let mut x = 0x2545_f491u32;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            (x >> 8) as f32 / (1u32 << 24) as f32
        };
        let (mut sampled, mut evaluated) = (0, 0);
        for _ in 0..300 {
            let mut direction = || Vec3::new(next() - 0.5, next() - 0.5, 0.7 * next() - 0.1).normalize();
            let wo: [Vec3; N] = std::array::from_fn(|_| direction());
            let wi: [Vec3; N] = std::array::from_fn(|_| direction());
            let (wo_l, wi_l) = (Vec3s::from_fn(|i| wo[i]), Vec3s::from_fn(|i| wi[i]));
            let u = [0; 2].map(|_| F32s::<N>::from_fn(|_| next()));
            let (f, pdf) = lanes.eval_pdf(&wo_l, &wi_l);
            let s = lanes.sample(&wo_l, F32s::ZERO, u[0], u[1], Ms::ALL);
            for i in 0..N {
                let m = model(i);
                let (f1, pdf1) = (m.eval(wo[i], wi[i]), m.pdf(wo[i], wi[i]));
                assert_eq!(rgb_lane(&f, i).to_array().map(f32::to_bits), f1.to_array().map(f32::to_bits));
                assert_eq!(pdf.0[i].to_bits(), pdf1.to_bits());
                evaluated += usize::from(pdf1 > 0.0);
                let one = m.sample(wo[i], Vec2::new(u[0].0[i], u[1].0[i]));
                assert_eq!(s.valid.lane(i), one.is_some(), "lane {i}");
                let Some(one) = one else { continue };
                sampled += 1;
                assert_eq!(s.wi.lane(i).to_array().map(f32::to_bits), one.wi.to_array().map(f32::to_bits));
                let w = rgb_lane(&s.weight, i).to_array().map(f32::to_bits);
                assert_eq!(w, one.weight.to_array().map(f32::to_bits));
                assert_eq!(s.pdf.0[i].to_bits(), one.pdf.to_bits());
            }
        }
        assert!(sampled > 1000 && evaluated > 1000, "{sampled} {evaluated}");
    }
}
