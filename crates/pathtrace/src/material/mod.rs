//! Materials (BSDFs): one file per model, gathered in the closed [`Material`] enum.
//!
//! Conventions: directions are in the local shading frame (normal = +z), both pointing away
//! from the surface; `wo` towards the viewer, `wi` towards the light. `eval` returns
//! `f(wo, wi)·|cos θi|`, so models whose BRDF is singular at grazing angles stay finite.
//! Reflective models are two-sided: the integrator flips the frame so that `wo.z > 0`. The
//! dielectric sees both sides (z > 0 is outside, where the geometric normal points); the thin
//! dielectric is symmetric, so it is two-sided too.

mod beckmann_slopes;
mod blend;
mod conductor;
mod dielectric;
mod diffuse;
mod fresnel;
mod glossy;
mod ior;
pub(crate) mod lambertian;
#[cfg(test)]
mod lane_checks;
mod lanes;
mod metals;
pub mod microfacet;
mod mirror;
mod plastic;
mod rough_conductor;
mod rough_dielectric;
mod rough_plastic;
mod rough_plastic_alpha;
mod scattering;
mod thin_dielectric;

pub use blend::{Blend, Mixture};
pub use conductor::Conductor;
pub(crate) use conductor::SmoothConductorLanes;
pub(crate) use dielectric::DielectricLanes;
pub use dielectric::{fresnel_dielectric, Dielectric};
pub use diffuse::Diffuse;
pub(crate) use diffuse::DiffuseLanes;
pub use fresnel::{fresnel_conductor, fresnel_conductor_rgb};
pub use glossy::Glossy;
pub(crate) use glossy::GlossyLanes;
pub use ior::{ior_names, named_ior};
pub use lambertian::Lambertian;
pub(crate) use lambertian::LambertianLanes;
pub(crate) use lanes::{rgb_lane, DeltaModel, LaneDeltaScattering, LaneSamples, LaneScattering, SmoothModel};
pub use metals::{metal, metal_names};
pub use microfacet::{Microfacet, MicrofacetKind};
pub use mirror::Mirror;
pub use plastic::Plastic;
pub(crate) use plastic::PlasticLanes;
pub use rough_conductor::RoughConductor;
pub(crate) use rough_conductor::RoughConductorLanes;
pub use rough_dielectric::RoughDielectric;
pub(crate) use rough_dielectric::RoughDielectricLanes;
pub use rough_plastic::RoughPlastic;
pub(crate) use rough_plastic::RoughPlasticLanes;
pub use rough_plastic_alpha::RoughPlasticAlphaTable;
pub use scattering::Scattering;
pub use thin_dielectric::ThinDielectric;
pub(crate) use thin_dielectric::ThinDielectricLanes;

use crate::math::{Rgb, Vec2, Vec3};
use crate::texture::ColourSlot;
use crate::wide::simd::Vec3s;

/// A sampled scattering direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BsdfSample {
    /// Incident direction (local frame).
    pub wi: Vec3,
    /// `f·|cos θi| / pdf`: what the path throughput is multiplied by.
    pub weight: Rgb,
    /// Solid-angle density of `wi` (for delta lobes: the discrete probability of the lobe).
    pub pdf: f32,
    /// True for a Dirac lobe (mirror, glass): light sampling cannot reach it.
    pub delta: bool,
    /// Relative index of refraction crossed (1 for reflection), for Russian roulette.
    pub eta: f32,
}

/// Every surface model.
///
/// `RoughPlastic` carries its 64-entry transmittance table inline, so the enum is large; it
/// lives in the scene's material table and the path loop borrows it (`Interaction::material` is
/// a reference), so its size costs nothing per hit, while boxing would cost `Copy` and an
/// indirection.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Material {
    /// Black: absorbs everything (the surface of a pure emitter).
    Black,
    /// An index-matched boundary (Mitsuba's `null`): light passes straight through. It only
    /// marks where a medium begins and ends; the estimator crosses it without counting a vertex.
    Null,
    Diffuse(Diffuse),
    Lambertian(Lambertian),
    Mirror(Mirror),
    Glossy(Glossy),
    Dielectric(Dielectric),
    Conductor(Conductor),
    RoughConductor(RoughConductor),
    RoughDielectric(RoughDielectric),
    Plastic(Plastic),
    RoughPlastic(RoughPlastic),
    ThinDielectric(ThinDielectric),
    /// A mix of two other materials of the scene (see [`Blend`]); shaded as the [`Mixture`] the
    /// scene makes of it at a hit (`Scene::mixture`): on its own it scatters nothing.
    Blend(Blend),
}

