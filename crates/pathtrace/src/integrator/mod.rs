//! Integrators: how a camera ray becomes a radiance estimate.

mod aov;
mod path;
mod strategy;

pub use aov::{first_hit_aovs, FirstHitAovs};

pub use path::{radiance, PathSettings, PathStats};
pub use strategy::Strategy;
