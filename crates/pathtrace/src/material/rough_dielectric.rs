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

use super::dielectric::fresnel_dielectric_lanes;
use super::lanes::{LaneSamples, LaneScattering, SmoothModel};
use super::microfacet::{reflect_about_lanes, refract_about_lanes, Microfacet, MicrofacetLanes};
use crate::math::Rgb;
use crate::wide::simd::{map_rgb, F32s, Ms, Vec3s};

/// A rough dielectric interface with interior index `ior` (exterior 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughDielectric {
    pub distribution: Microfacet,
    pub ior: f32,
    /// Colour multiplied into both lobes (white for clear glass).
    pub tint: Rgb,
}

impl SmoothModel for RoughDielectric {
    type Lanes<'a, const N: usize> = RoughDielectricLanes<N>;

    /// This interface in every lane of a group (the scalar methods are the one-lane instances
    /// of [`RoughDielectricLanes`]'s).
    #[inline(always)]
    fn lanes<const N: usize>(&self) -> Self::Lanes<'_, N> {
        RoughDielectricLanes {
            distribution: self.distribution.lanes(),
            ior: F32s::splat(self.ior),
            tint: self.tint.to_array().map(F32s::splat),
        }
    }
}

/// Rough dielectrics per lane (lanes can hold different ones), the tint's channels as lane
/// groups.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RoughDielectricLanes<const N: usize> {
    pub distribution: MicrofacetLanes<N>,
    pub ior: F32s<N>,
    pub tint: [F32s<N>; 3],
}

/// Directions and indices seen from wo's side per lane: both turned over where wo is below, so
/// that wo is above (z > 0); `eta` = index below / index above.
struct Oriented<const N: usize> {
    wo: Vec3s<N>,
    sign: F32s<N>,
    eta: F32s<N>,
}

// Always inlined, as the lane loop's helpers (see `MicrofacetLanes`).
impl<const N: usize> RoughDielectricLanes<N> {
    /// Lane `i` holds `m`.
    #[inline(always)]
    pub fn set(&mut self, i: usize, m: &RoughDielectric) {
        self.distribution.set(i, &m.distribution);
        self.ior.0[i] = m.ior;
        for (c, tint) in m.tint.to_array().into_iter().enumerate() {
            self.tint[c].0[i] = tint;
        }
    }

    /// `wo` seen from its own side (`z ≥ 0` is outside; a NaN counts as inside).
    #[inline(always)]
    fn orient(&self, wo: &Vec3s<N>) -> Oriented<N> {
        let outside = wo.z.ge(F32s::ZERO);
        Oriented {
            wo: Vec3s::select(outside, wo, &wo.neg()),
            sign: F32s::select(outside, F32s::ONE, F32s::splat(-1.0)),
            eta: F32s::select(outside, self.ior, 1.0 / self.ior),
        }
    }

    /// `v · sign` per component.
    #[inline(always)]
    fn signed(v: &Vec3s<N>, sign: F32s<N>) -> Vec3s<N> {
        Vec3s { x: v.x * sign, y: v.y * sign, z: v.z * sign }
    }

    /// `tint · x` per channel.
    #[inline(always)]
    fn tinted(&self, x: F32s<N>) -> [F32s<N>; 3] {
        [self.tint[0] * x, self.tint[1] * x, self.tint[2] * x]
    }
}

impl<const N: usize> LaneScattering<N> for RoughDielectricLanes<N> {
    /// The side wo comes from decides whether light enters or leaves: the frame is never
    /// turned over.
    const TWO_SIDED: bool = false;

    /// A visible normal m of wo, then reflection about m with probability F(wo·m), refraction
    /// through it otherwise; the weight is the tint times G1(wi, m) (over η² through m).
    #[inline(always)]
    fn sample(&self, wo: &Vec3s<N>, u_lobe: F32s<N>, u1: F32s<N>, u2: F32s<N>, active: Ms<N>) -> LaneSamples<N> {
        let zero = F32s::ZERO;
        let active = active & !wo.z.eq(zero);
        let o = self.orient(wo);
        let m = self.distribution.sample_visible(&o.wo, u1, u2, active);
        let cos_om = o.wo.dot(&m);
        // `!(x <= 0)` keeps the scalar rule for NaN.
        let active = active & !cos_om.le(zero);
        let pdf_m = self.distribution.pdf_visible(&o.wo, &m);
        let (f, cos_t, eta) = fresnel_dielectric_lanes(cos_om, o.eta);
        let reflect = u_lobe.lt(f);
        let reflected = reflect_about_lanes(&o.wo, &m);
        let refracted = refract_about_lanes(&o.wo, &m, cos_om, cos_t, eta);
        let wi = Vec3s::select(reflect, &reflected, &refracted);
        let g1 = self.distribution.g1(&wi, &m);
        // Reflection: pdf F·D_v/(4 wo·m). Refraction: the Jacobian η²|wi·m|/(wo·m + η wi·m)²
        // (Walter 2007 eq. 17).
        let pdf_reflect = f * pdf_m / (4.0 * cos_om);
        let cos_im = refracted.dot(&m);
        let denom = cos_om + eta * cos_im;
        let pdf_refract = (1.0 - f) * pdf_m * eta * eta * cos_im.abs() / (denom * denom);
        let pdf = F32s::select(reflect, pdf_reflect, pdf_refract);
        let sides = (reflect & !reflected.z.le(zero)) | (!reflect & !refracted.z.ge(zero));
        LaneSamples {
            valid: active & sides & pdf.gt(zero),
            wi: Self::signed(&wi, o.sign),
            weight: self.tinted(F32s::select(reflect, g1, g1 / (eta * eta))),
            pdf,
            specular: Ms::NONE,
            eta: F32s::select(reflect, F32s::ONE, eta),
        }
    }

