//! `conductor`: a smooth metal. Perfect specular reflection weighted by the exact conductor
//! Fresnel reflectance per RGB channel (complex index η + ik, e.g. from [`super::metal`]),
//! times an optional `reflectance` tint (Mitsuba's `specular_reflectance`).
//!
//! Its lane form [`SmoothConductorLanes`] serves the `mirror` too: a mirror is a smooth
//! reflector without the Fresnel factor.

use super::fresnel::fresnel_conductor_rgb_lanes;
use super::lanes::{DeltaModel, LaneDeltaScattering, LaneSamples};
use super::{reflect_local_lanes, Mirror};
use crate::math::Rgb;
use crate::wide::simd::{F32s, Ms, Vec3s};

/// A smooth conductor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conductor {
    /// Real part of the relative index of refraction, per channel.
    pub eta: Rgb,
    /// Imaginary part (absorption), per channel.
    pub k: Rgb,
    /// Multiplies the Fresnel reflectance (1 for a physical metal).
    pub reflectance: Rgb,
}

impl DeltaModel for Conductor {
    type Lanes<const N: usize> = SmoothConductorLanes<N>;

    /// This conductor in every lane (its scalar sample, the mirror direction weighted by the
    /// Fresnel reflectance, is the one-lane instance of [`SmoothConductorLanes::sample`]).
    #[inline(always)]
    fn lanes<const N: usize>(&self) -> SmoothConductorLanes<N> {
        let mut lanes = SmoothConductorLanes::none();
        for i in 0..N {
            lanes.set_conductor(i, self);
        }
        lanes
    }
}

/// Smooth conductors and mirrors per lane (lanes can hold different ones), RGB channels as lane
/// groups.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SmoothConductorLanes<const N: usize> {
    pub eta: [F32s<N>; 3],
    pub k: [F32s<N>; 3],
    pub reflectance: [F32s<N>; 3],
    /// Lanes holding a mirror: their reflectance is not multiplied by a Fresnel term.
    pub mirror: Ms<N>,
}

impl<const N: usize> SmoothConductorLanes<N> {
    /// Mirrors of reflectance 0 in every lane, to be set lane by lane.
    #[inline(always)]
    pub fn none() -> Self {
        let zero = [F32s::ZERO; 3];
        SmoothConductorLanes { eta: zero, k: zero, reflectance: zero, mirror: Ms::ALL }
    }

    /// Lane `i` holds the conductor `m`.
    #[inline(always)]
    pub fn set_conductor(&mut self, i: usize, m: &Conductor) {
        for c in 0..3 {
            self.eta[c].0[i] = m.eta.to_array()[c];
            self.k[c].0[i] = m.k.to_array()[c];
            self.reflectance[c].0[i] = m.reflectance.to_array()[c];
        }
        self.mirror.0[i] = 0;
    }

    /// Lane `i` holds the mirror `m`.
    #[inline(always)]
    pub fn set_mirror(&mut self, i: usize, m: &Mirror) {
        for c in 0..3 {
            self.reflectance[c].0[i] = m.reflectance.to_array()[c];
        }
        self.mirror.0[i] = u32::MAX;
    }
}

impl<const N: usize> LaneDeltaScattering<N> for SmoothConductorLanes<N> {
    const TWO_SIDED: bool = true;

    /// The mirror direction of the lanes of `active` seen from the front (cos θo > 0),
    /// weighted by the reflectance times, for conductors, the Fresnel reflectance at cos θo.
    #[inline(always)]
    fn sample(&self, wo: &Vec3s<N>, _u_lobe: F32s<N>, active: Ms<N>) -> LaneSamples<N> {
        // `!(z <= 0)` keeps the scalar rule for NaN.
        let valid = active & !wo.z.le(F32s::ZERO);
        let conductors = valid & !self.mirror;
        let weight = if conductors.any() {
            let f = fresnel_conductor_rgb_lanes(wo.z, self.eta, self.k);
            // Channels written out, as in `fresnel_conductor_rgb_lanes`.
            let r = &self.reflectance;
            [
                F32s::select(self.mirror, r[0], r[0] * f[0]),
                F32s::select(self.mirror, r[1], r[1] * f[1]),
                F32s::select(self.mirror, r[2], r[2] * f[2]),
            ]
        } else {
            self.reflectance
        };
        LaneSamples { valid, wi: reflect_local_lanes(wo), weight, pdf: F32s::ONE, specular: valid, eta: F32s::ONE }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::lane_checks::{assert_delta_lanes_match, Numbers};
    use crate::material::metal;
    use crate::math::Vec3;

    /// Each lane of a group mixing conductors and mirrors, seen from the front and from
    /// behind, gives the bits of its own one-lane sample.
    #[test]
    fn lanes_of_mixed_conductors_and_mirrors_match_each_scalar_one() {
        const N: usize = 8;
        let names = ["Cu", "Au", "Al", "Ag"];
        let conductor = |i: usize| {
            let (eta, k) = metal(names[i % 4]).unwrap();
            Conductor {
                eta: Rgb::from_array(eta),
                k: Rgb::from_array(k),
                reflectance: Rgb::new(1.0, 0.95 - 0.05 * i as f32, 0.9),
            }
        };
        let mirror = |i: usize| Mirror { reflectance: Rgb::new(0.9, 0.8, 0.7 - 0.05 * i as f32) };
        let mut lanes = SmoothConductorLanes::<N>::none();
        for i in 0..N {
            if i % 3 == 0 {
                lanes.set_mirror(i, &mirror(i));
            } else {
                lanes.set_conductor(i, &conductor(i));
            }
        }
        let one_lane =
            |i: usize, wo, u| if i.is_multiple_of(3) { mirror(i).sample(wo, u) } else { conductor(i).sample(wo, u) };
        let mut seen = [0usize; 3];
        let mut numbers = Numbers::new(0x9e37_79b9);
        assert_delta_lanes_match(
            &lanes,
            one_lane,
            &mut numbers,
            200,
            |n| n.direction(-0.6, 2.0),
            |i, _, one| {
                assert!(one.is_none_or(|s| s.delta));
                seen[if one.is_none() { 2 } else { usize::from(i % 3 != 0) }] += 1;
            },
        );
        assert!(seen.iter().all(|&n| n > 100), "{seen:?}");
    }

    #[test]
    fn a_conductor_reflects_its_fresnel_reflectance() {
        let (eta, k) = metal("Au").unwrap();
        let (eta, k) = (Rgb::from_array(eta), Rgb::from_array(k));
        let gold = Conductor { eta, k, reflectance: Rgb::WHITE };
        let wo = Vec3::new(0.6, 0.0, 0.8);
        let s = gold.sample(wo, 0.5).unwrap();
        assert_eq!(s.wi, Vec3::new(-0.6, 0.0, 0.8));
        let expected = crate::material::fresnel::fresnel_conductor_rgb(0.8, eta, k);
        assert_eq!(s.weight, expected);
        assert!(gold.sample(Vec3::new(0.6, 0.0, -0.8), 0.5).is_none());
    }
}
