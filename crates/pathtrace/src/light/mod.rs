//! Lights: emissive surfaces (area lights), point, spot and directional lights, the environment, and the light
//! set that picks one by power or uniformly.

pub(crate) mod area;
mod directional;
mod environment;
mod envmap;
mod kind;
mod point;
mod radiance_texture;
mod set;
mod spot;

pub use area::{AreaLight, Emission, LightShape};
pub use directional::DirectionalLight;
pub use environment::EnvironmentLight;
pub use envmap::{EnvMap, EnvSamples, EnvSampling};
pub use kind::Light;
pub use point::PointLight;
pub use radiance_texture::RadianceTexture;
pub use set::{LightSample, LightSelection, LightSet};
pub(crate) use spot::SpotLanes;
pub use spot::SpotLight;
