//! `conductor`: a smooth metal. Perfect specular reflection weighted by the exact conductor
//! Fresnel reflectance per RGB channel (complex index η + ik, e.g. from [`super::metal`]),
//! times an optional `reflectance` tint (Mitsuba's `specular_reflectance`).

use super::fresnel::fresnel_conductor_rgb;
use super::{reflect_local, BsdfSample};
use crate::math::{Rgb, Vec3};

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
    pub fn sample(&self, wo: Vec3) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let weight = self.reflectance * fresnel_conductor_rgb(wo.z, self.eta, self.k);
        Some(BsdfSample { wi: reflect_local(wo), weight, pdf: 1.0, delta: true, eta: 1.0 })
    }
}
