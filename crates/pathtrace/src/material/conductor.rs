//! `conductor`: a smooth metal. Perfect specular reflection weighted by the exact conductor
//! Fresnel reflectance per RGB channel (complex index η + ik, e.g. from [`super::metal`]),
//! times an optional `reflectance` tint (Mitsuba's `specular_reflectance`).
//!
//! Its lane form [`SmoothConductorLanes`] serves the `mirror` too: a mirror is a smooth
//! reflector without the Fresnel factor.

use super::fresnel::fresnel_conductor_rgb_lanes;
use super::lanes::{LaneDeltaScattering, LaneSamples};
use super::{reflect_local_lanes, BsdfSample, Mirror};
use crate::math::{Rgb, Vec3};
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

impl Conductor {
    /// The mirror direction, weighted by the Fresnel reflectance: the one-lane instance of
    /// [`SmoothConductorLanes::sample`].
    pub fn sample(&self, wo: Vec3) -> Option<BsdfSample> {
        let mut lanes = SmoothConductorLanes::<1>::none();
        lanes.set_conductor(0, self);
        lanes.sample(&Vec3s::splat(wo), F32s::ZERO, Ms::ALL).lane(0)
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
    use crate::material::metal;

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
        let mut x = 0x9e37_79b9u32;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            (x >> 8) as f32 / (1u32 << 24) as f32
        };
        let mut seen = [0usize; 3];
        for _ in 0..200 {
            let wo: [Vec3; N] =
                std::array::from_fn(|_| Vec3::new(next() - 0.5, next() - 0.5, 2.0 * next() - 0.6).normalize());
            let s = lanes.sample(&Vec3s::from_fn(|i| wo[i]), F32s::ZERO, Ms::ALL);
            for (i, &wo_i) in wo.iter().enumerate() {
                let one = if i % 3 == 0 { mirror(i).sample(wo_i) } else { conductor(i).sample(wo_i) };
                assert_eq!(s.valid.lane(i), one.is_some(), "lane {i}, wo {wo_i:?}");
                let Some(one) = one else {
                    seen[2] += 1;
                    continue;
                };
                seen[usize::from(i % 3 != 0)] += 1;
                assert!(s.specular.lane(i) && one.delta);
                assert_eq!(s.wi.lane(i).to_array().map(f32::to_bits), one.wi.to_array().map(f32::to_bits));
                let w = [s.weight[0].0[i], s.weight[1].0[i], s.weight[2].0[i]];
                assert_eq!(w.map(f32::to_bits), one.weight.to_array().map(f32::to_bits));
                assert_eq!([s.pdf.0[i], s.eta.0[i]].map(f32::to_bits), [one.pdf, one.eta].map(f32::to_bits));
            }
        }
        assert!(seen.iter().all(|&n| n > 100), "{seen:?}");
    }

    #[test]
    fn a_conductor_reflects_its_fresnel_reflectance() {
        let (eta, k) = metal("Au").unwrap();
        let (eta, k) = (Rgb::from_array(eta), Rgb::from_array(k));
        let gold = Conductor { eta, k, reflectance: Rgb::WHITE };
        let wo = Vec3::new(0.6, 0.0, 0.8);
        let s = gold.sample(wo).unwrap();
        assert_eq!(s.wi, Vec3::new(-0.6, 0.0, 0.8));
        let expected = crate::material::fresnel::fresnel_conductor_rgb(0.8, eta, k);
        assert_eq!(s.weight, expected);
        assert!(gold.sample(Vec3::new(0.6, 0.0, -0.8)).is_none());
    }
}
