//! The wide kernel: eight paths traced side by side in SIMD lanes, for scenes made of
//! Lambertian surfaces lit by flat area lights (the Cornell box and its kin).
//!
//! Why: the scalar path loop spends ~5,300 instructions per camera sample spread thinly over
//! traversal, shading and sampling, with nothing left to vectorise inside one path. Lanes of
//! *paths* are what Mitsuba 3's `llvm_ad_rgb` variant and wavefront renderers vectorise. A lane
//! whose path ends starts the next camera sample of its tile at once ("path regeneration"),
//! so lanes stay busy instead of waiting for the longest path of a packet.
//!
//! The kernel computes the same estimator as `integrator::path` with the `mis` and
//! `mis-balance` strategies: the same random dimensions in the same order from the same
//! per-sample sampler (so stratified and Sobol samplers keep their properties), the same
//! next-event estimation, MIS weights, cosine sampling and Russian roulette. Its images agree
//! with the scalar kernel's within confidence intervals (tests/wide_kernel.rs); they are not
//! bit-identical (different rounding, polynomial sin/cos).
//!
//! Scenes outside its reach (other materials, textures, spheres, point, spot, sphere or
//! environment lights, other strategies) render with the scalar kernel: see
//! [`WideScene::new`] and `RenderSettings::kernel`.

// Lane loops index several structure-of-arrays fields with the same lane number; iterator
// chains over them would hide that and vectorise no better.
#![allow(clippy::needless_range_loop)]

mod boxes;
mod geometry;
mod kernel;
mod lights;
mod sampler;
pub mod simd;
pub mod warp;

pub use geometry::MAX_FLAT_POLYGONS;
pub(crate) use kernel::{render_tile_wide, WideJob};

use crate::integrator::{PathSettings, Strategy};
use crate::material::Material;
use crate::math::Rgb;
use crate::scene::Scene;
use geometry::FlatGeometry;
use lights::WideLights;

/// Which path loop renders.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Kernel {
    /// The wide kernel when the scene and settings allow it, else the scalar one (the default).
    #[default]
    Auto,
    /// One path at a time (`integrator::path`): every scene and strategy.
    Scalar,
    /// Eight paths at a time; rendering fails if the scene or settings do not allow it.
    Wide,
}

impl Kernel {
    pub const NAMES: [&'static str; 3] = ["auto", "scalar", "wide"];

    pub fn name(self) -> &'static str {
        match self {
            Kernel::Auto => "auto",
            Kernel::Scalar => "scalar",
            Kernel::Wide => "wide",
        }
    }

    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "auto" => Some(Kernel::Auto),
            "scalar" => Some(Kernel::Scalar),
            "wide" => Some(Kernel::Wide),
            _ => None,
        }
    }
}

impl std::str::FromStr for Kernel {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Self::from_name(s).ok_or_else(|| format!("unknown kernel '{s}' (expected auto, scalar or wide)"))
    }
}

impl std::fmt::Display for Kernel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// What the wide kernel needs of a scene, prepared once per render.
#[derive(Clone, Debug)]
pub struct WideScene {
    /// Brute-force polygons for small scenes; `None`: intersect through the scene's BVH.
    geometry: Option<FlatGeometry>,
    lights: WideLights,
    /// Per material: Lambertian albedo, or `None` for black (pure emitters).
    albedo: Vec<Option<Rgb>>,
    settings: PathSettings,
}

impl WideScene {
    /// Prepares `scene` for the wide kernel, or says why it cannot take it.
    pub fn new(scene: &Scene, settings: &PathSettings) -> Result<Self, String> {
        if !matches!(settings.strategy, Strategy::Mis | Strategy::MisBalance) {
            return Err(format!("strategy '{}' (only mis and mis-balance)", settings.strategy.name()));
        }
        if scene.has_textures() {
            return Err("textures".into());
        }
        if scene.has_unbounded() || scene.has_instances() {
            return Err("infinite planes or instances".into());
        }
        let albedo = scene
            .materials()
            .iter()
            .map(|m| match m {
                Material::Lambertian(l) => Ok(Some(l.albedo)),
                Material::Black => Ok(None),
                other => Err(format!("material '{}' (only lambertian)", other.name())),
            })
            .collect::<Result<Vec<_>, _>>()?;
        let lights = WideLights::new(&scene.lights)
            .ok_or("lights other than quad or triangle area lights (point, spot, sphere, disk, environment)")?;
        if scene.lights.is_empty() {
            return Err("no light with power".into());
        }
        let geometry =
            scene.flat_polygons().filter(|p| p.len() <= MAX_FLAT_POLYGONS).and_then(|p| FlatGeometry::new(&p));
        Ok(Self { geometry, lights, albedo, settings: *settings })
    }

    /// True when rays are tested against every polygon (small scenes) rather than the BVH.
    pub fn brute_force(&self) -> bool {
        self.geometry.is_some()
    }
}
