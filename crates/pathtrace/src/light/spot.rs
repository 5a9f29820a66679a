//! Spot lights: a point light whose intensity falls off with the angle θ from its axis, with
//! Mitsuba 3's profile (`src/emitters/spot.cpp`): full `intensity` I for θ ≤ `beam_width`, a
//! linear ramp in θ down to zero at `cutoff_angle`, and nothing beyond.
//!
//! ```toml
//! [[lights]]
//! type = "spot"
//! intensity = [10, 10, 10]   # W·sr⁻¹ on the axis
//! cutoff_angle = 30          # degrees; default 20
//! beam_width = 20            # degrees; default 3/4 of cutoff_angle
//! # At the transform's origin, pointing along its local +z: here from (0, 4, 0) down.
//! transform = [{ look_at = { from = [0, 4, 0], to = [0, 0, 0], up = [0, 0, 1] } }]
//! ```
//!
//! Like a point light it is a Dirac delta in position: only next-event estimation sees it.

use crate::math::{Mat3, Rgb, Transform, Vec3};
use crate::wide::simd::{F32s, Ms, Vec3s};

/// A spot light placed by a transform: it sits at the local origin and points along local +z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotLight {
    position: Vec3,
    /// World → local for directions (the inverse of the transform's linear part), so the angle to
    /// the axis is measured exactly as Mitsuba measures it, also under a non-rigid transform.
    to_local: Mat3,
    intensity: Rgb,
    cutoff: f32,
    beam: f32,
    cos_cutoff: f32,
    cos_beam: f32,
    inv_transition: f32,
}

impl SpotLight {
    /// A spot light with `intensity` on its axis and the two angles in degrees; `None` unless
    /// 0 < beam_width ≤ cutoff_angle ≤ 180 (degrees), the intensity is finite and ≥ 0 and the
    /// transform is finite.
    pub fn new(to_world: &Transform, intensity: Rgb, cutoff_degrees: f32, beam_degrees: f32) -> Option<Self> {
        let i = intensity;
        let ok_i = i.is_finite() && i.r >= 0.0 && i.g >= 0.0 && i.b >= 0.0;
        let ok_angles = beam_degrees > 0.0 && beam_degrees <= cutoff_degrees && cutoff_degrees <= 180.0;
        let to_local = Mat3::from_mat4(to_world.inverse);
        let position = to_world.point(Vec3::ZERO);
        if !(ok_i && ok_angles && position.is_finite() && to_local.is_finite()) {
            return None;
        }
        let (cutoff, beam) = (cutoff_degrees.to_radians(), beam_degrees.to_radians());
        Some(Self {
            position,
            to_local,
            intensity,
            cutoff,
            beam,
            cos_cutoff: cutoff.cos(),
            cos_beam: beam.cos(),
            // Infinite when beam = cutoff: the ramp is then never evaluated (no θ lies between).
            inv_transition: 1.0 / (cutoff - beam),
        })
    }

    /// Mitsuba's default beam width: 3/4 of the cutoff angle.
    pub fn default_beam_width(cutoff_degrees: f32) -> f32 {
        0.75 * cutoff_degrees
    }

    /// Where the light sits.
    pub fn position(&self) -> Vec3 {
        self.position
    }

    /// The falloff factor in [0, 1] for the world direction `w` leaving the light: 1 inside the
    /// beam, (θc − θ)/(θc − θb) in the transition, 0 at and beyond the cutoff (Mitsuba 3's
    /// `falloff_curve`). The one-lane instance of [`SpotLanes::falloff`].
    pub fn falloff(&self, w: Vec3) -> f32 {
        self.lanes::<1>().falloff(&Vec3s::splat(w)).0[0]
    }

    /// This light in every lane of a group.
    #[inline(always)]
    pub(crate) fn lanes<const N: usize>(&self) -> SpotLanes<N> {
        let column = |c: Vec3| Vec3s::splat(c);
        SpotLanes {
            position: Vec3s::splat(self.position),
            to_local: [column(self.to_local.x_axis), column(self.to_local.y_axis), column(self.to_local.z_axis)],
            intensity: self.intensity.to_array().map(F32s::splat),
            cutoff: F32s::splat(self.cutoff),
            cos_cutoff: F32s::splat(self.cos_cutoff),
            cos_beam: F32s::splat(self.cos_beam),
            inv_transition: F32s::splat(self.inv_transition),
        }
    }

    /// Total emitted power in luminance units: I · ∫ falloff dω = 2π I [1 − (sin θc − sin θb)/(θc − θb)]
    /// (integrating the linear ramp by parts; → 2π I (1 − cos θc) when θb = θc).
    pub fn power(&self) -> f64 {
        let (c, b) = (self.cutoff as f64, self.beam as f64);
        let solid_angle = if c - b > 1e-6 {
            2.0 * std::f64::consts::PI * (1.0 - (c.sin() - b.sin()) / (c - b))
        } else {
            2.0 * std::f64::consts::PI * (1.0 - c.cos())
        };
        self.intensity.luminance_f64() * solid_angle
    }

    /// The unit direction and distance from `ref_p` to the light, and I·falloff/r², the
    /// radiance-like term of a Dirac delta in direction: the one-lane instance of
    /// [`SpotLanes::sample`].
    pub(super) fn sample(&self, ref_p: Vec3) -> Option<(Vec3, f32, Rgb)> {
        let (wi, dist, radiance, valid) = self.lanes::<1>().sample(&Vec3s::splat(ref_p));
        valid.lane(0).then(|| (wi.lane(0), dist.0[0], Rgb::new(radiance[0].0[0], radiance[1].0[0], radiance[2].0[0])))
    }
}