    /// f·cos θi and the density of `wi` per lane, through the microfacet normal joining wo and
    /// wi (zero where none can, Walter 2007 §5.3: neither direction may see m's back).
    #[inline(always)]
    fn eval_pdf(&self, wo: &Vec3s<N>, wi: &Vec3s<N>) -> ([F32s<N>; 3], F32s<N>) {
        let zero = F32s::ZERO;
        let o = self.orient(wo);
        let wi = Self::signed(wi, o.sign);
        // The half vector: wo + wi for reflection, the generalised wo + η wi for refraction.
        let reflect = wi.z.gt(zero);
        let eta_wi = Vec3s { x: o.eta * wi.x, y: o.eta * wi.y, z: o.eta * wi.z };
        let h = o.wo.add(&Vec3s::select(reflect, &wi, &eta_wi));
        let m = Self::signed(&h.normalize(), h.z.signum());
        let cos_om = o.wo.dot(&m);
        let cos_im = wi.dot(&m);
        let connects = m.x.is_finite()
            & m.y.is_finite()
            & m.z.is_finite()
            & m.z.gt(zero)
            & cos_om.gt(zero)
            & (cos_im * wi.z).gt(zero);
        let ok = connects & !wo.z.eq(zero) & !wi.z.eq(zero);
        let f = fresnel_dielectric_lanes(cos_om, o.eta).0;
        let d = self.distribution.d(&m);
        let g1_o = self.distribution.g1(&o.wo, &m);
        let dg = d * (g1_o * self.distribution.g1(&wi, &m));
        let denom = cos_om + o.eta * cos_im;
        let value_reflect = f * dg / (4.0 * o.wo.z);
        let value_refract = (1.0 - f) * dg * (cos_im * cos_om).abs() / (o.wo.z * denom * denom);
        let value = F32s::select(reflect, value_reflect, value_refract);
        // `f32::max`, whose NaN and signed-zero rules the scalar form had.
        let value = F32s::from_fn(|i| value.0[i].max(0.0));
        let pdf_m = self.distribution.pdf_visible(&o.wo, &m);
        let pdf_reflect = f * pdf_m / (4.0 * cos_om);
        let pdf_refract = (1.0 - f) * pdf_m * o.eta * o.eta * cos_im.abs() / (denom * denom);
        let pdf = F32s::select(reflect, pdf_reflect, pdf_refract);
        (map_rgb(self.tinted(value), |c| F32s::select(ok, c, zero)), F32s::select(ok, pdf, zero))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::lane_checks::{assert_smooth_lanes_match, Numbers};
    use crate::material::MicrofacetKind;

    /// Each lane of a group of mixed rough dielectrics (both distributions, several roughnesses
    /// and indices), seen from outside and inside, gives the bits of its own one-lane
    /// evaluation and sample, through reflection and refraction.
    #[test]
    fn lanes_of_mixed_rough_dielectrics_match_each_scalar_one() {
        const N: usize = 8;
        let glass = |i: usize| {
            let kind = if i.is_multiple_of(2) { MicrofacetKind::Beckmann } else { MicrofacetKind::Ggx };
            let distribution = Microfacet::isotropic(kind, [0.02, 0.1, 0.3, 0.7][i % 4]);
            RoughDielectric {
                distribution,
                ior: 1.2 + 0.15 * i as f32,
                tint: Rgb::new(1.0, 0.9, 0.8 - 0.05 * i as f32),
            }
        };
        let mut lanes = glass(0).lanes::<N>();
        for i in 0..N {
            lanes.set(i, &glass(i));
        }
        let (mut reflected, mut refracted, mut evaluated) = (0, 0, 0);
        let mut numbers = Numbers::new(0x2545_f491);
        assert_smooth_lanes_match(
            &lanes,
            glass,
            &mut numbers,
            300,
            |n| n.direction(-1.0, 2.0),
            |wo, pdf, one| {
                evaluated += usize::from(pdf > 0.0);
                match one {
                    Some(one) if one.wi.z * wo.z > 0.0 => reflected += 1,
                    Some(_) => refracted += 1,
                    None => {}
                }
            },
        );
        assert!(reflected > 100 && refracted > 1000 && evaluated > 1000, "{reflected} {refracted} {evaluated}");
    }
}
