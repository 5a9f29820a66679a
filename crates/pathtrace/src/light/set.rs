//! The scene's lights, with a discrete distribution that picks one in proportion to its power
//! (the default) or uniformly ([`LightSelection`]).
//!
//! Lights are numbered in the order the scene gives them (the scene builder puts area lights
//! first, so a primitive's light id indexes them). Two selection distributions exist:
//! `selection` over all lights, for next-event estimation, and `continuous` without the delta
//! lights (point, spot, directional), for the `light` and `mixture` strategies, which continue
//! the path along the sampled direction and so need a density in solid angle (a delta light has
//! none). Without delta lights both are the same distribution.

use super::area::AreaLight;
use super::environment::EnvironmentLight;
use super::kind::Light;
use crate::math::{Rgb, Vec2, Vec3};
use crate::sampling::Distribution1D;
use crate::wide::simd::{F32s, Ms};

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
    /// True for a point or spot light: a Dirac delta in direction, which bsdf sampling can never
    /// find.
    pub delta: bool,
}

/// How next-event estimation picks a light.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum LightSelection {
    /// In proportion to each light's emitted power (the default): bright lights get the samples.
    #[default]
    Power,
    /// Every emitter with nonzero power equally likely, Mitsuba's default: an emitter is what the
    /// scene declared as one (a shape or a whole emissive mesh, a point, spot or directional
    /// light, the environment); within an emissive mesh, its triangles are picked by area, as
    /// Mitsuba samples a point on the mesh by area.
    Uniform,
}

impl LightSelection {
    /// The scene-file and command-line name.
    pub fn name(self) -> &'static str {
        match self {
            LightSelection::Power => "power",
            LightSelection::Uniform => "uniform",
        }
    }

    /// Parses `power` or `uniform`.
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "power" => Some(LightSelection::Power),
            "uniform" => Some(LightSelection::Uniform),
            _ => None,
        }
    }
}

impl std::str::FromStr for LightSelection {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Self::from_name(s).ok_or_else(|| format!("unknown light selection '{s}' (expected power or uniform)"))
    }
}

impl std::fmt::Display for LightSelection {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// All lights, selectable by power or uniformly.
#[derive(Clone, Debug, Default)]
pub struct LightSet {
    /// Every light, in selection order; a primitive's light id indexes it.
    lights: Vec<Light>,
    /// Where the environment is in `lights`, if the scene has one.
    environment: Option<usize>,
    /// Every light's power, in index order (lights at infinity measured over the scene).
    powers: Vec<f64>,
    /// Per light, the emitter it belongs to (the lights of one emissive mesh share one; see
    /// [`LightSelection::Uniform`]).
    emitters: Vec<u32>,
    mode: LightSelection,
    selection: Option<Distribution1D>,
    continuous: Option<Distribution1D>,
}

impl LightSet {
    /// Area lights only, numbered in order. Lights of zero power are kept (so ids stay valid) but
    /// never picked.
    pub fn from_area(lights: Vec<AreaLight>) -> Self {
        Self::new(lights.into_iter().map(Light::Area).collect(), 0.0)
    }

    /// The scene's lights, numbered in the order given (primitives refer to area lights by
    /// that number); lights at infinity are weighed by what crosses a scene bounded by a sphere
    /// of radius `scene_radius`. A scene has at most one environment (the scene builder keeps
    /// the last one set); were two given, the first would be the one seen by escaping paths.
    /// Selection is by power until [`LightSet::set_selection`] says otherwise.
    /// Every light is its own emitter (see [`LightSet::with_emitters`]).
    pub fn new(lights: Vec<Light>, scene_radius: f32) -> Self {
        let emitters = (0..lights.len() as u32).collect();
        Self::with_emitters(lights, emitters, scene_radius)
    }

