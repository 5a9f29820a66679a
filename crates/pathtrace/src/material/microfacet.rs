//! Microfacet normal distributions — GGX (Trowbridge–Reitz) and Beckmann, isotropic or
//! anisotropic — with Smith masking and sampling of the distribution of visible normals.
//!
//! Conventions (local frame, normal = +z; `alpha_u` along x, `alpha_v` along y):
//! - `d(m)` is normalised in projected area: ∫ D(m) (m·n) dω_m = 1.
//! - `g1(v, m) = 1/(1 + Λ(v))` (Smith), zero when `v` sees the back of `m`. The BSDFs use the
//!   separable form G = G1(wo)·G1(wi), as Mitsuba 3 does (so images match it); Mitsuba 3
//!   approximates Beckmann's Λ by Walter et al.'s rational fit (< 0.35% error), we use the exact
//!   Λ, which the visible-normal pdf needs to integrate to exactly 1.
//! - `sample_visible(v, u)` draws m with density D_v(m) = G1(v, m) max(0, v·m) D(m) / cos θv
//!   (Heitz & d'Eon 2014, "Importance Sampling Microfacet-Based BSDFs using the Distribution of
//!   Visible Normals", eq. 2), returned by `pdf_visible`.
//!
//! Sources: D and Λ of both models from Walter et al. 2007 ("Microfacet Models for Refraction
//! through Rough Surfaces", eqs. 25–27, 33–34) and Heitz 2014 ("Understanding the
//! Masking-Shadowing Function", §5 for the anisotropic forms); GGX visible normals by Heitz
//! 2018 ("Sampling the GGX Distribution of Visible Normals", JCGT 7(4), listing 1); Beckmann
//! visible slopes by Jakob's numerical inversion (2014, "An Improved Visible Normal Sampling
//! Routine for the Beckmann Distribution"), here bracketed and iterated to convergence (see
//! `beckmann_slopes.rs`).

use super::beckmann_slopes::visible_slopes_11;
use crate::math::special::{erf_and_gaussian_fast, exp_flushed_f32};
use crate::math::{Vec2, Vec3, PI};

/// Which normal distribution.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MicrofacetKind {
    /// Trowbridge–Reitz, long-tailed.
    Ggx,
    /// Gaussian slopes (Mitsuba's default).
    Beckmann,
}

/// A microfacet distribution with roughness `alpha_u` (along x) and `alpha_v` (along y).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Microfacet {
    pub kind: MicrofacetKind,
    pub alpha_u: f32,
    pub alpha_v: f32,
}

/// Roughness below this is clamped (as Mitsuba does): the lobes would be numerically delta.
pub const MIN_ALPHA: f32 = 1e-4;

impl Microfacet {
    /// A distribution; roughness values are clamped to at least [`MIN_ALPHA`].
    pub fn new(kind: MicrofacetKind, alpha_u: f32, alpha_v: f32) -> Self {
        Self { kind, alpha_u: alpha_u.max(MIN_ALPHA), alpha_v: alpha_v.max(MIN_ALPHA) }
    }

    /// The same roughness in every direction.
    pub fn isotropic(kind: MicrofacetKind, alpha: f32) -> Self {
        Self::new(kind, alpha, alpha)
    }

    /// D(m): microfacet area density per unit projected area (Walter 2007 eqs. 25, 33, with
    /// the anisotropic tan²θ (cos²φ/αu² + sin²φ/αv²) of Heitz 2014 §5.2).
    pub fn d(&self, m: Vec3) -> f32 {
        if m.z <= 0.0 {
            return 0.0;
        }
        let (ax, ay) = (self.alpha_u, self.alpha_v);
        let cos2 = m.z * m.z;
        let d = match self.kind {
            MicrofacetKind::Beckmann => {
                let e = ((m.x / ax) * (m.x / ax) + (m.y / ay) * (m.y / ay)) / cos2;
                exp_flushed_f32(-e) / (PI * ax * ay * cos2 * cos2)
            }
            MicrofacetKind::Ggx => {
                let t = (m.x / ax) * (m.x / ax) + (m.y / ay) * (m.y / ay) + cos2;
                1.0 / (PI * ax * ay * t * t)
            }
        };
        if d.is_finite() {
            d
        } else {
            0.0
        }
    }

    /// α² tan²θ of `v` with the roughness projected onto v's azimuth (Heitz 2014 eq. 80).
    fn alpha2_tan2(&self, v: Vec3) -> f32 {
        let xy = (self.alpha_u * v.x) * (self.alpha_u * v.x) + (self.alpha_v * v.y) * (self.alpha_v * v.y);
        xy / (v.z * v.z)
    }

    /// Smith's Λ(v) (Heitz 2014 eqs. 72 and 86).
    pub fn lambda(&self, v: Vec3) -> f32 {
        let a2t2 = self.alpha2_tan2(v);
        if a2t2 == 0.0 || !a2t2.is_finite() {
            return if a2t2 == 0.0 { 0.0 } else { f32::INFINITY };
        }
        match self.kind {
            MicrofacetKind::Ggx => 0.5 * (-1.0 + (1.0 + a2t2).sqrt()),
            MicrofacetKind::Beckmann => {
                let a = 1.0 / a2t2.sqrt();
                let (erf_a, gaussian) = erf_and_gaussian_fast(a);
                0.5 * (erf_a - 1.0) + gaussian / (2.0 * a * PI.sqrt())
            }
        }
    }

