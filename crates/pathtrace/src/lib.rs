//! pathtrace: a physically based Monte Carlo path tracer — the engine.
//!
//! The engine never prints, exits or opens a window; file formats live in `pathtrace-scene`.

pub mod accel;
pub mod camera;
mod cutout;
pub mod film;
pub mod instance;
pub mod light;
pub mod material;
pub mod math;
pub mod medium;
mod primitive_store;
pub mod sampling;
pub mod scene;
pub mod shape;
pub mod texture;

pub use camera::{Camera, CameraDesc, Lens};
pub use instance::{GroupId, ShapeGroup};
pub use scene::{MaterialId, Scene, SceneBuilder};
pub mod integrator;
pub mod render;
pub mod wide;

pub use render::{render, AdaptiveSettings, Progress, RenderOutcome, RenderSession, RenderSettings, SampleRange};
pub mod metrics;
