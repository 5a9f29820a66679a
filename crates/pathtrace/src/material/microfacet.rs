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

use super::beckmann_slopes::visible_slopes_lanes;
use crate::math::exp_lanes;
use crate::math::special::erf_and_gaussian_lanes;
use crate::math::{Vec2, Vec3, PI};
use crate::wide::simd::{F32s, Ms, Vec3s};

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

    /// This distribution in every lane of a group (the scalar methods below are the one-lane
    /// instances of [`MicrofacetLanes`]'s: one implementation of each formula).
    #[inline(always)]
    pub(crate) fn lanes<const N: usize>(&self) -> MicrofacetLanes<N> {
        MicrofacetLanes {
            beckmann: Ms::from_fn(|_| self.kind == MicrofacetKind::Beckmann),
            alpha_u: F32s::splat(self.alpha_u),
            alpha_v: F32s::splat(self.alpha_v),
        }
    }

    /// D(m): microfacet area density per unit projected area.
    pub fn d(&self, m: Vec3) -> f32 {
        self.lanes::<1>().d(&Vec3s::splat(m)).0[0]
    }

    /// Smith's Λ(v).
    pub fn lambda(&self, v: Vec3) -> f32 {
        self.lanes::<1>().lambda(&Vec3s::splat(v)).0[0]
    }

    /// Smith's masking G1(v, m) = 1/(1 + Λ(v)), zero when v sees the back of m.
    pub fn g1(&self, v: Vec3, m: Vec3) -> f32 {
        self.lanes::<1>().g1(&Vec3s::splat(v), &Vec3s::splat(m)).0[0]
    }

    /// Separable masking–shadowing G1(wo, m)·G1(wi, m) (Mitsuba 3's choice).
    pub fn g(&self, wo: Vec3, wi: Vec3, m: Vec3) -> f32 {
        self.g1(wo, m) * self.g1(wi, m)
    }

    /// Density of [`Microfacet::sample_visible`]: D_v(m) = G1(v, m) max(0, v·m) D(m) / cos θv
    /// (Heitz & d'Eon 2014 eq. 2), for `v` above the surface.
    pub fn pdf_visible(&self, v: Vec3, m: Vec3) -> f32 {
        self.lanes::<1>().pdf_visible(&Vec3s::splat(v), &Vec3s::splat(m)).0[0]
    }

    /// Draws a microfacet normal visible from `v` (which must have `v.z > 0`).
    pub fn sample_visible(&self, v: Vec3, u: Vec2) -> Vec3 {
        self.lanes::<1>().sample_visible(&Vec3s::splat(v), F32s([u.x]), F32s([u.y]), Ms::ALL).lane(0)
    }
}

/// A microfacet distribution per lane: each lane's kind and roughness (lanes of one group can
/// hold different materials).
#[derive(Clone, Copy, Debug)]
pub(crate) struct MicrofacetLanes<const N: usize> {
    /// Beckmann lanes; the others are GGX.
    pub beckmann: Ms<N>,
    pub alpha_u: F32s<N>,
    pub alpha_v: F32s<N>,
}

// Always inlined: the lane loop's callers are compiled for AVX2/AVX-512, and a helper compiled
// outside them would work on the lanes with narrower instructions. Each model is evaluated
// only if some lane has it.
impl<const N: usize> MicrofacetLanes<N> {
    /// The same distributions, with the lanes outside `lanes` taken as GGX: their values are
    /// then not needed, and a group without Beckmann lanes skips Beckmann's exponentials and
    /// slope inversion altogether.
    #[inline(always)]
    pub fn only(self, lanes: Ms<N>) -> Self {
        Self { beckmann: self.beckmann & lanes, ..self }
    }

    /// Lane `i` holds `m`.
    #[inline(always)]
    pub fn set(&mut self, i: usize, m: &Microfacet) {
        self.beckmann.0[i] = u32::from(m.kind == MicrofacetKind::Beckmann).wrapping_neg();
        self.alpha_u.0[i] = m.alpha_u;
        self.alpha_v.0[i] = m.alpha_v;
    }

    /// D(m) (Walter 2007 eqs. 25, 33, with the anisotropic tan²θ (cos²φ/αu² + sin²φ/αv²) of
    /// Heitz 2014 §5.2); 0 below the surface and where the value overflows.
    #[inline(always)]
    pub fn d(&self, m: &Vec3s<N>) -> F32s<N> {
        let (ax, ay) = (self.alpha_u, self.alpha_v);
        let cos2 = m.z * m.z;
        let (sx, sy) = (m.x / ax, m.y / ay);
        let beckmann = if self.beckmann.any() {
            let e = (sx * sx + sy * sy) / cos2;
            exp_lanes(-e) / (PI * ax * ay * cos2 * cos2)
        } else {
            F32s::ZERO
        };
        let ggx = if (!self.beckmann).any() {
            let t = sx * sx + sy * sy + cos2;
            1.0 / (PI * ax * ay * t * t)
        } else {
            F32s::ZERO
        };
        let d = F32s::select(self.beckmann, beckmann, ggx);
        F32s::select(m.z.gt(F32s::ZERO) & d.is_finite(), d, F32s::ZERO)
    }

