//! `diffuse`: the naive "uniform diffuse" model of early path tracers — a ray scatters uniformly
//! over the hemisphere and keeps `albedo` of its energy. As a BRDF that is
//! f(wo, wi) = albedo / (2π cos θi), so f·cos θi = albedo / 2π: the surface reflects `albedo`
//! times the *unweighted* hemispherical average of incident radiance. Unlike Lambertian it
//! ignores the cosine law (grazing light counts as much as overhead light), which is why
//! a Cornell box looks flatter with it. Sampled uniformly (pdf 1/2π), so every sample's weight is
//! exactly `albedo`.

use super::lanes::{LaneSamples, LaneScattering, SmoothModel};
use crate::math::{Rgb, INV_2PI};
use crate::wide::simd::{F32s, Ms, Vec3s};
use crate::wide::warp;

/// Uniform-hemisphere diffuse reflection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Diffuse {
    pub albedo: Rgb,
}

impl SmoothModel for Diffuse {
    type Lanes<'a, const N: usize> = DiffuseLanes<N>;

    /// This model in every lane of a group (the scalar methods are the one-lane instances of
    /// [`DiffuseLanes`]'s).
    #[inline(always)]
    fn lanes<const N: usize>(&self) -> Self::Lanes<'_, N> {
        DiffuseLanes { albedo: self.albedo.to_array().map(F32s::splat) }
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
    use crate::material::lane_checks::assert_mixed_lanes_match;

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
        assert_mixed_lanes_match(&lanes, model);
    }
}
