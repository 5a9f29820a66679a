//! `mirror`: perfect specular reflection R = L - 2(L·N)N, scaled by a reflectance colour.
//! Its lane form is the smooth conductor's ([`super::conductor::SmoothConductorLanes`]),
//! without the Fresnel factor.

use super::conductor::SmoothConductorLanes;
use super::lanes::LaneDeltaScattering;
use super::BsdfSample;
use crate::math::{Rgb, Vec3};
use crate::wide::simd::{F32s, Ms, Vec3s};

/// A perfect mirror.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mirror {
    pub reflectance: Rgb,
}

impl Mirror {
    /// The mirror direction, weighted by the reflectance: the one-lane instance of the lane form.
    pub fn sample(&self, wo: Vec3) -> Option<BsdfSample> {
        let mut lanes = SmoothConductorLanes::<1>::none();
        lanes.set_mirror(0, self);
        lanes.sample(&Vec3s::splat(wo), F32s::ZERO, Ms::ALL).lane(0)
    }
}