    /// Smith's Λ(v) (Heitz 2014 eqs. 72 and 86), from α² tan²θ of `v` with the roughness
    /// projected onto v's azimuth (Heitz 2014 eq. 80): 0 at normal incidence, ∞ at grazing.
    #[inline(always)]
    pub fn lambda(&self, v: &Vec3s<N>) -> F32s<N> {
        let (au, av) = (self.alpha_u, self.alpha_v);
        let xy = (au * v.x) * (au * v.x) + (av * v.y) * (av * v.y);
        let a2t2 = xy / (v.z * v.z);
        let beckmann = if self.beckmann.any() {
            let a = 1.0 / a2t2.sqrt();
            let (erf_a, gaussian) = erf_and_gaussian_lanes(a);
            0.5 * (erf_a - 1.0) + gaussian / (2.0 * a * PI.sqrt())
        } else {
            F32s::ZERO
        };
        let ggx = if (!self.beckmann).any() { 0.5 * (-1.0 + (1.0 + a2t2).sqrt()) } else { F32s::ZERO };
        let lambda = F32s::select(self.beckmann, beckmann, ggx);
        let lambda = F32s::select(a2t2.is_finite(), lambda, F32s::splat(f32::INFINITY));
        F32s::select(a2t2.eq(F32s::ZERO), F32s::ZERO, lambda)
    }

    /// G1(v, m) = 1/(1 + Λ(v)), zero when v sees the back of m.
    #[inline(always)]
    pub fn g1(&self, v: &Vec3s<N>, m: &Vec3s<N>) -> F32s<N> {
        let back = (v.dot(m) * v.z).le(F32s::ZERO);
        F32s::select(back, F32s::ZERO, 1.0 / (1.0 + self.lambda(v)))
    }

    /// D_v(m) (see [`Microfacet::pdf_visible`]); 0 for `v` below the surface.
    #[inline(always)]
    pub fn pdf_visible(&self, v: &Vec3s<N>, m: &Vec3s<N>) -> F32s<N> {
        let density = visible_density_lanes(self.g1(v, m), v.dot(m), self.d(m), v.z);
        F32s::select(v.z.le(F32s::ZERO), F32s::ZERO, density)
    }

    /// A microfacet normal visible from `v` (`v.z > 0`) per lane of `active`, from the numbers
    /// `u1`, `u2` (other lanes: unspecified).
    #[inline(always)]
    pub fn sample_visible(&self, v: &Vec3s<N>, u1: F32s<N>, u2: F32s<N>, active: Ms<N>) -> Vec3s<N> {
        let (au, av) = (self.alpha_u, self.alpha_v);
        // Both models start from the view direction stretched to the α = 1 configuration.
        let stretched = Vec3s { x: au * v.x, y: av * v.y, z: v.z }.normalize();
        let beckmann = active & self.beckmann;
        let ggx = active & !self.beckmann;
        let m_ggx = if ggx.any() { self.sample_visible_ggx(&stretched, u1, u2, ggx) } else { Vec3s::default() };
        let m_beckmann =
            if beckmann.any() { self.sample_visible_beckmann(&stretched, u1, u2, beckmann) } else { Vec3s::default() };
        Vec3s::select(self.beckmann, &m_beckmann, &m_ggx)
    }

    /// Heitz 2018, listing 1: sample the projected half-disk seen from the stretched view
    /// direction `vh`, unstretch (in the lanes of `lanes`; the others' values are unspecified).
    #[inline(always)]
    fn sample_visible_ggx(&self, vh: &Vec3s<N>, u1: F32s<N>, u2: F32s<N>, lanes: Ms<N>) -> Vec3s<N> {
        let zero = F32s::ZERO;
        let len2 = vh.x * vh.x + vh.y * vh.y;
        let len = len2.sqrt();
        let t1 = Vec3s::select(
            len2.gt(zero),
            &Vec3s { x: -vh.y / len, y: vh.x / len, z: zero / len },
            &Vec3s::splat(Vec3::X),
        );
        let t2 = cross(vh, &t1);
        let r = u1.sqrt();
        let phi = 2.0 * PI * u2;
        // libm's cosine and sine, lane by lane (the scalar form's bits).
        let (mut cos_phi, mut sin_phi) = (F32s::ZERO, F32s::ZERO);
        for i in lanes.lanes() {
            (cos_phi.0[i], sin_phi.0[i]) = (phi.0[i].cos(), phi.0[i].sin());
        }
        let p1 = r * cos_phi;
        let s = 0.5 * (1.0 + vh.z);
        let p2 = (1.0 - s) * (1.0 - p1 * p1).max(zero).sqrt() + s * r * sin_phi;
        let h = (1.0 - p1 * p1 - p2 * p2).max(zero).sqrt();
        let nh = t1.scale(p1).add(&t2.scale(p2)).add(&vh.scale(h));
        Vec3s { x: self.alpha_u * nh.x, y: self.alpha_v * nh.y, z: nh.z.max(zero) }.normalize()
    }

