//! The scene's lights, with a discrete distribution that picks one in proportion to its power.
//!
//! Lights are numbered area lights first (so a primitive's light id indexes them), then point
//! lights, then the environment. Two selection distributions exist: `selection` over all
//! lights, for next-event estimation, and `continuous` without the point lights, for the
//! `light` and `mixture` strategies, which continue the path along the sampled direction and so
//! need a density in solid angle (a point light has none). Without point lights both are the
//! same distribution.

use super::area::AreaLight;
use super::environment::EnvironmentLight;
use super::point::PointLight;
use crate::math::{Rgb, Vec2, Vec3};
use crate::sampling::Distribution1D;

/// A light sample as the integrator sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    pub point: Vec3,
    pub normal: Vec3,
    /// Unit direction from the reference point to `point`.
    pub wi: Vec3,
    /// Distance to `point`; infinite for the environment (then `point` is meaningless).
    pub dist: f32,
    /// Solid-angle density, including the probability of having picked this light; for a point
    /// light (`delta`), only the probability of having picked it.
    pub pdf: f32,
    /// Radiance the light sends towards the reference point (for a point light: I/r²).
    pub radiance: Rgb,
    /// True for a point light: a Dirac delta in direction, which bsdf sampling can never find.
    pub delta: bool,
}

/// All lights, selectable by power.
#[derive(Clone, Debug, Default)]
pub struct LightSet {
    lights: Vec<AreaLight>,
    points: Vec<PointLight>,
    environment: Option<EnvironmentLight>,
    selection: Option<Distribution1D>,
    continuous: Option<Distribution1D>,
}