impl Material {
    /// Samples `wi` given `wo`, a number for lobe selection and a 2D point.
    #[inline(always)]
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        match self {
            Material::Black => None,
            // Straight on (wi = −wo, which crosses the surface) with weight 1.
            Material::Null => Some(BsdfSample { wi: -wo, weight: Rgb::splat(1.0), pdf: 1.0, delta: true, eta: 1.0 }),
            Material::Diffuse(m) => m.sample(wo, u_lobe, u),
            Material::Lambertian(m) => m.sample(wo, u_lobe, u),
            Material::Mirror(m) => m.sample(wo, u_lobe),
            Material::Glossy(m) => m.sample(wo, u_lobe, u),
            Material::Dielectric(m) => m.sample(wo, u_lobe),
            Material::Conductor(m) => m.sample(wo, u_lobe),
            Material::RoughConductor(m) => m.sample(wo, u_lobe, u),
            Material::RoughDielectric(m) => m.sample(wo, u_lobe, u),
            Material::Plastic(m) => m.sample(wo, u_lobe, u),
            Material::RoughPlastic(m) => m.sample(wo, u_lobe, u),
            Material::ThinDielectric(m) => m.sample(wo, u_lobe),
            Material::Blend(_) => None,
        }
    }

    /// `f(wo, wi)·|cos θi|`; zero for delta lobes.
    #[inline(always)]
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        match self {
            Material::Diffuse(m) => m.eval(wo, wi),
            Material::Lambertian(m) => m.eval(wo, wi),
            Material::Glossy(m) => m.eval(wo, wi),
            Material::RoughConductor(m) => m.eval(wo, wi),
            Material::RoughDielectric(m) => m.eval(wo, wi),
            Material::Plastic(m) => m.eval(wo, wi),
            Material::RoughPlastic(m) => m.eval(wo, wi),
            Material::Black
            | Material::Null
            | Material::Mirror(_)
            | Material::Dielectric(_)
            | Material::Conductor(_)
            | Material::ThinDielectric(_)
            | Material::Blend(_) => Rgb::BLACK,
        }
    }

    /// Solid-angle density with which [`Material::sample`] produces `wi`; zero for delta lobes.
    #[inline(always)]
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        match self {
            Material::Diffuse(m) => m.pdf(wo, wi),
            Material::Lambertian(m) => m.pdf(wo, wi),
            Material::Glossy(m) => m.pdf(wo, wi),
            Material::RoughConductor(m) => m.pdf(wo, wi),
            Material::RoughDielectric(m) => m.pdf(wo, wi),
            Material::Plastic(m) => m.pdf(wo, wi),
            Material::RoughPlastic(m) => m.pdf(wo, wi),
            Material::Black
            | Material::Null
            | Material::Mirror(_)
            | Material::Dielectric(_)
            | Material::Conductor(_)
            | Material::ThinDielectric(_)
            | Material::Blend(_) => 0.0,
        }
    }

    /// [`Material::eval`] and [`Material::pdf`] of one pair of directions: models whose two
    /// share work (the half vector, D and G1 of a microfacet model, a Fresnel term) compute it
    /// once; the values are those of the two calls.
    #[inline(always)]
    pub fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Rgb, f32) {
        match self {
            Material::RoughConductor(m) => m.eval_pdf(wo, wi),
            Material::Plastic(m) => m.eval_pdf(wo, wi),
            Material::RoughPlastic(m) => m.eval_pdf(wo, wi),
            Material::RoughDielectric(m) => m.eval_pdf(wo, wi),
            Material::Diffuse(m) => m.eval_pdf(wo, wi),
            Material::Glossy(m) => m.eval_pdf(wo, wi),
            Material::Black
            | Material::Null
            | Material::Lambertian(_)
            | Material::Mirror(_)
            | Material::Dielectric(_)
            | Material::Conductor(_)
            | Material::ThinDielectric(_)
            | Material::Blend(_) => (self.eval(wo, wi), self.pdf(wo, wi)),
        }
    }

    /// The model with its `slot` colour replaced by `c` (a texture's value at a hit). Slots a
    /// model does not have leave it unchanged.
    #[inline]
    pub fn with_colour(&self, slot: ColourSlot, c: Rgb) -> Material {
        let mut m = *self;
        let base = slot == ColourSlot::Base;
        // A roughness texture's value (its luminance, as Mitsuba's `eval_1`) is an isotropic α.
        let rough =
            || Microfacet::isotropic(MicrofacetKind::Beckmann, c.luminance().clamp(0.0, crate::scene::MAX_ALPHA));
        // One arm per model, no catch-all: a new model does not compile until it says which of
        // its colours a texture replaces.
        match &mut m {
            Material::Black | Material::Null => {}
            Material::Diffuse(d) if base => d.albedo = c,
            Material::Lambertian(d) if base => d.albedo = c,
            Material::Glossy(g) if base => g.albedo = c,
            Material::Mirror(r) if base => r.reflectance = c,
            Material::Dielectric(d) if base => d.tint = c,
            Material::ThinDielectric(d) if base => d.tint = c,
            Material::RoughDielectric(d) if base => d.tint = c,
            Material::RoughDielectric(d) if slot == ColourSlot::Roughness => {
                d.distribution = Microfacet { kind: d.distribution.kind, ..rough() }
            }
            Material::Conductor(k) if base => k.reflectance = c,
            Material::RoughConductor(k) if base => k.reflectance = c,
            Material::RoughConductor(k) if slot == ColourSlot::Roughness => {
                k.distribution = Microfacet { kind: k.distribution.kind, ..rough() }
            }
            Material::Diffuse(_)
            | Material::Lambertian(_)
            | Material::Glossy(_)
            | Material::Mirror(_)
            | Material::Dielectric(_)
            | Material::ThinDielectric(_)
            | Material::RoughDielectric(_)
            | Material::Conductor(_)
            | Material::RoughConductor(_) => {}
            Material::Plastic(p) => match slot {
                ColourSlot::Base => *p = p.with_albedo(c),
                ColourSlot::Specular => p.specular = c,
                ColourSlot::Roughness => {}
            },
            // Its coating tables depend on α: a roughness texture goes through
            // `RoughPlastic::with_alpha` and the material's α table (`Scene::textured_material`).
            Material::RoughPlastic(p) => match slot {
                ColourSlot::Base => *p = p.with_albedo(c),
                ColourSlot::Specular => p.specular = c,
                ColourSlot::Roughness => {}
            },
            // A blend's one colour is its weight (the value's luminance, as Mitsuba's
            // `blendbsdf` reads its `weight` texture with `eval_1`).
            Material::Blend(b) => {
                if base {
                    b.weight = c.luminance().clamp(0.0, 1.0)
                }
            }
        }
        m
    }

    /// The slots this model has, for front ends that bind textures.
    pub fn has_slot(&self, slot: ColourSlot) -> bool {
        match slot {
            ColourSlot::Base => !matches!(self, Material::Black | Material::Null),
            ColourSlot::Specular => matches!(self, Material::Plastic(_) | Material::RoughPlastic(_)),
            ColourSlot::Roughness => {
                matches!(self, Material::RoughConductor(_) | Material::RoughDielectric(_) | Material::RoughPlastic(_))
            }
        }
    }

    /// True if the model only scatters into discrete directions, so light sampling is skipped.
    pub fn is_delta(&self) -> bool {
        matches!(
            self,
            Material::Null
                | Material::Mirror(_)
                | Material::Dielectric(_)
                | Material::Conductor(_)
                | Material::ThinDielectric(_)
        )
    }

    /// True if some but not all of the model's scattering is a Dirac lobe (`plastic`'s coating):
    /// light sampling covers the rest, and sampling towards lights alone would miss that lobe.
    pub fn has_delta_lobe(&self) -> bool {
        matches!(self, Material::Plastic(_))
    }

    /// True for a microfacet model with different roughness along its two tangent axes: its
    /// shading frame must then follow the surface's ∂p/∂u rather than an arbitrary basis.
    pub fn is_anisotropic(&self) -> bool {
        let aniso = |d: &Microfacet| d.alpha_u != d.alpha_v;
        match self {
            Material::RoughConductor(m) => aniso(&m.distribution),
            Material::RoughDielectric(m) => aniso(&m.distribution),
            Material::RoughPlastic(m) => aniso(&m.distribution),
            Material::Black
            | Material::Null
            | Material::Diffuse(_)
            | Material::Lambertian(_)
            | Material::Mirror(_)
            | Material::Glossy(_)
            | Material::Dielectric(_)
            | Material::Conductor(_)
            | Material::Plastic(_)
            | Material::ThinDielectric(_)
            | Material::Blend(_) => false,
        }
    }

    /// True unless the model has an inside (dielectrics): opaque models shade both faces.
    pub fn is_two_sided(&self) -> bool {
        !matches!(self, Material::Dielectric(_) | Material::RoughDielectric(_))
    }

    /// True for the index-matched boundary `Null`.
    pub fn is_null(&self) -> bool {
        matches!(self, Material::Null)
    }

    /// True if the model scatters no light at all.
    pub fn is_black(&self) -> bool {
        matches!(self, Material::Black)
    }

    /// The model's name in scene files.
    pub fn name(&self) -> &'static str {
        match self {
            Material::Black => "black",
            Material::Null => "null",
            Material::Diffuse(_) => "diffuse",
            Material::Lambertian(_) => "lambertian",
            Material::Mirror(_) => "mirror",
            Material::Glossy(_) => "glossy",
            Material::Dielectric(_) => "dielectric",
            Material::Conductor(_) => "conductor",
            Material::RoughConductor(_) => "rough_conductor",
            Material::RoughDielectric(_) => "rough_dielectric",
            Material::Plastic(_) => "plastic",
            Material::RoughPlastic(_) => "rough_plastic",
            Material::ThinDielectric(_) => "thindielectric",
            Material::Blend(_) => "blend",
        }
    }
}

/// Mirror reflection about the local normal per lane: R = -wo + 2(wo·n)n, i.e. the book form
/// R = L - 2(L·N)N with L = -wo.
#[inline(always)]
pub(crate) fn reflect_local_lanes<const N: usize>(wo: &Vec3s<N>) -> Vec3s<N> {
    Vec3s { x: -wo.x, y: -wo.y, z: wo.z }
}