    /// Heitz & d'Eon 2014 §4 (sample slopes for α = 1 seen from the stretched `vs`, rotate,
    /// unstretch) with the α = 1 Beckmann visible slopes drawn by inverting their marginal CDF
    /// in x (Jakob 2014), all lanes iterating together.
    #[inline(always)]
    fn sample_visible_beckmann(&self, vs: &Vec3s<N>, u1: F32s<N>, u2: F32s<N>, lanes: Ms<N>) -> Vec3s<N> {
        let (sx, sy) = visible_slopes_lanes(vs.z, u1, u2, lanes);
        // Rotate from the frame where the (stretched) view direction has azimuth 0.
        let len = (vs.x * vs.x + vs.y * vs.y).sqrt();
        let tilted = len.gt(F32s::ZERO);
        let cos_phi = F32s::select(tilted, vs.x / len, F32s::ONE);
        let sin_phi = F32s::select(tilted, vs.y / len, F32s::ZERO);
        let rx = cos_phi * sx - sin_phi * sy;
        let ry = sin_phi * sx + cos_phi * sy;
        // Unstretch the slopes; the normal of slope (x, y) is (−x, −y, 1) normalised.
        Vec3s { x: -(rx * self.alpha_u), y: -(ry * self.alpha_v), z: F32s::ONE }.normalize()
    }
}

/// `a × b` per lane, in glam's operand order (bit-identical lanes).
#[inline(always)]
fn cross<const N: usize>(a: &Vec3s<N>, b: &Vec3s<N>) -> Vec3s<N> {
    Vec3s { x: a.y * b.z - b.y * a.z, y: a.z * b.x - b.z * a.x, z: a.x * b.y - b.x * a.y }
}

/// D_v(m) = G1(v, m) max(0, v·m) D(m) / cos θv from its parts (Heitz & d'Eon 2014 eq. 2) per
/// lane, for callers that already hold G1 and D (a model's value and density at one pair of
/// directions).
#[inline(always)]
pub(crate) fn visible_density_lanes<const N: usize>(
    g1_v: F32s<N>,
    v_dot_m: F32s<N>,
    d: F32s<N>,
    cos_theta_v: F32s<N>,
) -> F32s<N> {
    g1_v * v_dot_m.max(F32s::ZERO) * d / cos_theta_v
}

/// Mirror reflection of `v` about the microfacet normal `m`: 2(v·m)m − v.
#[inline]
pub fn reflect_about(v: Vec3, m: Vec3) -> Vec3 {
    reflect_about_lanes(&Vec3s::<1>::splat(v), &Vec3s::splat(m)).lane(0)
}

/// [`reflect_about`] in every lane.
#[inline(always)]
pub(crate) fn reflect_about_lanes<const N: usize>(v: &Vec3s<N>, m: &Vec3s<N>) -> Vec3s<N> {
    m.scale(2.0 * v.dot(m)).sub(v)
}

/// Refraction of `v` (with cos θ = `cos_vm` > 0 to `m`) through the microfacet normal `m`, for
/// a crossing of relative index `eta` whose refracted cosine is `cos_t` (from
/// [`super::dielectric::fresnel_dielectric`]). Snell about m: −v/η + (cos θv/η − cos θt) m (the
/// tangential part shrinks by 1/η).
#[inline]
pub fn refract_about(v: Vec3, m: Vec3, cos_vm: f32, cos_t: f32, eta: f32) -> Vec3 {
    refract_about_lanes(&Vec3s::<1>::splat(v), &Vec3s::splat(m), F32s([cos_vm]), F32s([cos_t]), F32s([eta])).lane(0)
}

/// [`refract_about`] in every lane.
#[inline(always)]
pub(crate) fn refract_about_lanes<const N: usize>(
    v: &Vec3s<N>,
    m: &Vec3s<N>,
    cos_vm: F32s<N>,
    cos_t: F32s<N>,
    eta: F32s<N>,
) -> Vec3s<N> {
    let tangential = Vec3s { x: -v.x / eta, y: -v.y / eta, z: -v.z / eta };
    tangential.add(&m.scale(cos_vm / eta - cos_t)).normalize()
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
