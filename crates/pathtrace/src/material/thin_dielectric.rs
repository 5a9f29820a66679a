//! `thindielectric`: a thin slab of glass (a window pane), as Mitsuba 3's `thindielectric`.
//! Light reflects off the front face or passes straight through, with the interreflections
//! inside the slab summed in closed form: with R the Fresnel reflectance of one interface and
//! T = 1 − R, the slab reflects R' = R + T²R/(1 − R²) (the geometric series R + T²R + T²R³ + …)
//! and transmits T' = 1 − R'. The two refractions cancel, so the transmitted ray continues along
//! −wo with no offset and no change of η (Mitsuba 3, src/bsdfs/thindielectric.cpp).

use super::dielectric::fresnel_dielectric_lanes;
use super::lanes::{DeltaModel, LaneDeltaScattering, LaneSamples};
use super::reflect_local_lanes;
use crate::math::Rgb;
use crate::wide::simd::{F32s, Ms, Vec3s};

/// Thin dielectric slab of index `ior` (relative to the outside).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThinDielectric {
    pub ior: f32,
    /// Colour multiplied into both lobes (white for clear glass).
    pub tint: Rgb,
}

impl ThinDielectric {
    /// Slab reflectance R' at incidence cosine `cos_theta` (either side: the slab is symmetric).
    pub fn reflectance(&self, cos_theta: f32) -> f32 {
        self.lanes::<1>().reflectance(F32s([cos_theta])).0[0]
    }
}

impl DeltaModel for ThinDielectric {
    type Lanes<const N: usize> = ThinDielectricLanes<N>;

    /// This slab in every lane (its scalar sample, a reflection with probability R', else
    /// straight through, is the one-lane instance of [`ThinDielectricLanes::sample`]).
    #[inline(always)]
    fn lanes<const N: usize>(&self) -> ThinDielectricLanes<N> {
        ThinDielectricLanes { ior: F32s::splat(self.ior), tint: self.tint.to_array().map(F32s::splat) }
    }
}

/// Thin dielectric slabs per lane (lanes can hold different ones), the tint's channels as lane
/// groups.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ThinDielectricLanes<const N: usize> {
    pub ior: F32s<N>,
    pub tint: [F32s<N>; 3],
}

impl<const N: usize> ThinDielectricLanes<N> {
    /// Lane `i` holds `m`.
    #[inline(always)]
    pub fn set(&mut self, i: usize, m: &ThinDielectric) {
        self.ior.0[i] = m.ior;
        for (c, tint) in m.tint.to_array().into_iter().enumerate() {
            self.tint[c].0[i] = tint;
        }
    }

    /// R' per lane: 1 where one interface already reflects everything.
    #[inline(always)]
    fn reflectance(&self, cos_theta: F32s<N>) -> F32s<N> {
        let r = fresnel_dielectric_lanes(cos_theta.abs(), self.ior).0;
        let t = 1.0 - r;
        F32s::select(r.ge(F32s::ONE), F32s::ONE, r + t * t * r / (1.0 - r * r))
    }
}

impl<const N: usize> LaneDeltaScattering<N> for ThinDielectricLanes<N> {
    const TWO_SIDED: bool = true;

    /// Per lane of `active`: the mirror direction when `u_lobe < R'`, else straight on (−wo);
    /// both lobes are Dirac deltas, so the weight is the tint alone.
    #[inline(always)]
    fn sample(&self, wo: &Vec3s<N>, u_lobe: F32s<N>, active: Ms<N>) -> LaneSamples<N> {
        let r = self.reflectance(wo.z);
        let reflect = u_lobe.lt(r);
        LaneSamples {
            valid: active,
            wi: Vec3s::select(reflect, &reflect_local_lanes(wo), &wo.neg()),
            weight: self.tint,
            pdf: F32s::select(reflect, r, 1.0 - r),
            specular: active,
            eta: F32s::ONE,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::lane_checks::{assert_delta_lanes_match, Numbers};

    #[test]
    fn normal_incidence_matches_the_slab_series() {
        // R = 0.04 for η = 1.5, so R' = 0.04 + 0.96²·0.04/(1 − 0.0016) = 2R/(1 + R) ≈ 0.076923.
        let slab = ThinDielectric { ior: 1.5, tint: Rgb::WHITE };
        assert!((slab.reflectance(1.0) - 2.0 * 0.04 / 1.04).abs() < 1e-6);
        assert_eq!(slab.reflectance(-1.0), slab.reflectance(1.0));
    }

    /// Each lane of a group of mixed slabs, seen from both sides, gives the bits of its own
    /// one-lane sample, through both lobes.
    #[test]
    fn lanes_of_mixed_slabs_match_each_scalar_one() {
        const N: usize = 8;
        let slab =
            |i: usize| ThinDielectric { ior: 1.1 + 0.2 * i as f32, tint: Rgb::new(1.0, 0.9, 0.8 - 0.05 * i as f32) };
        let mut lanes = slab(0).lanes::<N>();
        for i in 0..N {
            lanes.set(i, &slab(i));
        }
        let (mut reflected, mut through) = (0, 0);
        let mut numbers = Numbers::new(0x1234_5679);
        let one_lane = |i: usize, wo, u| slab(i).sample(wo, u);
        assert_delta_lanes_match(
            &lanes,
            one_lane,
            &mut numbers,
            200,
            |n| n.direction(-1.0, 2.0),
            |_, wo, one| {
                let one = one.expect("a slab always scatters");
                assert!(one.delta);
                if one.wi == -wo {
                    through += 1;
                } else {
                    reflected += 1;
                }
            },
        );
        assert!(reflected > 100 && through > 1000, "{reflected} {through}");
    }
}
