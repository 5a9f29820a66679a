//! Maths primitives: glam re-exports, colours, frames, transforms, boxes and rays.

mod rgb;

pub use glam::{Mat4, Vec2, Vec3};
pub use rgb::Rgb;
