//! `dielectric`: smooth glass. Reflects with the exact unpolarised Fresnel reflectance and
//! refracts by Snell's law otherwise, choosing between the two with probability F; past the
//! critical angle it reflects totally. Refracted radiance is scaled by 1/η² (radiance
//! compresses into the denser medium; Veach's thesis §5.2), so a closed glass object is
//! energy-neutral.

use super::BsdfSample;
use crate::math::{Rgb, Vec3};
use crate::wide::simd::F32s;

/// Smooth dielectric interface with interior index of refraction `ior` (exterior 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dielectric {
    pub ior: f32,
    /// Colour multiplied into both lobes (white for clear glass).
    pub tint: Rgb,
}

/// Fresnel reflectance of a smooth dielectric for unpolarised light, from the cosine of the
/// incident angle (measured on the incident side, may be negative for inside) and the relative
/// index η = η_inside / η_outside. Returns (F, cos θt, η of the crossing) — cos θt = 0 on total
/// internal reflection. (Born & Wolf; as in pbrt-v4 `FrDielectric`.)
pub fn fresnel_dielectric(cos_theta_i: f32, eta: f32) -> (f32, f32, f32) {
    let (f, cos_t, eta) = fresnel_dielectric_lanes(F32s([cos_theta_i]), F32s([eta]));
    (f.0[0], cos_t.0[0], eta.0[0])
}

/// [`fresnel_dielectric`] in every lane (the scalar form is its one-lane instance).
#[inline(always)]
pub(crate) fn fresnel_dielectric_lanes<const N: usize>(
    cos_theta_i: F32s<N>,
    eta: F32s<N>,
) -> (F32s<N>, F32s<N>, F32s<N>) {
    let inside = cos_theta_i.lt(F32s::ZERO);
    let cos_i = F32s::select(inside, -cos_theta_i, cos_theta_i);
    let eta = F32s::select(inside, 1.0 / eta, eta);
    let sin2_t = (1.0 - cos_i * cos_i).max(F32s::ZERO) / (eta * eta);
    let cos_t = (1.0 - sin2_t).max(F32s::ZERO).sqrt();
    let r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let f = 0.5 * (r_parl * r_parl + r_perp * r_perp);
    // Total internal reflection.
    let total = sin2_t.ge(F32s::ONE);
    (F32s::select(total, F32s::ONE, f), F32s::select(total, F32s::ZERO, cos_t), eta)
}

impl Dielectric {
    pub fn sample(&self, wo: Vec3, u_lobe: f32) -> Option<BsdfSample> {
        let (f, cos_t, eta) = fresnel_dielectric(wo.z, self.ior);
        if u_lobe < f {
            let wi = Vec3::new(-wo.x, -wo.y, wo.z);
            return Some(BsdfSample { wi, weight: self.tint, pdf: f, delta: true, eta: 1.0 });
        }
        // Snell: wi = -wo/η + (cos θo/η - cos θt)·n with n on wo's side; the tangential part is
        // -wo/η and the normal part -cos θt·n (the two cos θo terms cancel).
        let n_sign = if wo.z >= 0.0 { 1.0 } else { -1.0 };
        let wi = Vec3::new(-wo.x / eta, -wo.y / eta, -n_sign * cos_t).normalize();
        Some(BsdfSample { wi, weight: self.tint * (1.0 / (eta * eta)), pdf: 1.0 - f, delta: true, eta })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_incidence_reflectance_matches_the_closed_form() {
        // F0 = ((η - 1)/(η + 1))² = 0.04 for η = 1.5.
        let (f, _, _) = fresnel_dielectric(1.0, 1.5);
        assert!((f - 0.04).abs() < 1e-6);
        let (f_inside, _, _) = fresnel_dielectric(-1.0, 1.5);
        assert!((f_inside - 0.04).abs() < 1e-6);
    }

    #[test]
    fn total_internal_reflection_beyond_the_critical_angle() {
        // From inside glass, sin θc = 1/1.5 → θc ≈ 41.8°; at 60° everything reflects.
        let cos60 = 0.5;
        let (f, cos_t, _) = fresnel_dielectric(-cos60, 1.5);
        assert_eq!(f, 1.0);
        assert_eq!(cos_t, 0.0);
    }

    #[test]
    fn refraction_obeys_snell() {
        let glass = Dielectric { ior: 1.5, tint: Rgb::WHITE };
        let theta_o = 0.6f32;
        let wo = Vec3::new(theta_o.sin(), 0.0, theta_o.cos());
        let s = glass.sample(wo, 0.999).unwrap();
        assert!(s.wi.z < 0.0);
        let sin_t = (s.wi.x * s.wi.x + s.wi.y * s.wi.y).sqrt();
        assert!((theta_o.sin() - 1.5 * sin_t).abs() < 1e-5);
        assert!((s.wi.length() - 1.0).abs() < 1e-5);
        // The refracted direction lies in the plane of incidence, on the far side.
        assert!(s.wi.x < 0.0);
    }
}
