//! Maths primitives: glam re-exports, colours, frames, transforms, boxes and rays.

mod aabb;
mod exp_log;
mod frame;
mod ray;
mod rgb;
pub mod special;
mod transform;

pub use aabb::Aabb;
pub use exp_log::{exp_f64_lanes, exp_lanes, ln_lanes};
pub use frame::Frame;
pub use glam::{Mat3, Mat4, Vec2, Vec3, Vec4};
pub use ray::{offset_ray_origin, offset_ray_origin_lanes, Ray};
pub use rgb::Rgb;
pub use transform::{InvalidTransform, Transform};

/// π as f32.
pub const PI: f32 = std::f32::consts::PI;
/// 1/π.
pub const INV_PI: f32 = std::f32::consts::FRAC_1_PI;
/// 1/(2π).
pub const INV_2PI: f32 = 0.5 * std::f32::consts::FRAC_1_PI;
/// 1/(4π).
pub const INV_4PI: f32 = 0.25 * std::f32::consts::FRAC_1_PI;

/// `v` scaled to unit length, or `None` when it is zero or not finite. Unlike
/// `Vec3::try_normalize`, it first divides by the largest component, so vectors longer than
/// ~1.8e19 (whose squared length overflows f32) still have a direction.
pub fn normalize_robust(v: Vec3) -> Option<Vec3> {
    let largest = v.abs().max_element();
    if !(largest.is_finite() && largest > 0.0) {
        return None;
    }
    (v / largest).try_normalize()
}
