//! Integrators: how a camera ray becomes a radiance estimate.

mod features;
mod lanes;
mod material_lanes;
mod media;
mod path;
mod regenerate;
mod shade;
mod shading_frame;
mod strategy;

pub use path::{PathSettings, PathStats};
pub(crate) use regenerate::{render_tile_lanes, LaneJob};
pub use strategy::Strategy;
