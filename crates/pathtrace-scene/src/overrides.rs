//! Render settings from a scene's suggestions and a caller's choices: each setting is the
//! caller's if given (a CLI option, a Python keyword argument), else the scene file's
//! `[render]` value, else the engine's default. One rule for every front end, so
//! `pathtrace render SCENE --spp 16` and `pathtrace.render(scene, spp=16)` render the same thing.

use crate::RenderDefaults;
use pathtrace::film::PixelFilter;
use pathtrace::integrator::Strategy;
use pathtrace::sampling::SamplerKind;
use pathtrace::wide::Kernel;
use pathtrace::RenderSettings;
use std::time::Duration;

/// What a caller asks for; `None` leaves the scene's (or the engine's) choice.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RenderOverrides {
    /// Image size in pixels, width × height.
    pub size: Option<(u32, u32)>,
    pub spp: Option<u32>,
    /// A time limit; with one and no `spp`, the render is open-ended until the limit.
    pub time: Option<Duration>,
    /// Maximum path segments; -1 is unlimited.
    pub max_depth: Option<i32>,
    /// Path segments after which Russian roulette may end a path (at least 1).
    pub rr_depth: Option<u32>,
    pub strategy: Option<Strategy>,
    pub sampler: Option<SamplerKind>,
    pub filter: Option<PixelFilter>,
    pub seed: Option<u64>,
    /// Worker threads; 0 or `None` is one per core.
    pub threads: Option<usize>,
    pub kernel: Kernel,
}

impl RenderDefaults {
    /// The render settings for `o` applied over these scene defaults.
    pub fn settings(&self, o: &RenderOverrides) -> RenderSettings {
        let (width, height) = o.size.unwrap_or((self.width, self.height));
        // A time limit without a sample count renders until the limit, not to the scene's spp.
        let spp = if o.time.is_some() { o.spp.unwrap_or(0) } else { o.spp.unwrap_or(self.spp) };
        let mut s = RenderSettings {
            width,
            height,
            spp,
            time_limit: o.time,
            sampler: o.sampler.or(self.sampler).unwrap_or_default(),
            filter: o.filter.clone().or_else(|| self.filter.clone()).unwrap_or_default(),
            seed: o.seed.or(self.seed).unwrap_or(0),
            threads: o.threads.unwrap_or(0),
            kernel: o.kernel,
            ..RenderSettings::default()
        };
        s.path.strategy = o.strategy.or(self.strategy).unwrap_or_default();
        s.path.max_depth = o.max_depth.unwrap_or(self.max_depth);
        if let Some(rr_depth) = o.rr_depth.or(self.rr_depth) {
            s.path.rr_depth = rr_depth;
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene_defaults() -> RenderDefaults {
        RenderDefaults {
            width: 64,
            height: 32,
            spp: 128,
            max_depth: 5,
            rr_depth: Some(3),
            strategy: Some(Strategy::Bsdf),
            sampler: Some(SamplerKind::Stratified),
            seed: Some(9),
            filter: None,
            light_selection: None,
        }
    }

    #[test]
    fn the_scene_suggests_and_the_caller_overrides() {
        let d = scene_defaults();
        let s = d.settings(&RenderOverrides::default());
        assert_eq!((s.width, s.height, s.spp, s.seed, s.path.max_depth), (64, 32, 128, 9, 5));
        assert_eq!((s.path.strategy, s.sampler, s.path.rr_depth), (Strategy::Bsdf, SamplerKind::Stratified, 3));
        let o = RenderOverrides {
            size: Some((8, 4)),
            spp: Some(3),
            seed: Some(1),
            max_depth: Some(-1),
            rr_depth: Some(7),
            strategy: Some(Strategy::Mis),
            ..Default::default()
        };
        let s = d.settings(&o);
        assert_eq!((s.width, s.height, s.spp, s.seed, s.path.max_depth), (8, 4, 3, 1, -1));
        assert_eq!((s.path.strategy, s.path.rr_depth), (Strategy::Mis, 7));
        // Neither the scene nor the caller: the engine's default.
        let d = RenderDefaults { rr_depth: None, ..scene_defaults() };
        assert_eq!(d.settings(&RenderOverrides::default()).path.rr_depth, RenderSettings::default().path.rr_depth);
    }

    #[test]
    fn a_time_limit_alone_is_open_ended() {
        let o = RenderOverrides { time: Some(Duration::from_secs(2)), ..Default::default() };
        let s = scene_defaults().settings(&o);
        assert_eq!((s.spp, s.time_limit), (0, Some(Duration::from_secs(2))));
    }
}
