//! A homogeneous medium: constant absorption σa and scattering σs per RGB channel (per unit
//! length), as Mitsuba 3's `homogeneous` (src/media/homogeneous.cpp), with its phase function.
//!
//! Transmittance over a distance d is Beer–Lambert's T(d) = exp(−σt·d), σt = σa + σs, per
//! channel. Free-flight distances are sampled as Mitsuba's `volpath` does for chromatic media:
//! one channel c is chosen uniformly and t ~ σt,c·exp(−σt,c·t); the estimator then divides by
//! the average of the three channels' densities (one-sample MIS over the channels), so each
//! channel stays unbiased even though only one channel's density was followed.

use super::PhaseFunction;
use crate::math::Rgb;

/// A medium with constant coefficients.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HomogeneousMedium {
    pub sigma_a: Rgb,
    pub sigma_s: Rgb,
    pub phase: PhaseFunction,
}

/// The outcome of free-flight sampling along a segment of length `t_max`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FreeFlight {
    /// Distance to the sampled interaction; `t_max` (or more) when the segment is crossed.
    pub t: f32,
    /// Whether a medium interaction happens at `t` (inside the segment).
    pub scattered: bool,
    /// The throughput factor of the sample: T(t)·σs / p(t) at an interaction (f = the scattering
    /// albedo-weighted transmittance over the channel-averaged density), T(t_max) / P(t ≥ t_max)
    /// when the segment is crossed.
    pub weight: Rgb,
}

impl HomogeneousMedium {
    /// From the extinction σt (`sigma_t`), the single-scattering albedo σs/σt (`albedo`) and a
    /// density `scale` multiplying σt, as Mitsuba's `homogeneous` takes them.
    pub fn from_extinction(sigma_t: Rgb, albedo: Rgb, scale: f32, phase: PhaseFunction) -> Self {
        let sigma_t = sigma_t * scale;
        let sigma_s = sigma_t * albedo;
        Self { sigma_a: sigma_t - sigma_s, sigma_s, phase }
    }

    /// Why the medium's coefficients are unusable, if they are.
    pub fn check(&self) -> Result<(), String> {
        let ok = |c: Rgb| c.is_finite() && c.to_array().iter().all(|&v| v >= 0.0);
        if !ok(self.sigma_a) || !ok(self.sigma_s) {
            return Err(format!(
                "medium coefficients must be finite and ≥ 0 (σa = {:?}, σs = {:?}); an albedo must lie in [0, 1]",
                self.sigma_a, self.sigma_s
            ));
        }
        match self.phase {
            PhaseFunction::HenyeyGreenstein { g } => PhaseFunction::check_g(g),
            PhaseFunction::Isotropic => Ok(()),
        }
    }

    /// The extinction coefficient σt = σa + σs.
    #[inline]
    pub fn sigma_t(&self) -> Rgb {
        self.sigma_a + self.sigma_s
    }

    /// Beer–Lambert transmittance over a distance `d`: exp(−σt·d) per channel (1 at d = 0, and 0
    /// for an infinite distance through an absorbing channel; a clear channel stays 1).
    #[inline]
    pub fn transmittance(&self, d: f32) -> Rgb {
        self.sigma_t().map(|s| if s == 0.0 { 1.0 } else { (-s * d).exp() })
    }

    /// Samples a free-flight distance along a segment of length `t_max` (∞ for a ray that
    /// leaves the scene): channel `⌊3·u_channel⌋`, then t = −ln(1 − u)/σt,c.
    #[inline]
    pub fn sample_distance(&self, t_max: f32, u_channel: f32, u: f32) -> FreeFlight {
        let sigma_t = self.sigma_t().to_array();
        let c = ((u_channel * 3.0) as usize).min(2);
        let t = if sigma_t[c] > 0.0 { -(1.0 - u).ln() / sigma_t[c] } else { f32::INFINITY };
        let scattered = t < t_max;
        let t_end = if scattered { t } else { t_max };
        let tr = self.transmittance(t_end);
        // The density of the event under the channel mixture: σt,c·T_c(t) for an interaction at
        // t, T_c(t_max) for crossing, averaged over the three equally likely channels.
        let density =
            if scattered { (0..3).map(|k| sigma_t[k] * tr.to_array()[k]).sum::<f32>() / 3.0 } else { tr.average() };
        let weight = if density > 0.0 {
            if scattered {
                tr * self.sigma_s / density
            } else {
                tr / density
            }
        } else {
            Rgb::BLACK
        };
        FreeFlight { t: t_end, scattered, weight }
    }
}
