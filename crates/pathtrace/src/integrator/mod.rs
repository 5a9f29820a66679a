//! Integrators: how a camera ray becomes a radiance estimate.

mod path;
mod strategy;

pub use path::{radiance, PathSettings, PathStats};
pub use strategy::Strategy;
