//! `mirror`: perfect specular reflection R = L - 2(L·N)N, scaled by a reflectance colour.

use super::{reflect_local, BsdfSample};
use crate::math::{Rgb, Vec3};

/// A perfect mirror.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mirror {
    pub reflectance: Rgb,
}

impl Mirror {
    pub fn sample(&self, wo: Vec3) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        Some(BsdfSample { wi: reflect_local(wo), weight: self.reflectance, pdf: 1.0, delta: true, eta: 1.0 })
    }
}
