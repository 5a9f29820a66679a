//! Scene formats for pathtrace: every way a scene arrives (today: the built-in scenes) becomes a
//! [`pathtrace::Scene`] through the engine's `SceneBuilder`; plus mesh files ([`mesh`]: OBJ, PLY) and
//! image reading and writing.

pub mod builtin;
pub mod image_io;
pub mod mesh;

use pathtrace::Scene;

/// What a scene suggests for rendering it, before command-line overrides.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RenderDefaults {
    pub width: u32,
    pub height: u32,
    pub spp: u32,
    /// Maximum path segments; -1 is unlimited.
    pub max_depth: i32,
}

/// A built scene with its suggested render settings.
#[derive(Clone, Debug)]
pub struct LoadedScene {
    pub scene: Scene,
    pub defaults: RenderDefaults,
}
