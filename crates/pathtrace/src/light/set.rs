//! The scene's lights, with a discrete distribution that picks one in proportion to its power.

use super::area::AreaLight;
use crate::math::{Rgb, Vec2, Vec3};
use crate::sampling::Distribution1D;

/// A light sample as the integrator sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    pub point: Vec3,
    pub normal: Vec3,
    /// Unit direction from the reference point to `point`.
    pub wi: Vec3,
    pub dist: f32,
    /// Solid-angle density, including the probability of having picked this light.
    pub pdf: f32,
    /// Radiance the light sends towards the reference point.
    pub radiance: Rgb,
}

/// All lights, selectable by power.
#[derive(Clone, Debug, Default)]
pub struct LightSet {
    lights: Vec<AreaLight>,
    selection: Option<Distribution1D>,
}

impl LightSet {
    /// Lights of zero power are kept (so ids stay valid) but never picked.
    pub fn new(lights: Vec<AreaLight>) -> Self {
        let powers: Vec<f32> = lights.iter().map(AreaLight::power).collect();
        let selection = Distribution1D::new(&powers);
        Self { lights, selection }
    }

    pub fn len(&self) -> usize {
        self.lights.len()
    }

    /// True when nothing can be sampled (no lights, or none with power).
    pub fn is_empty(&self) -> bool {
        self.selection.is_none()
    }

    pub fn get(&self, id: u32) -> Option<&AreaLight> {
        self.lights.get(id as usize)
    }

    pub fn iter(&self) -> impl Iterator<Item = &AreaLight> {
        self.lights.iter()
    }

    /// Probability of picking light `id`.
    pub fn selection_pmf(&self, id: u32) -> f32 {
        self.selection.as_ref().map_or(0.0, |d| d.pmf(id as usize))
    }

    /// Picks a light by power and a point on it.
    #[inline(always)]
    pub fn sample(&self, ref_p: Vec3, u_select: f32, u: Vec2) -> Option<LightSample> {
        let (id, pmf) = self.selection.as_ref()?.sample(u_select);
        let light = &self.lights[id];
        let s = light.sample(ref_p, u)?;
        Some(LightSample {
            point: s.point,
            normal: s.normal,
            wi: s.wi,
            dist: s.dist,
            pdf: s.pdf * pmf,
            radiance: light.emitted(s.normal, -s.wi),
        })
    }

    /// Density of sampling hit point `p` on light `id` from `ref_p` (selection included).
    #[inline(always)]
    pub fn pdf_hit(&self, id: u32, ref_p: Vec3, p: Vec3, n: Vec3) -> f32 {
        let pmf = self.selection_pmf(id);
        if pmf <= 0.0 {
            return 0.0;
        }
        pmf * self.lights[id as usize].pdf_hit(ref_p, p, n)
    }

    /// Density of direction `dir` under light sampling from `ref_p`: the sum over all lights
    /// (O(number of lights): used only by the mixture and light-only strategies).
    pub fn pdf_direction(&self, ref_p: Vec3, dir: Vec3) -> f32 {
        let Some(sel) = &self.selection else {
            return 0.0;
        };
        self.lights
            .iter()
            .enumerate()
            .filter(|(i, _)| sel.pmf(*i) > 0.0)
            .map(|(i, l)| sel.pmf(i) * l.pdf_direction(ref_p, dir))
            .sum()
    }
}
