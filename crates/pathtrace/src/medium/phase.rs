//! Phase functions: the angular distribution of light scattered inside a medium.
//!
//! Directions follow the surface convention of `material`: `wo` points back along the path
//! (towards the previous vertex, Mitsuba's `mi.wi`), `wi` is the new direction. The scattering
//! angle θ is measured between the propagation direction −wo and wi, so cos θ = −wo·wi, and
//! `g > 0` scatters forwards, as Mitsuba 3's `hg` (src/phase/hg.cpp) and pbrt-v4 §11.3.1.
//!
//! Every phase function here is sampled exactly by its own density, so a sample's weight
//! f/pdf is 1.

use crate::math::{Frame, Vec2, Vec3, INV_4PI, PI};
use crate::sampling::warp::square_to_uniform_sphere;

/// A phase function.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PhaseFunction {
    /// 1/(4π) in every direction (Mitsuba's `isotropic`).
    Isotropic,
    /// Henyey–Greenstein with asymmetry `g` ∈ (−1, 1), the mean cosine of the scattering angle
    /// (Mitsuba's `hg`; its default is 0.8).
    HenyeyGreenstein { g: f32 },
}

/// A sampled direction and its density (= the phase function's value).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhaseSample {
    pub wi: Vec3,
    pub pdf: f32,
}

/// |g| below this is treated as isotropic when sampling (the inversion divides by g).
const ISOTROPIC_G: f32 = 1e-3;

impl PhaseFunction {
    /// Why a Henyey–Greenstein `g` is unusable, if it is.
    pub fn check_g(g: f32) -> Result<(), String> {
        if g.is_finite() && g > -1.0 && g < 1.0 {
            Ok(())
        } else {
            Err(format!("the Henyey–Greenstein asymmetry g = {g} must lie strictly between −1 and 1"))
        }
    }

    /// The phase function's value for light arriving along −`wo` scattered into `wi`
    /// (both unit vectors); it is also the solid-angle density of [`PhaseFunction::sample`].
    #[inline]
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> f32 {
        match *self {
            PhaseFunction::Isotropic => INV_4PI,
            PhaseFunction::HenyeyGreenstein { g } => henyey_greenstein(-wo.dot(wi), g),
        }
    }

    /// Samples `wi` from the phase function for the path arriving along −`wo`.
    #[inline]
    pub fn sample(&self, wo: Vec3, u: Vec2) -> PhaseSample {
        match *self {
            PhaseFunction::Isotropic => PhaseSample { wi: square_to_uniform_sphere(u), pdf: INV_4PI },
            PhaseFunction::HenyeyGreenstein { g } => {
                // Inverting the cdf of cos θ (pbrt-v4 §11.3.1, eq. 11.11's inverse; Mitsuba's form).
                let cos_theta = if g.abs() < ISOTROPIC_G {
                    1.0 - 2.0 * u.x
                } else {
                    let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u.x);
                    ((1.0 + g * g - s * s) / (2.0 * g)).clamp(-1.0, 1.0)
                };
                let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
                let phi = 2.0 * PI * u.y;
                // θ is measured from the propagation direction −wo.
                let frame = Frame::from_normal(-wo);
                let wi = frame.to_world(Vec3::new(sin_theta * phi.cos(), sin_theta * phi.sin(), cos_theta));
                PhaseSample { wi, pdf: henyey_greenstein(cos_theta, g) }
            }
        }
    }
}

/// p(θ) = (1 − g²) / (4π (1 + g² − 2g cos θ)^{3/2}) (Henyey & Greenstein 1941).
#[inline]
fn henyey_greenstein(cos_theta: f32, g: f32) -> f32 {
    let denom = 1.0 + g * g - 2.0 * g * cos_theta;
    INV_4PI * (1.0 - g * g) / (denom * denom.max(0.0).sqrt())
}
