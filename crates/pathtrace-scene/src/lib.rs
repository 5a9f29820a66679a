//! Scene formats for pathtrace: every way a scene arrives (native TOML/JSON files, the built-in
//! scenes, which are embedded native files) becomes a [`pathtrace::Scene`] through the engine's
//! `SceneBuilder`; plus mesh files ([`mesh`]: OBJ, PLY) and image reading and writing.

pub mod builtin;
pub mod elide;
pub mod film_file;
pub mod gltf;
pub mod image_io;
pub mod load;
pub mod mesh;
pub mod mitsuba;
pub mod native;
mod overrides;

pub use load::load_file;
pub use overrides::RenderOverrides;

use pathtrace::integrator::Strategy;
use pathtrace::sampling::SamplerKind;
use pathtrace::Scene;

/// What a scene suggests for rendering it, before command-line overrides.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderDefaults {
    pub width: u32,
    pub height: u32,
    pub spp: u32,
    /// Maximum path segments; -1 is unlimited.
    pub max_depth: i32,
    /// Path segments after which Russian roulette may end a path, if the scene says.
    pub rr_depth: Option<u32>,
    /// Direction sampling strategy, if the scene names one.
    pub strategy: Option<Strategy>,
    /// Pixel sampler, if the scene names one.
    pub sampler: Option<SamplerKind>,
    /// Random seed, if the scene gives one.
    pub seed: Option<u64>,
    /// Pixel reconstruction filter, if the scene names one.
    pub filter: Option<pathtrace::film::PixelFilter>,
    /// How lights are picked, if the scene says.
    pub light_selection: Option<pathtrace::light::LightSelection>,
}

/// A built scene with its suggested render settings.
#[derive(Clone, Debug)]
pub struct LoadedScene {
    pub scene: Scene,
    pub defaults: RenderDefaults,
}
