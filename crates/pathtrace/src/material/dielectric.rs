//! `dielectric`: smooth glass. Reflects with the exact unpolarised Fresnel reflectance and
//! refracts by Snell's law otherwise, choosing between the two with probability F; past the
//! critical angle it reflects totally. Refracted radiance is scaled by 1/η² (radiance
//! compresses into the denser medium; Veach's thesis §5.2), so a closed glass object is
//! energy-neutral.

use super::lanes::{DeltaModel, LaneDeltaScattering, LaneSamples};
use super::reflect_local_lanes;
use crate::math::Rgb;
use crate::wide::simd::{map_rgb, F32s, Ms, Vec3s};

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

impl DeltaModel for Dielectric {
    type Lanes<const N: usize> = DielectricLanes<N>;

    /// This material in every lane (its scalar sample, a reflection with probability F, else
    /// the refraction, is the one-lane instance of [`DielectricLanes::sample`]).
    #[inline(always)]
    fn lanes<const N: usize>(&self) -> DielectricLanes<N> {
        DielectricLanes { ior: F32s::splat(self.ior), tint: self.tint.to_array().map(F32s::splat) }
    }
}

/// A smooth dielectric per lane (lanes can hold different ones), the tint's channels as lane
/// groups.
#[derive(Clone, Copy, Debug)]
pub(crate) struct DielectricLanes<const N: usize> {
    pub ior: F32s<N>,
    pub tint: [F32s<N>; 3],
}

impl<const N: usize> DielectricLanes<N> {
    /// Lane `i` holds `m`.
    #[inline(always)]
    pub fn set(&mut self, i: usize, m: &Dielectric) {
        self.ior.0[i] = m.ior;
        for (c, tint) in m.tint.to_array().into_iter().enumerate() {
            self.tint[c].0[i] = tint;
        }
    }
}

impl<const N: usize> LaneDeltaScattering<N> for DielectricLanes<N> {
    const TWO_SIDED: bool = false;

    /// Per lane of `active`: the mirror direction when `u_lobe < F`, else the refracted one.
    #[inline(always)]
    fn sample(&self, wo: &Vec3s<N>, u_lobe: F32s<N>, active: Ms<N>) -> LaneSamples<N> {
        let (f, cos_t, eta) = fresnel_dielectric_lanes(wo.z, self.ior);
        let reflect = u_lobe.lt(f);
        let mirrored = reflect_local_lanes(wo);
        // Snell: wi = -wo/η + (cos θo/η - cos θt)·n with n on wo's side; the tangential part is
        // -wo/η and the normal part -cos θt·n (the two cos θo terms cancel). `!(z >= 0)` puts
        // a NaN on the inside, as the comparison does.
        let minus_n_sign = F32s::select(wo.z.ge(F32s::ZERO), F32s::splat(-1.0), F32s::ONE);
        let refracted = Vec3s { x: -wo.x / eta, y: -wo.y / eta, z: minus_n_sign * cos_t }.normalize();
        // Radiance compresses by 1/η² into the denser medium.
        let compression = 1.0 / (eta * eta);
        LaneSamples {
            valid: active,
            wi: Vec3s::select(reflect, &mirrored, &refracted),
            weight: map_rgb(self.tint, |c| F32s::select(reflect, c, c * compression)),
            pdf: F32s::select(reflect, f, 1.0 - f),
            specular: active,
            eta: F32s::select(reflect, F32s::ONE, eta),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::lane_checks::{assert_delta_lanes_match, Numbers};
    use crate::math::Vec3;

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

    /// Each lane of a group of mixed dielectrics, seen from outside and inside (past the
    /// critical angle too), gives the bits of its own one-lane sample.
    #[test]
    fn lanes_of_mixed_dielectrics_match_each_scalar_one() {
        const N: usize = 8;
        let glass =
            |i: usize| Dielectric { ior: 1.1 + 0.15 * i as f32, tint: Rgb::new(1.0, 0.9 - 0.05 * i as f32, 0.8) };
        let mut lanes = glass(0).lanes::<N>();
        for i in 0..N {
            lanes.set(i, &glass(i));
        }
        let (mut reflected, mut refracted, mut total) = (0, 0, 0);
        let mut numbers = Numbers::new(0x2545_f491);
        let one_lane = |i: usize, wo, u| glass(i).sample(wo, u);
        assert_delta_lanes_match(
            &lanes,
            one_lane,
            &mut numbers,
            300,
            |n| n.direction(-1.0, 2.0),
            |_, wo, one| {
                let one = one.expect("a dielectric always scatters");
                assert!(one.delta);
                if one.wi.z * wo.z > 0.0 {
                    reflected += 1;
                    total += usize::from(one.pdf == 1.0);
                } else {
                    refracted += 1;
                }
            },
        );
        assert!(reflected > 100 && refracted > 1000 && total > 50, "{reflected} {refracted} {total}");
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