    /// [`LightSet::new`] with each light's emitter: `emitters[i]` names the emitter light `i` is
    /// part of (the triangles of one emissive mesh share one), which uniform selection picks
    /// as a whole.
    ///
    /// # Panics
    /// If `emitters` and `lights` differ in length (a scene builder's bug).
    pub fn with_emitters(lights: Vec<Light>, emitters: Vec<u32>, scene_radius: f32) -> Self {
        assert_eq!(lights.len(), emitters.len(), "one emitter id per light");
        let radius = scene_radius.max(1e-3);
        let powers: Vec<f64> = lights.iter().map(|l| l.power(radius)).collect();
        let environment = lights.iter().position(|l| matches!(l, Light::Environment(_)));
        let mut set = Self { lights, environment, powers, emitters, ..Default::default() };
        set.set_selection(LightSelection::Power);
        set
    }

    /// Uniform selection's weights: each emitter with power sums to 1, shared among its lights
    /// by area (a single light, or one that is not an area light, takes all of it).
    fn uniform_weights(&self) -> Vec<f32> {
        let lit = |i: usize| self.powers[i] > 0.0;
        let share = |i: usize| match &self.lights[i] {
            Light::Area(a) => f64::from(a.area()),
            Light::Point(_) | Light::Spot(_) | Light::Directional(_) | Light::Environment(_) => 1.0,
        };
        let groups = self.emitters.iter().copied().max().map_or(0, |m| m as usize + 1);
        let mut total = vec![0.0f64; groups];
        for i in (0..self.lights.len()).filter(|&i| lit(i)) {
            total[self.emitters[i] as usize] += share(i);
        }
        (0..self.lights.len())
            .map(|i| {
                let t = total[self.emitters[i] as usize];
                if !lit(i) || t <= 0.0 {
                    0.0
                } else {
                    // An emitter's lights of zero area (degenerate) would otherwise never be
                    // picked; they are kept selectable at the smallest weight, as power does.
                    ((share(i) / t) as f32).max(f32::MIN_POSITIVE)
                }
            })
            .collect()
    }

    /// Rebuilds the selection distributions for `mode`. Both modes give every light with power a
    /// nonzero probability, so both are unbiased; they differ only in noise.
    pub fn set_selection(&mut self, mode: LightSelection) {
        // Powers are f64 (bright lights overflow f32); the distribution takes them relative to the
        // brightest, a light with any power keeping a nonzero chance.
        let brightest = self.powers.iter().copied().filter(|p| p.is_finite()).fold(0.0, f64::max);
        let all: Vec<f32> = match mode {
            LightSelection::Power => self
                .powers
                .iter()
                .map(|&p| if p > 0.0 && p.is_finite() { ((p / brightest) as f32).max(f32::MIN_POSITIVE) } else { 0.0 })
                .collect(),
            LightSelection::Uniform => self.uniform_weights(),
        };
        self.selection = Distribution1D::new(&all);
        self.continuous = if self.has_delta() {
            // Same indices, with the delta lights' weight zeroed.
            let no_delta: Vec<f32> =
                all.iter().zip(&self.lights).map(|(&w, l)| if l.is_delta() { 0.0 } else { w }).collect();
            Distribution1D::new(&no_delta)
        } else {
            self.selection.clone()
        };
        self.mode = mode;
    }

    /// How lights are picked.
    pub fn selection(&self) -> LightSelection {
        self.mode
    }

    /// Probability that next-event estimation picks light `index`; these sum to 1 over
    /// `0..self.count()` when any light has power.
    pub fn index_pmf(&self, index: usize) -> f32 {
        self.selection.as_ref().map_or(0.0, |d| d.pmf(index))
    }

    /// Number of lights of every kind (the environment counts as one).
    pub fn count(&self) -> usize {
        self.lights.len()
    }

    /// True when nothing can be sampled (no lights, or none with power).
    pub fn is_empty(&self) -> bool {
        self.selection.is_none()
    }

    /// True when some light other than a delta light has power (the `light` and `mixture`
    /// strategies can sample it).
    pub fn has_continuous(&self) -> bool {
        self.continuous.is_some()
    }

    /// The area light with this id; `None` for other kinds.
    pub fn get(&self, id: u32) -> Option<&AreaLight> {
        match self.lights.get(id as usize)? {
            Light::Area(l) => Some(l),
            Light::Point(_) | Light::Spot(_) | Light::Directional(_) | Light::Environment(_) => None,
        }
    }