/// What a selection index refers to.
enum Picked<'a> {
    Area(&'a AreaLight),
    Point(&'a PointLight),
    Environment(&'a EnvironmentLight),
}

impl LightSet {
    /// Area lights only. Lights of zero power are kept (so ids stay valid) but never picked.
    pub fn new(lights: Vec<AreaLight>) -> Self {
        Self::with_all(lights, Vec::new(), None, 0.0)
    }

    /// Area lights, point lights and an optional environment, whose power is measured over a
    /// scene bounded by a sphere of radius `scene_radius`.
    pub fn with_all(
        lights: Vec<AreaLight>,
        points: Vec<PointLight>,
        environment: Option<EnvironmentLight>,
        scene_radius: f32,
    ) -> Self {
        let area: Vec<f32> = lights.iter().map(AreaLight::power).collect();
        let point: Vec<f32> = points.iter().map(PointLight::power).collect();
        let env: Vec<f32> = environment.iter().map(|e| e.power(scene_radius.max(1e-3))).collect();
        let all: Vec<f32> = area.iter().chain(&point).chain(&env).copied().collect();
        let selection = Distribution1D::new(&all);
        let continuous = if points.is_empty() {
            selection.clone()
        } else {
            // Same indices, with the point lights' power zeroed.
            let zeros = vec![0.0; point.len()];
            let no_points: Vec<f32> = area.iter().chain(&zeros).chain(&env).copied().collect();
            Distribution1D::new(&no_points)
        };
        Self { lights, points, environment, selection, continuous }
    }

    /// Number of area lights.
    pub fn len(&self) -> usize {
        self.lights.len()
    }

    /// True when nothing can be sampled (no lights, or none with power).
    pub fn is_empty(&self) -> bool {
        self.selection.is_none()
    }

    /// True when some light other than a point light has power (the `light` and `mixture`
    /// strategies can sample it).
    pub fn has_continuous(&self) -> bool {
        self.continuous.is_some()
    }

    /// The area light with this id.
    pub fn get(&self, id: u32) -> Option<&AreaLight> {
        self.lights.get(id as usize)
    }

    /// The area lights.
    pub fn iter(&self) -> impl Iterator<Item = &AreaLight> {
        self.lights.iter()
    }

    pub fn points(&self) -> &[PointLight] {
        &self.points
    }

    pub fn environment(&self) -> Option<&EnvironmentLight> {
        self.environment.as_ref()
    }

    fn env_index(&self) -> usize {
        self.lights.len() + self.points.len()
    }

    fn picked(&self, i: usize) -> Picked<'_> {
        let n = self.lights.len();
        if i < n {
            Picked::Area(&self.lights[i])
        } else if i < n + self.points.len() {
            Picked::Point(&self.points[i - n])
        } else {
            match &self.environment {
                Some(e) => Picked::Environment(e),
                // Unreachable: indices past the points exist only with an environment.
                None => Picked::Point(&self.points[self.points.len() - 1]),
            }
        }
    }

    /// Probability of picking area light `id` for next-event estimation.
    pub fn selection_pmf(&self, id: u32) -> f32 {
        self.selection.as_ref().map_or(0.0, |d| d.pmf(id as usize))
    }

    /// Picks a light by power (any kind) and a point on it: next-event estimation.
    #[inline(always)]
    pub fn sample(&self, ref_p: Vec3, u_select: f32, u: Vec2) -> Option<LightSample> {
        let (id, pmf) = self.selection.as_ref()?.sample(u_select);
        self.sample_picked(id, pmf, ref_p, u)
    }

    /// Picks a light other than a point light by power and a direction towards it: the `light`
    /// and `mixture` strategies, whose density is [`LightSet::pdf_direction`].
    #[inline(always)]
    pub fn sample_continuous(&self, ref_p: Vec3, u_select: f32, u: Vec2) -> Option<LightSample> {
        let (id, pmf) = self.continuous.as_ref()?.sample(u_select);
        self.sample_picked(id, pmf, ref_p, u)
    }

    #[inline(always)]
    fn sample_picked(&self, id: usize, pmf: f32, ref_p: Vec3, u: Vec2) -> Option<LightSample> {
        match self.picked(id) {
            Picked::Area(light) => {
                let s = light.sample(ref_p, u)?;
                Some(LightSample {
                    point: s.point,
                    normal: s.normal,
                    wi: s.wi,
                    dist: s.dist,
                    pdf: s.pdf * pmf,
                    radiance: light.emitted(s.normal, -s.wi),
                    delta: false,
                })
            }
            Picked::Point(light) => {
                let (wi, dist, radiance) = light.sample(ref_p)?;
                Some(LightSample { point: light.position, normal: -wi, wi, dist, pdf: pmf, radiance, delta: true })
            }
            Picked::Environment(env) => {
                let (wi, pdf) = env.sample(u);
                if pdf <= 0.0 {
                    return None;
                }
                Some(LightSample {
                    point: ref_p + wi,
                    normal: -wi,
                    wi,
                    dist: f32::INFINITY,
                    pdf: pdf * pmf,
                    radiance: env.radiance(wi),
                    delta: false,
                })
            }
        }
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

    /// Density with which next-event estimation picks the environment along `dir` (selection
    /// included), for weighting a path that escaped along `dir`.
    #[inline(always)]
    pub fn pdf_environment(&self, dir: Vec3) -> f32 {
        match (&self.environment, &self.selection) {
            (Some(env), Some(sel)) => sel.pmf(self.env_index()) * env.pdf(dir),
            _ => 0.0,
        }
    }

    /// Density of direction `dir` under [`LightSet::sample_continuous`] from `ref_p`: the sum over
    /// all lights but point lights (O(number of lights): used only by the mixture and light-only
    /// strategies).
    pub fn pdf_direction(&self, ref_p: Vec3, dir: Vec3) -> f32 {
        let Some(sel) = &self.continuous else {
            return 0.0;
        };
        let area: f32 = self
            .lights
            .iter()
            .enumerate()
            .filter(|(i, _)| sel.pmf(*i) > 0.0)
            .map(|(i, l)| sel.pmf(i) * l.pdf_direction(ref_p, dir))
            .sum();
        let env = self.environment.as_ref().map_or(0.0, |e| sel.pmf(self.env_index()) * e.pdf(dir));
        area + env
    }
}
