//! Lights: emissive surfaces (area lights) and the light set that picks one by power.

mod area;
mod set;

pub use area::{AreaLight, Emission, LightShape};
pub use set::{LightSample, LightSet};