/// Spot lights per lane (lanes can hold different ones).
#[derive(Clone, Copy, Debug)]
pub(crate) struct SpotLanes<const N: usize> {
    pub position: Vec3s<N>,
    /// The columns of the world → local matrix for directions.
    pub to_local: [Vec3s<N>; 3],
    pub intensity: [F32s<N>; 3],
    pub cutoff: F32s<N>,
    pub cos_cutoff: F32s<N>,
    pub cos_beam: F32s<N>,
    pub inv_transition: F32s<N>,
}

impl<const N: usize> SpotLanes<N> {
    /// Lane `i` holds `l`.
    #[inline(always)]
    pub fn set(&mut self, i: usize, l: &SpotLight) {
        self.position.set(i, l.position);
        for (column, c) in self.to_local.iter_mut().zip([l.to_local.x_axis, l.to_local.y_axis, l.to_local.z_axis]) {
            column.set(i, c);
        }
        [self.intensity[0].0[i], self.intensity[1].0[i], self.intensity[2].0[i]] = l.intensity.to_array();
        self.cutoff.0[i] = l.cutoff;
        self.cos_cutoff.0[i] = l.cos_cutoff;
        self.cos_beam.0[i] = l.cos_beam;
        self.inv_transition.0[i] = l.inv_transition;
    }

    /// [`SpotLight::falloff`] per lane, for world directions `w` leaving the lanes' lights.
    #[inline(always)]
    pub fn falloff(&self, w: &Vec3s<N>) -> F32s<N> {
        // M·w as glam's `Mat3::mul_vec3` (x_axis·wx + y_axis·wy + z_axis·wz), then
        // `normalize_or_zero`'s z: times the reciprocal length where that is finite and positive.
        let [cx, cy, cz] = &self.to_local;
        let local = cx.scale(w.x).add(&cy.scale(w.y)).add(&cz.scale(w.z));
        let rcp = 1.0 / local.length();
        let cos_theta = F32s::select(rcp.is_finite() & rcp.gt(F32s::ZERO), local.z * rcp, F32s::ZERO);
        // The ramp (θc − θ)/(θc − θb), θ = acos(cos θ): libm's acos per lane, as the scalar form.
        let ramp = F32s::from_fn(|i| {
            let theta = cos_theta.0[i].clamp(-1.0, 1.0).acos();
            ((self.cutoff.0[i] - theta) * self.inv_transition.0[i]).clamp(0.0, 1.0)
        });
        let inside = cos_theta.ge(self.cos_beam);
        F32s::select(cos_theta.le(self.cos_cutoff), F32s::ZERO, F32s::select(inside, F32s::ONE, ramp))
    }

    /// Per lane, the unit direction and distance from `ref_p` to the lane's light, I·falloff/r²,
    /// and whether the lane has a sample (the two points differ and are finitely apart).
    #[inline(always)]
    pub fn sample(&self, ref_p: &Vec3s<N>) -> (Vec3s<N>, F32s<N>, [F32s<N>; 3], Ms<N>) {
        let (wi, dist, dist2, valid) = super::point::towards_lanes(&self.position, ref_p);
        let scale = self.falloff(&wi.neg()) / dist2;
        (wi, dist, self.intensity.map(|i| i * scale), valid)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn power_matches_a_numerical_integral_of_the_falloff() {
        let spot = SpotLight::new(&Transform::rotate_x(37.0), Rgb::WHITE, 40.0, 15.0).unwrap();
        // Midpoint rule over θ around the (rotated) axis: ∫ f(θ) 2π sin θ dθ.
        let axis = Transform::rotate_x(37.0).vector(Vec3::Z);
        let perp = axis.any_orthonormal_vector();
        let n = 20000;
        let mut sum = 0.0f64;
        for k in 0..n {
            let theta = (k as f64 + 0.5) / n as f64 * std::f64::consts::PI;
            let w = axis * theta.cos() as f32 + perp * theta.sin() as f32;
            sum +=
                spot.falloff(w) as f64 * 2.0 * std::f64::consts::PI * theta.sin() * (std::f64::consts::PI / n as f64);
        }
        assert!((spot.power() - sum).abs() < 1e-3 * sum, "{} vs {sum}", spot.power());
        assert!(spot.power() < 2.0 * std::f64::consts::PI * (1.0 - 40f64.to_radians().cos()));
    }

    #[test]
    fn falloff_is_one_in_the_beam_linear_in_the_ramp_and_zero_outside() {
        let spot = SpotLight::new(&Transform::IDENTITY, Rgb::WHITE, 30.0, 10.0).unwrap();
        let at = |deg: f32| {
            let t = deg.to_radians();
            spot.falloff(Vec3::new(t.sin(), 0.0, t.cos()))
        };
        assert_eq!(at(0.0), 1.0);
        assert_eq!(at(9.9), 1.0);
        assert!((at(20.0) - 0.5).abs() < 1e-4);
        assert!((at(25.0) - 0.25).abs() < 1e-4);
        assert_eq!(at(30.5), 0.0);
        assert_eq!(at(170.0), 0.0);
        assert!(SpotLight::new(&Transform::IDENTITY, Rgb::WHITE, 10.0, 20.0).is_none(), "beam > cutoff");
    }
}