    /// Every light, in selection order.
    pub fn lights(&self) -> &[Light] {
        &self.lights
    }

    /// The area lights, in id order.
    pub fn area_lights(&self) -> impl Iterator<Item = &AreaLight> {
        self.lights.iter().filter_map(|l| match l {
            Light::Area(a) => Some(a),
            Light::Point(_) | Light::Spot(_) | Light::Directional(_) | Light::Environment(_) => None,
        })
    }

    /// True when the scene has delta lights (point, spot, directional), which only next-event
    /// estimation sees.
    pub fn has_delta(&self) -> bool {
        self.lights.iter().any(Light::is_delta)
    }

    pub fn environment(&self) -> Option<&EnvironmentLight> {
        match &self.lights[self.environment?] {
            Light::Environment(env) => Some(env),
            Light::Area(_) | Light::Point(_) | Light::Spot(_) | Light::Directional(_) => None,
        }
    }

    /// Probability of picking area light `id` for next-event estimation.
    pub fn selection_pmf(&self, id: u32) -> f32 {
        self.selection.as_ref().map_or(0.0, |d| d.pmf(id as usize))
    }

    /// Picks a light index for next-event estimation for each lane of `active` (as
    /// [`LightSet::sample`] does for one point), with its probability; `None` when no light
    /// has power.
    #[inline(always)]
    pub fn pick_lanes<const N: usize>(&self, u_select: &F32s<N>, active: Ms<N>) -> Option<([u32; N], F32s<N>)> {
        self.selection.as_ref().map(|d| d.sample_lanes(u_select, active))
    }

    /// Picks a light (any kind) and a point on it: next-event estimation.
    #[inline(always)]
    pub fn sample(&self, ref_p: Vec3, u_select: f32, u: Vec2) -> Option<LightSample> {
        let (id, pmf) = self.selection.as_ref()?.sample(u_select);
        self.sample_picked(id, pmf, ref_p, u)
    }

    /// Picks a light other than a delta light and a direction towards it: the `light` and
    /// `mixture` strategies, whose density is [`LightSet::pdf_direction`].
    #[inline(always)]
    pub fn sample_continuous(&self, ref_p: Vec3, u_select: f32, u: Vec2) -> Option<LightSample> {
        let (id, pmf) = self.continuous.as_ref()?.sample(u_select);
        self.sample_picked(id, pmf, ref_p, u)
    }

    #[inline(always)]
    fn sample_picked(&self, id: usize, pmf: f32, ref_p: Vec3, u: Vec2) -> Option<LightSample> {
        let s = self.lights.get(id)?.sample(ref_p, u)?;
        Some(LightSample { pdf: s.pdf * pmf, ..s })
    }

    /// Density of sampling hit point `p` on light `id` from `ref_p` (selection included).
    #[inline(always)]
    pub fn pdf_hit(&self, id: u32, ref_p: Vec3, p: Vec3, n: Vec3) -> f32 {
        let pmf = self.selection_pmf(id);
        if pmf <= 0.0 {
            return 0.0;
        }
        self.get(id).map_or(0.0, |light| pmf * light.pdf_hit(ref_p, p, n))
    }

    /// Density with which next-event estimation picks the environment along `dir` (selection
    /// included), for weighting a path that escaped along `dir`: `environment_pmf()` times the
    /// environment's own density.
    #[inline(always)]
    pub fn pdf_environment(&self, dir: Vec3) -> f32 {
        match self.environment() {
            Some(env) => self.environment_pmf() * env.pdf(dir),
            None => 0.0,
        }
    }

    /// Probability that next-event estimation picks the environment (0 without one).
    #[inline(always)]
    pub fn environment_pmf(&self) -> f32 {
        match (self.environment, &self.selection) {
            (Some(index), Some(sel)) => sel.pmf(index),
            _ => 0.0,
        }
    }

    /// Density of direction `dir` under [`LightSet::sample_continuous`] from `ref_p`: the sum over
    /// all lights but point and spot lights (O(number of lights): used only by the mixture and light-only
    /// strategies).
    pub fn pdf_direction(&self, ref_p: Vec3, dir: Vec3) -> f32 {
        let Some(sel) = &self.continuous else {
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
