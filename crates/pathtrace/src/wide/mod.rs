//! The lane-parallel building blocks of the path estimator (`integrator::path`): lane-group
//! types, the samplers continued in SIMD lanes, the brute-force intersector for small scenes,
//! flat area-light sampling and the warps of the Lambertian form.
//!
//! Why lanes of *paths*: one path leaves nothing to vectorise (the scalar loop spent ~5,300
//! instructions per Cornell-box sample spread thinly over traversal, shading and sampling);
//! groups of paths are what Mitsuba 3's `llvm_ad_rgb` variant and wavefront renderers
//! vectorise. [`WideScene`] holds what a scene offers these forms, prepared once per render;
//! lanes it cannot serve are shaded one at a time through the scene's own materials and
//! lights, within the same estimator.

// Lane loops index several structure-of-arrays fields with the same lane number; iterator
// chains over them would hide that and vectorise no better.
#![allow(clippy::needless_range_loop)]

mod boxes;
mod geometry;
pub mod inverse_trig;
mod light_picks;
mod lights;
pub mod prefetch;
mod sampler;
pub mod simd;
pub mod warp;

pub(crate) use geometry::FlatGeometry;
pub use geometry::MAX_FLAT_POLYGONS;
pub(crate) use lights::{LaneLightSample, LightSamples, WideLights};
pub(crate) use sampler::LaneSamplers;

use crate::integrator::{PathSettings, Strategy};
use crate::light::EnvSampling;
use crate::material::Material;
use crate::math::Rgb;
use crate::scene::Scene;

/// How many paths the estimator traces at once.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Kernel {
    /// Groups of 16 paths in SIMD lanes (32 with AVX-512): the default. `auto` and `wide` are
    /// the same since every scene runs in lanes; both names are kept for scripts.
    #[default]
    Auto,
    /// One path at a time: the one-lane instance of the same estimator, for debugging and tests.
    Scalar,
    /// Groups of 16 (32 with AVX-512) paths, as `auto`.
    Wide,
    /// The AVX2 kernel (8-lane vectors, groups of 16) even where AVX-512 offers 32: to check
    /// that AVX2 and AVX-512 machines give the same film (docs/distributed.md), and to measure
    /// the narrower build. Named when that kernel ran groups of 8.
    Wide8,
}

impl Kernel {
    pub const NAMES: [&'static str; 4] = ["auto", "scalar", "wide", "wide8"];

    pub fn name(self) -> &'static str {
        match self {
            Kernel::Auto => "auto",
            Kernel::Scalar => "scalar",
            Kernel::Wide => "wide",
            Kernel::Wide8 => "wide8",
        }
    }

    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "auto" => Some(Kernel::Auto),
            "scalar" => Some(Kernel::Scalar),
            "wide" => Some(Kernel::Wide),
            "wide8" => Some(Kernel::Wide8),
            _ => None,
        }
    }
}

impl std::str::FromStr for Kernel {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Self::from_name(s).ok_or_else(|| format!("unknown kernel '{s}' (expected auto, scalar, wide or wide8)"))
    }
}

impl std::fmt::Display for Kernel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// How the estimator treats a material, looked up once per lane and vertex.
#[derive(Clone, Copy, Debug)]
pub(crate) struct MaterialClass {
    /// A Lambertian surface, shaded in SIMD lanes with this albedo (or its texture's value at
    /// the hit); otherwise shaded lane by lane through `Material`.
    pub simd: bool,
    pub albedo: Rgb,
    /// Some colour is textured: evaluated per hit.
    pub textured: bool,
    /// Anisotropic: shaded in the frame of the surface's tangent.
    pub anisotropic: bool,
    /// A normal or bump map tilts its frame, per hit.
    pub perturbed: bool,
    /// Only Dirac lobes (mirror, smooth glass): no light sampling.
    pub delta: bool,
    /// Reflects nothing (pure emitters): the path ends there.
    pub black: bool,
    /// Scatters from its front only: seen from behind, the path ends there.
    pub one_sided: bool,
    /// The material's lane form, when its lanes are shaded together through it
    /// (`integrator::material_lanes`).
    pub lane_form: Option<LaneForm>,
}

/// The materials with a lane form ([`crate::material::LaneScattering`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum LaneForm {
    RoughConductor,
    RoughPlastic,
    Plastic,
    Dielectric,
    /// Smooth conductors and mirrors.
    SmoothConductor,
    ThinDielectric,
    RoughDielectric,
    Diffuse,
    Glossy,
    /// Lambertian surfaces under a normal or bump map (the others take the estimator's own
    /// Lambertian lanes).
    Lambertian,
}

/// What a scene offers the lane-parallel forms, prepared once per render.
#[derive(Clone, Debug)]
pub struct WideScene {
    /// Brute-force polygons for small scenes; `None`: intersect through the scene's BVH.
    pub(crate) geometry: Option<FlatGeometry>,
    /// The lights, in their lane-parallel forms.
    pub(crate) lights: WideLights,
    /// Per material: how the estimator treats it.
    pub(crate) classes: Vec<MaterialClass>,
    /// Some material with a lane form has textured colours.
    pub(crate) textured_forms: bool,
    pub(crate) settings: PathSettings,
    /// Some light can be hit by a ray (an area light, or an environment). Without one, a
    /// path's last segment could only find emitters that are not there: it is not traced.
    pub(crate) emitters_hittable: bool,
}

