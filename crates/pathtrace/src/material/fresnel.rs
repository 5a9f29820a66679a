//! Fresnel reflectance of a conductor (the dielectric one lives with `dielectric`).

use crate::math::Rgb;
use crate::wide::simd::F32s;

/// Unpolarised Fresnel reflectance of a conductor with complex relative index η + ik, from the
/// cosine of the incident angle (≥ 0). Exact closed form for the s and p amplitudes
/// (Born & Wolf §14.2; written as in pbrt-v3 `FrConductor`, after Lazányi & Szirmay-Kalos).
pub fn fresnel_conductor(cos_theta_i: f32, eta: f32, k: f32) -> f32 {
    fresnel_conductor_lanes(F32s([cos_theta_i]), F32s([eta]), F32s([k])).0[0]
}

/// [`fresnel_conductor`] per RGB channel.
pub fn fresnel_conductor_rgb(cos_theta_i: f32, eta: Rgb, k: Rgb) -> Rgb {
    let lanes = |c: Rgb| c.to_array().map(|x| F32s([x]));
    let [r, g, b] = fresnel_conductor_rgb_lanes(F32s([cos_theta_i]), lanes(eta), lanes(k));
    Rgb::new(r.0[0], g.0[0], b.0[0])
}

/// [`fresnel_conductor`] in every lane (the scalar form is its one-lane instance).
#[inline(always)]
pub(crate) fn fresnel_conductor_lanes<const N: usize>(cos_theta_i: F32s<N>, eta: F32s<N>, k: F32s<N>) -> F32s<N> {
    let c = clamp_unit(cos_theta_i);
    let cos2 = c * c;
    let sin2 = 1.0 - cos2;
    let (eta2, k2) = (eta * eta, k * k);
    let t0 = eta2 - k2 - sin2;
    let a2_plus_b2 = (t0 * t0 + 4.0 * eta2 * k2).sqrt();
    let t1 = a2_plus_b2 + cos2;
    let a = (0.5 * (a2_plus_b2 + t0)).max(F32s::ZERO).sqrt();
    let t2 = 2.0 * c * a;
    let rs = (t1 - t2) / (t1 + t2);
    let t3 = cos2 * a2_plus_b2 + sin2 * sin2;
    let t4 = t2 * sin2;
    let rp = rs * (t3 - t4) / (t3 + t4);
    let f = 0.5 * (rp + rs);
    F32s::select(f.is_finite(), clamp_unit(f), F32s::ONE)
}

/// [`fresnel_conductor_lanes`] per RGB channel.
#[inline(always)]
pub(crate) fn fresnel_conductor_rgb_lanes<const N: usize>(
    cos_theta_i: F32s<N>,
    eta: [F32s<N>; 3],
    k: [F32s<N>; 3],
) -> [F32s<N>; 3] {
    // Channels written out: `array::from_fn`, or a closure per channel, was compiled out of
    // the SIMD kernels (as a function for baseline SSE).
    [
        fresnel_conductor_lanes(cos_theta_i, eta[0], k[0]),
        fresnel_conductor_lanes(cos_theta_i, eta[1], k[1]),
        fresnel_conductor_lanes(cos_theta_i, eta[2], k[2]),
    ]
}

/// `x.clamp(0, 1)` per lane, NaN kept (as `f32::clamp`).
#[inline(always)]
fn clamp_unit<const N: usize>(x: F32s<N>) -> F32s<N> {
    let x = F32s::select(x.lt(F32s::ZERO), F32s::ZERO, x);
    F32s::select(x.gt(F32s::ONE), F32s::ONE, x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::fresnel_dielectric;

    #[test]
    fn normal_incidence_matches_the_closed_form() {
        // F0 = ((η−1)² + k²)/((η+1)² + k²).
        let (eta, k) = (0.2f32, 3.0f32);
        let f0 = ((eta - 1.0).powi(2) + k * k) / ((eta + 1.0).powi(2) + k * k);
        assert!((fresnel_conductor(1.0, eta, k) - f0).abs() < 1e-6);
        assert!((fresnel_conductor(0.0, eta, k) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn zero_absorption_is_the_dielectric_formula_and_none_is_a_mirror() {
        for c in [0.05f32, 0.3, 0.7, 1.0] {
            let (fd, _, _) = fresnel_dielectric(c, 1.5);
            assert!((fresnel_conductor(c, 1.5, 0.0) - fd).abs() < 1e-5, "cos {c}");
            assert!((fresnel_conductor(c, 0.0, 1.0) - 1.0).abs() < 1e-6);
        }
    }
}
