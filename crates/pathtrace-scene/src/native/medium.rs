//! `[media.NAME]`: a homogeneous participating medium (Mitsuba 3's `homogeneous`), placed by
//! objects' `interior`/`exterior` and the camera's `medium`.
//!
//! The coefficients are given either as Mitsuba gives them, extinction `sigma_t` (default 1)
//! and single-scattering `albedo` (default 0.75), or as absorption `sigma_a` and scattering
//! `sigma_s`; `scale` (default 1) multiplies them all (a density). Values are checked when the
//! scene is built, at their own field (`native::build`).

use super::values::{Num, Triple};
use pathtrace::math::Rgb;
use pathtrace::medium::{HomogeneousMedium, PhaseFunction};
use serde::{Deserialize, Serialize};

/// The media types, as named by `type`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum MediumType {
    /// Constant coefficients everywhere inside the medium's boundary.
    #[default]
    Homogeneous,
}

/// One named medium of a scene file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MediumDef {
    /// `homogeneous` (the default and only type).
    #[serde(default, rename = "type", skip_serializing_if = "Option::is_none")]
    pub kind: Option<MediumType>,
    /// Extinction coefficient σt per unit length (default 1; with `albedo`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma_t: Option<Triple>,
    /// Single-scattering albedo σs/σt, each channel in [0, 1] (default 0.75; with `sigma_t`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub albedo: Option<Triple>,
    /// Absorption coefficient σa (instead of `sigma_t` and `albedo`; with `sigma_s`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma_a: Option<Triple>,
    /// Scattering coefficient σs (instead of `sigma_t` and `albedo`; with `sigma_a`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma_s: Option<Triple>,
    /// Density multiplying every coefficient (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale: Option<Num>,
    /// The phase function (default isotropic).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub phase: Option<PhaseDef>,
}

/// `phase = { type = "hg", g = 0.7 }`: how the medium scatters.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum PhaseDef {
    /// The same in every direction.
    Isotropic,
    /// Henyey–Greenstein with mean cosine `g` in (−1, 1): g > 0 scatters forwards (Mitsuba's
    /// `hg`, whose default is 0.8).
    Hg {
        #[serde(default, skip_serializing_if = "Option::is_none")]
        g: Option<Num>,
    },
}

impl PhaseDef {
    /// Mitsuba's default asymmetry for `hg`.
    pub const DEFAULT_G: f64 = 0.8;
}

impl MediumDef {
    /// Default extinction (Mitsuba's `sigma_t`).
    pub const DEFAULT_SIGMA_T: f64 = 1.0;
    /// Default single-scattering albedo (Mitsuba's `albedo`).
    pub const DEFAULT_ALBEDO: f64 = 0.75;
}

/// The engine's medium for a definition, or the field at fault and why.
pub(super) fn build_medium(def: &MediumDef) -> Result<HomogeneousMedium, (&'static str, String)> {
    let extinction = def.sigma_t.is_some() || def.albedo.is_some();
    if extinction && (def.sigma_a.is_some() || def.sigma_s.is_some()) {
        let field = if def.sigma_a.is_some() { "sigma_a" } else { "sigma_s" };
        return Err((field, "give either `sigma_t` and `albedo` or `sigma_a` and `sigma_s`, not both".into()));
    }
    let scale = def.scale.map_or(1.0, |s| s.f32());
    if !(scale.is_finite() && scale >= 0.0) {
        return Err(("scale", format!("`scale` must be a finite number ≥ 0, not {scale}")));
    }
    let coefficient = |t: Option<Triple>, default: f64, field: &'static str| {
        let c = t.map_or(Rgb::splat(default as f32), |t| t.rgb());
        if c.is_finite() && c.to_array().iter().all(|&v| v >= 0.0) {
            Ok(c)
        } else {
            Err((field, format!("`{field}` must be finite and ≥ 0 in every channel, not {:?}", c.to_array())))
        }
    };
    let phase = match def.phase {
        None | Some(PhaseDef::Isotropic) => PhaseFunction::Isotropic,
        Some(PhaseDef::Hg { g }) => {
            let g = g.map_or(PhaseDef::DEFAULT_G as f32, |g| g.f32());
            PhaseFunction::check_g(g).map_err(|e| ("phase", e))?;
            PhaseFunction::HenyeyGreenstein { g }
        }
    };
    let medium = if extinction || def.sigma_a.is_none() && def.sigma_s.is_none() {
        let sigma_t = coefficient(def.sigma_t, MediumDef::DEFAULT_SIGMA_T, "sigma_t")?;
        let albedo = coefficient(def.albedo, MediumDef::DEFAULT_ALBEDO, "albedo")?;
        if albedo.max_component() > 1.0 {
            return Err((
                "albedo",
                format!("`albedo` must be in [0, 1] in every channel, not {:?}", albedo.to_array()),
            ));
        }
        HomogeneousMedium::from_extinction(sigma_t, albedo, scale, phase)
    } else {
        let sigma_a = coefficient(def.sigma_a, 0.0, "sigma_a")?;
        let sigma_s = coefficient(def.sigma_s, 0.0, "sigma_s")?;
        HomogeneousMedium { sigma_a: sigma_a * scale, sigma_s: sigma_s * scale, phase }
    };
    // Products can still overflow (a huge σt times a huge scale).
    medium.check().map_err(|e| ("scale", e))?;
    Ok(medium)
}