impl WideScene {
    /// Prepares `scene` for rendering with `settings`.
    pub fn new(scene: &Scene, settings: &PathSettings) -> Self {
        let classes = scene
            .materials()
            .iter()
            .enumerate()
            .map(|(id, m)| {
                // A normal or bump map moves the frame off the shading normal per hit: such
                // Lambertian surfaces take the generic lane form below, in their perturbed frames.
                let perturbed = scene.normal_perturbation(id as u32).is_some();
                let simd = match m {
                    Material::Lambertian(l) if !perturbed => Some(l.albedo),
                    _ => None,
                };
                // Materials with a lane form, shaded in lanes under a strategy that continues
                // paths by the material. Textured colours and a normal or bump map's frame are
                // evaluated per lane and set into the form; an anisotropic model's frame follows
                // the tangent.
                let plain = matches!(settings.strategy, Strategy::Bsdf | Strategy::Mis | Strategy::MisBalance);
                // Every model is named, so a new one must say here whether it has a lane form.
                let lane_form = match m {
                    Material::RoughConductor(_) if plain => Some(LaneForm::RoughConductor),
                    Material::RoughPlastic(_) if plain => Some(LaneForm::RoughPlastic),
                    Material::RoughDielectric(_) if plain => Some(LaneForm::RoughDielectric),
                    Material::Plastic(_) if plain => Some(LaneForm::Plastic),
                    Material::Diffuse(_) if plain => Some(LaneForm::Diffuse),
                    Material::Glossy(_) if plain => Some(LaneForm::Glossy),
                    Material::Lambertian(_) if plain && perturbed => Some(LaneForm::Lambertian),
                    // Models of Dirac lobes only: every strategy continues them by the material.
                    Material::Dielectric(_) => Some(LaneForm::Dielectric),
                    Material::Conductor(_) | Material::Mirror(_) => Some(LaneForm::SmoothConductor),
                    Material::ThinDielectric(_) => Some(LaneForm::ThinDielectric),
                    // The models above under the `light` and `mixture` strategies, which sample
                    // the lights' directions lane by lane.
                    Material::RoughConductor(_)
                    | Material::RoughPlastic(_)
                    | Material::RoughDielectric(_)
                    | Material::Plastic(_)
                    | Material::Diffuse(_)
                    | Material::Glossy(_) => None,
                    // Other Lambertian surfaces take the estimator's Lambertian lanes (`simd`), or,
                    // normal-mapped under `light` and `mixture`, go lane by lane; black and null
                    // surfaces are never shaded; a blend is resolved per hit into its two models.
                    Material::Lambertian(_) | Material::Black | Material::Null | Material::Blend(_) => None,
                };
                MaterialClass {
                    lane_form,
                    albedo: simd.unwrap_or(Rgb::BLACK),
                    simd: simd.is_some(),
                    textured: scene.is_material_textured(id as u32),
                    anisotropic: m.is_anisotropic(),
                    perturbed,
                    delta: m.is_delta(),
                    black: m.is_black(),
                    one_sided: scene.is_one_sided(id as u32),
                }
            })
            .collect::<Vec<MaterialClass>>();
        let textured_forms = classes.iter().any(|c| c.textured && c.lane_form.is_some());
        // The brute-force intersector reports normals, material and light, not uv or ∂p/∂u:
        // it serves scenes whose shading needs neither (no textures, no anisotropic frames).
        // Opacity masks are textures: scenes with cut-outs take the BVH, which passes them.
        let needs_uv = scene.has_textures() || scene.materials().iter().any(Material::is_anisotropic);
        let geometry = if needs_uv || scene.has_unbounded() || scene.has_instances() {
            None
        } else {
            scene.small_scene_shapes().filter(|p| p.len() <= MAX_FLAT_POLYGONS).and_then(|p| FlatGeometry::new(&p))
        };
        let emitters_hittable = scene.lights.area_lights().next().is_some() || scene.lights.environment().is_some();
        // MIS compensation of an environment map (`light/envmap.rs`) needs every light sample
        // weighed by MIS against a material sample, with one density for both: surface vertices
        // under `mis` draw their light samples here, but a medium vertex draws its own from the
        // scalar light set, with the complete density, so volumetric scenes keep that one.
        let env_sampling = if settings.strategy.is_mis() && !scene.is_volumetric() {
            EnvSampling::Compensated
        } else {
            EnvSampling::Complete
        };
        Self {
            geometry,
            lights: WideLights::new(&scene.lights, env_sampling),
            classes,
            textured_forms,
            settings: *settings,
            emitters_hittable,
        }
    }

    /// True when rays are tested against every polygon (small scenes) rather than the BVH.
    pub fn brute_force(&self) -> bool {
        self.geometry.is_some()
    }
}