    /// Smith's masking G1(v, m) = 1/(1 + Λ(v)), zero when v sees the back of m.
    pub fn g1(&self, v: Vec3, m: Vec3) -> f32 {
        if v.dot(m) * v.z <= 0.0 {
            return 0.0;
        }
        1.0 / (1.0 + self.lambda(v))
    }

    /// Separable masking–shadowing G1(wo, m)·G1(wi, m) (Mitsuba 3's choice).
    pub fn g(&self, wo: Vec3, wi: Vec3, m: Vec3) -> f32 {
        self.g1(wo, m) * self.g1(wi, m)
    }

    /// Density of [`Microfacet::sample_visible`]: D_v(m) = G1(v, m) max(0, v·m) D(m) / cos θv
    /// (Heitz & d'Eon 2014 eq. 2), for `v` above the surface.
    pub fn pdf_visible(&self, v: Vec3, m: Vec3) -> f32 {
        if v.z <= 0.0 {
            return 0.0;
        }
        visible_density(self.g1(v, m), v.dot(m), self.d(m), v.z)
    }

    /// Draws a microfacet normal visible from `v` (which must have `v.z > 0`).
    pub fn sample_visible(&self, v: Vec3, u: Vec2) -> Vec3 {
        match self.kind {
            MicrofacetKind::Ggx => self.sample_visible_ggx(v, u),
            MicrofacetKind::Beckmann => self.sample_visible_beckmann(v, u),
        }
    }

    /// Heitz 2018, listing 1: stretch to the hemisphere configuration (α = 1), sample the
    /// projected half-disk seen from v, unstretch.
    fn sample_visible_ggx(&self, v: Vec3, u: Vec2) -> Vec3 {
        let vh = Vec3::new(self.alpha_u * v.x, self.alpha_v * v.y, v.z).normalize();
        let len2 = vh.x * vh.x + vh.y * vh.y;
        let t1 = if len2 > 0.0 { Vec3::new(-vh.y, vh.x, 0.0) / len2.sqrt() } else { Vec3::X };
        let t2 = vh.cross(t1);
        let r = u.x.sqrt();
        let phi = 2.0 * PI * u.y;
        let p1 = r * phi.cos();
        let s = 0.5 * (1.0 + vh.z);
        let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * r * phi.sin();
        let nh = p1 * t1 + p2 * t2 + (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt() * vh;
        Vec3::new(self.alpha_u * nh.x, self.alpha_v * nh.y, nh.z.max(0.0)).normalize()
    }

    /// Heitz & d'Eon 2014 §4 (stretch, sample slopes for α = 1, rotate, unstretch) with the
    /// α = 1 Beckmann visible slopes drawn by inverting their marginal CDF in x (Jakob 2014).
    fn sample_visible_beckmann(&self, v: Vec3, u: Vec2) -> Vec3 {
        let vs = Vec3::new(self.alpha_u * v.x, self.alpha_v * v.y, v.z).normalize();
        let (sx, sy) = visible_slopes_11(vs.z, u.x, u.y);
        // Rotate from the frame where the (stretched) view direction has azimuth 0.
        let len = (vs.x * vs.x + vs.y * vs.y).sqrt();
        let (cos_phi, sin_phi) = if len > 0.0 { (vs.x / len, vs.y / len) } else { (1.0, 0.0) };
        let rx = cos_phi * sx - sin_phi * sy;
        let ry = sin_phi * sx + cos_phi * sy;
        // Unstretch the slopes; the normal of slope (x, y) is (−x, −y, 1) normalised.
        Vec3::new(-(rx * self.alpha_u), -(ry * self.alpha_v), 1.0).normalize()
    }
}

/// D_v(m) = G1(v, m) max(0, v·m) D(m) / cos θv from its parts (Heitz & d'Eon 2014 eq. 2), for
/// callers that already hold G1 and D (a model's value and density at one pair of directions).
#[inline(always)]
pub(crate) fn visible_density(g1_v: f32, v_dot_m: f32, d: f32, cos_theta_v: f32) -> f32 {
    g1_v * v_dot_m.max(0.0) * d / cos_theta_v
}

/// Mirror reflection of `v` about the microfacet normal `m`: 2(v·m)m − v.
#[inline]
pub fn reflect_about(v: Vec3, m: Vec3) -> Vec3 {
    2.0 * v.dot(m) * m - v
}

/// Refraction of `v` (with cos θ = `cos_vm` > 0 to `m`) through the microfacet normal `m`, for
/// a crossing of relative index `eta` whose refracted cosine is `cos_t` (from
/// [`super::dielectric::fresnel_dielectric`]). Snell about m: −v/η + (cos θv/η − cos θt) m (the
/// tangential part shrinks by 1/η).
#[inline]
pub fn refract_about(v: Vec3, m: Vec3, cos_vm: f32, cos_t: f32, eta: f32) -> Vec3 {
    (-v / eta + (cos_vm / eta - cos_t) * m).normalize()
}

impl MicrofacetKind {
    /// The name in scene files (as Mitsuba's `distribution`).
    pub fn name(self) -> &'static str {
        match self {
            MicrofacetKind::Ggx => "ggx",
            MicrofacetKind::Beckmann => "beckmann",
        }
    }
}

impl std::str::FromStr for MicrofacetKind {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "ggx" => Ok(MicrofacetKind::Ggx),
            "beckmann" => Ok(MicrofacetKind::Beckmann),
            other => Err(format!("unknown microfacet distribution `{other}` (ggx or beckmann)")),
        }
    }
}
