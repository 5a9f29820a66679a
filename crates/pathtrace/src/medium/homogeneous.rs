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
    /// What the event contributes per channel: T(t)·σs at an interaction, T(t_max) when crossed.
    pub throughput: Rgb,
    /// The event's density per channel, had that channel been followed: σt·T(t) at an
    /// interaction, T(t_max) when crossed (the estimator's path-level channel MIS uses these).
    pub density: Rgb,
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
        self.sample_distance_in(t_max, ((u_channel * 3.0) as usize).min(2), u)
    }

    /// Samples a free-flight distance along a segment of length `t_max` following channel
    /// `channel`'s density: t = −ln(1 − u)/σt,c.
    #[inline]
    pub fn sample_distance_in(&self, t_max: f32, channel: usize, u: f32) -> FreeFlight {
        let sigma_t = self.sigma_t();
        let s = sigma_t.to_array()[channel];
        let t = if s > 0.0 { -(1.0 - u).ln() / s } else { f32::INFINITY };
        let scattered = t < t_max;
        let t_end = if scattered { t } else { t_max };
        let tr = self.transmittance(t_end);
        // Each channel's density of the event: σt·T(t) for an interaction at t, T(t_max) for
        // crossing. The weight divides by their average over the three equally likely channels.
        let (throughput, density) = if scattered { (tr * self.sigma_s, sigma_t * tr) } else { (tr, tr) };
        let mixture = density.average();
        let weight = if mixture > 0.0 { throughput / mixture } else { Rgb::BLACK };
        FreeFlight { t: t_end, scattered, weight, throughput, density }
    }
}
