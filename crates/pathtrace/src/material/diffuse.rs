//! `diffuse`: the naive "uniform diffuse" model of early path tracers — a ray scatters uniformly
//! over the hemisphere and keeps `albedo` of its energy. As a BRDF that is
//! f(wo, wi) = albedo / (2π cos θi), so f·cos θi = albedo / 2π: the surface reflects `albedo`
//! times the *unweighted* hemispherical average of incident radiance. Unlike Lambertian it
//! ignores the cosine law (grazing light counts as much as overhead light), which is why
//! a Cornell box looks flatter with it. Sampled uniformly (pdf 1/2π), so every sample's weight is
//! exactly `albedo`.

use super::lanes::{rgb_lane, LaneSamples, LaneScattering};
use super::BsdfSample;
use crate::math::{Rgb, Vec2, Vec3, INV_2PI};
use crate::wide::simd::{F32s, Ms, Vec3s};
use crate::wide::warp;

/// Uniform-hemisphere diffuse reflection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Diffuse {
    pub albedo: Rgb,
}

impl Diffuse {
    /// This model in every lane of a group (the scalar methods are the one-lane instances of
    /// [`DiffuseLanes`]'s).
    #[inline(always)]
    pub(crate) fn lanes<const N: usize>(&self) -> DiffuseLanes<N> {
        DiffuseLanes { albedo: self.albedo.to_array().map(F32s::splat) }
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

    /// `eval` and `pdf` together.
    #[inline]
    pub fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Rgb, f32) {
        let (f, pdf) = self.lanes::<1>().eval_pdf(&Vec3s::splat(wo), &Vec3s::splat(wi));
        (rgb_lane(&f, 0), pdf.0[0])
    }
}

/// Uniform-hemisphere diffuse models per lane, the albedo's channels as lane groups.
#[derive(Clone, Copy, Debug)]
pub(crate) struct DiffuseLanes<const N: usize> {
    pub albedo: [F32s<N>; 3],
}

impl<const N: usize> DiffuseLanes<N> {
    /// Lane `i` holds `m`.
    #[inline(always)]
    pub fn set(&mut self, i: usize, m: &Diffuse) {
        for (c, a) in m.albedo.to_array().into_iter().enumerate() {
            self.albedo[c].0[i] = a;
        }
    }
}

impl<const N: usize> LaneScattering<N> for DiffuseLanes<N> {
    /// A uniform direction on the hemisphere; its weight is the albedo.
    #[inline(always)]
    fn sample(&self, wo: &Vec3s<N>, _u_lobe: F32s<N>, u1: F32s<N>, u2: F32s<N>, active: Ms<N>) -> LaneSamples<N> {
        // `!(x <= 0)` keeps the scalar rule for NaN.
        let active = active & !wo.z.le(F32s::ZERO);
        let wi = warp::square_to_uniform_hemisphere(u1, u2, active);
        LaneSamples {
            valid: active & wi.z.gt(F32s::ZERO),
            wi,
            weight: self.albedo,
            pdf: F32s::splat(INV_2PI),
            specular: Ms::NONE,
            eta: F32s::ONE,
        }
    }

    /// albedo/2π and the density 1/2π where both directions are above the surface.
    #[inline(always)]
    fn eval_pdf(&self, wo: &Vec3s<N>, wi: &Vec3s<N>) -> ([F32s<N>; 3], F32s<N>) {
        let zero = F32s::ZERO;
        let below = wo.z.le(zero) | wi.z.le(zero);
        let a = &self.albedo;
        let value = [
            F32s::select(below, zero, a[0] * INV_2PI),
            F32s::select(below, zero, a[1] * INV_2PI),
            F32s::select(below, zero, a[2] * INV_2PI),
        ];
        (value, F32s::select(below, zero, F32s::splat(INV_2PI)))
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
        let model = |i: usize| Diffuse { albedo: Rgb::new(0.2 + 0.1 * (i % 4) as f32, 0.5, 0.7) };
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
