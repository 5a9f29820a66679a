//! `mirror`: perfect specular reflection R = L - 2(L·N)N, scaled by a reflectance colour.
//! Its lane form is the smooth conductor's ([`super::conductor::SmoothConductorLanes`]),
//! without the Fresnel factor.

use super::conductor::SmoothConductorLanes;
use super::lanes::DeltaModel;
use crate::math::Rgb;

/// A perfect mirror.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mirror {
    pub reflectance: Rgb,
}

impl DeltaModel for Mirror {
    type Lanes<const N: usize> = SmoothConductorLanes<N>;

    /// This mirror in every lane (its scalar sample, the mirror direction weighted by the
    /// reflectance, is the one-lane instance of [`SmoothConductorLanes::sample`]).
    #[inline(always)]
    fn lanes<const N: usize>(&self) -> SmoothConductorLanes<N> {
        let mut lanes = SmoothConductorLanes::none();
        for i in 0..N {
            lanes.set_mirror(i, self);
        }
        lanes
    }
}
