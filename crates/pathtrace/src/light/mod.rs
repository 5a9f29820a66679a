//! Lights: emissive surfaces (area lights), point lights, the environment, and the light set
//! that picks one by power.

mod area;
mod environment;
mod envmap;
mod point;
mod set;

pub use area::{AreaLight, Emission, LightShape};
pub use environment::EnvironmentLight;
pub use envmap::EnvMap;
pub use point::PointLight;
pub use set::{LightSample, LightSet};
