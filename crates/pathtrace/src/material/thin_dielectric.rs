//! `thindielectric`: a thin slab of glass (a window pane), as Mitsuba 3's `thindielectric`.
//! Light reflects off the front face or passes straight through, with the interreflections
//! inside the slab summed in closed form: with R the Fresnel reflectance of one interface and
//! T = 1 − R, the slab reflects R' = R + T²R/(1 − R²) (the geometric series R + T²R + T²R³ + …)
//! and transmits T' = 1 − R'. The two refractions cancel, so the transmitted ray continues along
//! −wo with no offset and no change of η (Mitsuba 3, src/bsdfs/thindielectric.cpp).

use super::{fresnel_dielectric, BsdfSample};
use crate::math::{Rgb, Vec3};

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
        let (r, _, _) = fresnel_dielectric(cos_theta.abs(), self.ior);
        if r >= 1.0 {
            return 1.0;
        }
        let t = 1.0 - r;
        r + t * t * r / (1.0 - r * r)
    }

    /// Reflects with probability R', else passes straight through; both lobes are Dirac deltas,
    /// so the weight is the tint alone.
    pub fn sample(&self, wo: Vec3, u_lobe: f32) -> Option<BsdfSample> {
        let r = self.reflectance(wo.z);
        if u_lobe < r {
            let wi = Vec3::new(-wo.x, -wo.y, wo.z);
            Some(BsdfSample { wi, weight: self.tint, pdf: r, delta: true, eta: 1.0 })
        } else {
            Some(BsdfSample { wi: -wo, weight: self.tint, pdf: 1.0 - r, delta: true, eta: 1.0 })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_incidence_matches_the_slab_series() {
        // R = 0.04 for η = 1.5, so R' = 0.04 + 0.96²·0.04/(1 − 0.0016) = 2R/(1 + R) ≈ 0.076923.
        let slab = ThinDielectric { ior: 1.5, tint: Rgb::WHITE };
        assert!((slab.reflectance(1.0) - 2.0 * 0.04 / 1.04).abs() < 1e-6);
        assert_eq!(slab.reflectance(-1.0), slab.reflectance(1.0));
    }
}
