//! Directional lights: a distant source (the sun) sending parallel light along one direction,
//! `irradiance` E in W·m⁻² per channel on a surface facing it. A surface with normal n receives
//! E·max(0, n·(−d)) from it. Like Mitsuba 3's `directional` emitter (src/emitters/directional.cpp)
//! it sends light along the transform's local +z (or along `direction`) and has no position: a
//! shadow ray towards it is unoccluded when it leaves the scene.
//!
//! ```toml
//! [[lights]]
//! type = "directional"
//! irradiance = [3, 3, 3]      # W·m⁻²
//! direction = [0, -1, -0.5]   # where the light travels (or a transform's local +z)
//! ```
//!
//! It is a Dirac delta in direction: only next-event estimation sees it, and no ray hits it.

use crate::math::{Rgb, Transform, Vec3};

/// A light at infinity shining along one direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionalLight {
    /// Unit direction the light travels in.
    direction: Vec3,
    irradiance: Rgb,
}

impl DirectionalLight {
    /// A light travelling along `direction` (normalised here) with `irradiance`; `None` when the
    /// direction is zero or not finite, or the irradiance negative or not finite.
    pub fn new(direction: Vec3, irradiance: Rgb) -> Option<Self> {
        let e = irradiance;
        let ok = e.is_finite() && e.r >= 0.0 && e.g >= 0.0 && e.b >= 0.0;
        let direction = direction.try_normalize().filter(|d| d.is_finite())?;
        ok.then_some(Self { direction, irradiance })
    }

    /// The light that `to_world` places shining along its local +z (Mitsuba's default frame).
    pub fn from_transform(to_world: &Transform, irradiance: Rgb) -> Option<Self> {
        Self::new(to_world.vector(Vec3::Z), irradiance)
    }

    /// The unit direction the light travels in.
    pub fn direction(&self) -> Vec3 {
        self.direction
    }

    /// The irradiance on a surface facing the light (W·m⁻² per channel).
    pub fn irradiance(&self) -> Rgb {
        self.irradiance
    }

    /// Power reaching a scene inside a sphere of `scene_radius`, in luminance units: the light
    /// crosses the sphere's disk, π r²·E (as Mitsuba's `sample_ray` weight π r²).
    pub fn power(&self, scene_radius: f32) -> f64 {
        // In f64, as every light's power: a bright light's would overflow f32.
        std::f64::consts::PI * f64::from(scene_radius).powi(2) * self.irradiance.luminance_f64()
    }

    /// The unit direction towards the light and the radiance-like term E that the integrator
    /// treats as a Dirac delta in direction (the same from every point).
    pub(super) fn sample(&self) -> (Vec3, Rgb) {
        (-self.direction, self.irradiance)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_checks_and_normalises() {
        let l = DirectionalLight::new(Vec3::new(0.0, -2.0, 0.0), Rgb::splat(1.0)).unwrap();
        assert_eq!(l.sample(), (Vec3::Y, Rgb::splat(1.0)));
        assert!(DirectionalLight::new(Vec3::ZERO, Rgb::splat(1.0)).is_none());
        assert!(DirectionalLight::new(Vec3::X, Rgb::new(-1.0, 0.0, 0.0)).is_none());
        assert!(DirectionalLight::new(Vec3::new(f32::NAN, 0.0, 1.0), Rgb::splat(1.0)).is_none());
        let t = Transform::rotate_x(90.0);
        let d = DirectionalLight::from_transform(&t, Rgb::splat(1.0)).unwrap().direction();
        assert!((d - t.vector(Vec3::Z)).length() < 1e-6);
    }

    #[test]
    fn power_is_the_disk_of_the_scene() {
        let l = DirectionalLight::new(Vec3::Z, Rgb::splat(2.0)).unwrap();
        assert!((l.power(3.0) - std::f64::consts::PI * 9.0 * 2.0).abs() < 1e-4);
    }
}
