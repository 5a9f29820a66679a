//! pathtrace: a physically based Monte Carlo path tracer — the engine.
//!
//! The engine never prints, exits or opens a window; file formats live in `pathtrace-scene`.

pub mod film;
pub mod math;
pub mod sampling;
pub mod shape;
pub mod accel;
pub mod material;
pub mod light;
pub mod camera;
pub mod scene;

pub use camera::{Camera, CameraDesc};
pub use scene::{MaterialId, Scene, SceneBuilder};
pub mod integrator;
pub mod render;

pub use render::{render, Progress, RenderOutcome, RenderSession, RenderSettings};
