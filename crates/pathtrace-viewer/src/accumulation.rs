//! The accumulation behind the window: which render is running, and when it must restart.
//!
//! Everything that changes the estimate (camera, strategy, sampler, maximum depth) is a
//! [`RenderKey`]; a new key cancels the running [`RenderSession`] and starts a fresh one at once.
//! Display-only settings (exposure, tone map, which view is shown, picture zoom) are not part of
//! the key, so they never throw samples away. Pausing cancels the session but keeps its film;
//! resuming starts a continuation with another seed, whose independent samples are merged in.

use pathtrace::film::{FeatureBuffers, Film, Image};
use pathtrace::integrator::Strategy;
use pathtrace::render::RenderError;
use pathtrace::sampling::SamplerKind;
use pathtrace::{CameraDesc, Progress, RenderSession, RenderSettings, Scene};
use std::sync::Arc;

/// What the estimate depends on besides the scene: a change restarts accumulation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderKey {
    pub camera: CameraDesc,
    pub strategy: Strategy,
    pub sampler: SamplerKind,
    /// Maximum path segments; -1 is unlimited.
    pub max_depth: i32,
}

impl RenderKey {
    /// The key of a scene's camera with the given settings.
    pub fn new(camera: CameraDesc, settings: &RenderSettings) -> Self {
        Self { camera, strategy: settings.path.strategy, sampler: settings.sampler, max_depth: settings.path.max_depth }
    }

    /// `base` with this key's strategy, sampler and depth.
    fn apply_to(&self, base: &RenderSettings) -> RenderSettings {
        let mut s = base.clone();
        s.path.strategy = self.strategy;
        s.sampler = self.sampler;
        s.path.max_depth = self.max_depth;
        s
    }
}

/// The running render of one [`RenderKey`], with what earlier (paused) segments gathered.
pub struct Accumulation {
    scene: Arc<Scene>,
    base: RenderSettings,
    key: RenderKey,
    session: Option<RenderSession>,
    /// Films of finished segments (before a pause) of the current key.
    kept: Option<Film>,
    /// Feature buffers of the kept segments (averaged over the same samples as `kept`).
    kept_features: Option<FeatureBuffers>,
    /// Segments started for the current key; each continuation uses seed + segment.
    segment: u64,
    /// Bumped on every restart, so the display knows its texture is stale.
    generation: u64,
    paused: bool,
}

impl Accumulation {
    /// Starts rendering `scene` through `key` with `base` settings (size, spp, seed, threads).
    pub fn start(scene: Arc<Scene>, base: RenderSettings, key: RenderKey) -> Result<Self, RenderError> {
        let mut acc = Self {
            scene,
            base,
            key,
            session: None,
            kept: None,
            kept_features: None,
            segment: 0,
            generation: 0,
            paused: false,
        };
        acc.launch()?;
        Ok(acc)
    }

    pub fn key(&self) -> &RenderKey {
        &self.key
    }

    pub fn settings(&self) -> RenderSettings {
        self.key.apply_to(&self.base)
    }

    pub fn generation(&self) -> u64 {
        self.generation
    }

    pub fn is_paused(&self) -> bool {
        self.paused
    }

    /// Switches to `key`; if it differs from the current one, the running render is cancelled
    /// and a new one starts immediately (also when paused: a new view is wanted now).
    /// Returns whether accumulation restarted.
    pub fn set_key(&mut self, key: RenderKey) -> Result<bool, RenderError> {
        if key == self.key {
            return Ok(false);
        }
        let previous = self.key;
        self.key = key;
        self.stop();
        self.kept = None;
        self.kept_features = None;
        self.segment = 0;
        self.paused = false;
        self.generation += 1;
        if let Err(e) = self.launch() {
            // Keep a usable state: go back to the last key that rendered.
            self.key = previous;
            self.launch()?;
            return Err(e);
        }
        Ok(true)
    }

    /// Pauses (keeping every sample so far) or resumes.
    pub fn toggle_pause(&mut self) -> Result<(), RenderError> {
        if self.paused {
            self.paused = false;
            self.segment += 1;
            self.launch()
        } else {
            self.paused = true;
            self.stop();
            Ok(())
        }
    }

    /// Samples per pixel the current key still needs (None: open-ended or done).
    fn remaining_spp(&self) -> Option<u32> {
        let done = self.kept.as_ref().map_or(0, |f| f.spp_range().0);
        match self.base.spp {
            0 => None,
            target => Some(target.saturating_sub(done)),
        }
    }

    fn launch(&mut self) -> Result<(), RenderError> {
        let mut settings = self.settings();
        settings.seed = settings.seed.wrapping_add(self.segment);
        if let Some(remaining) = self.remaining_spp() {
            if remaining == 0 {
                return Ok(());
            }
            settings.spp = remaining;
        }
        self.session = Some(RenderSession::start_with_camera(Arc::clone(&self.scene), &self.key.camera, settings)?);
        Ok(())
    }

    /// Cancels the running segment and folds its film into `kept`.
    fn stop(&mut self) {
        if let Some(session) = self.session.take() {
            session.cancel();
            let outcome = session.wait();
            self.kept = Some(match self.kept.take() {
                Some(mut kept) => {
                    kept.merge(&outcome.film);
                    kept
                }
                None => outcome.film,
            });
            self.kept_features = match (self.kept_features.take(), outcome.features) {
                (Some(mut kept), Some(f)) => {
                    kept.merge(&f);
                    Some(kept)
                }
                (kept, f) => kept.or(f),
            };
        }
    }

    /// The feature buffers so far (when the settings record them), kept segments merged with the
    /// running one.
    pub fn features(&self) -> Option<FeatureBuffers> {
        let running = self.session.as_ref().and_then(RenderSession::features);
        match (self.kept_features.clone(), running) {
            (Some(mut kept), Some(f)) => {
                kept.merge(&f);
                Some(kept)
            }
            (kept, f) => kept.or(f),
        }
    }

    /// The film so far: kept segments merged with the running one.
    pub fn film(&self) -> Film {
        match (&self.kept, &self.session) {
            (Some(kept), Some(s)) => {
                let mut f = kept.clone();
                f.merge(&s.film());
                f
            }
            (Some(kept), None) => kept.clone(),
            (None, Some(s)) => s.film(),
            (None, None) => Film::new(self.base.width, self.base.height),
        }
    }

    /// The current image (cheaper than [`Accumulation::film`] when nothing was kept).
    pub fn image(&self) -> Image {
        match (&self.kept, &self.session) {
            (None, Some(s)) => s.snapshot(),
            _ => self.film().image(),
        }
    }

    /// Progress of the current key: spp and sample counts include kept segments; rates and
    /// elapsed time are the running segment's.
    pub fn progress(&self) -> Progress {
        let kept_spp = self.kept.as_ref().map_or(0, |f| f.spp_range().0);
        let kept_samples = self.kept.as_ref().map_or(0, |f| f.total_samples());
        let mut p = self.session.as_ref().map(RenderSession::progress).unwrap_or_default();
        p.spp_done += kept_spp;
        p.samples += kept_samples;
        p.spp_target = self.base.spp;
        if self.session.is_none() {
            p.finished = !self.paused;
        }
        p
    }

    /// True when the target sample count is reached (never for open-ended renders).
    pub fn is_done(&self) -> bool {
        !self.paused && self.progress().finished && self.remaining_after_session() == Some(0)
    }

    fn remaining_after_session(&self) -> Option<u32> {
        (self.base.spp > 0).then(|| self.base.spp.saturating_sub(self.progress().spp_done))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use pathtrace::light::Emission;
    use pathtrace::material::{Lambertian, Material};
    use pathtrace::math::{Rgb, Transform, Vec3};
    use pathtrace::shape::{Shape, Sphere};
    use pathtrace::SceneBuilder;
    use std::time::{Duration, Instant};

    /// A furnace: inside a sphere that emits 1 and reflects half, every pixel converges to 2.
    fn scene() -> Arc<Scene> {
        let mut b = SceneBuilder::new();
        let wall = b.material_with_emission(
            Material::Lambertian(Lambertian { albedo: Rgb::splat(0.5) }),
            Emission { radiance: Rgb::splat(1.0), two_sided: true },
        );
        b.shape(Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0).unwrap()), wall, &Transform::IDENTITY).unwrap();
        b.camera(CameraDesc { look_at: Vec3::X, ..Default::default() });
        Arc::new(b.build().unwrap())
    }

    fn settings(spp: u32) -> RenderSettings {
        RenderSettings { width: 16, height: 16, spp, seed: 3, ..Default::default() }
    }

    fn wait_until(acc: &Accumulation, done: impl Fn(&Progress) -> bool) {
        let start = Instant::now();
        while !done(&acc.progress()) {
            assert!(start.elapsed() < Duration::from_secs(20), "timed out: {:?}", acc.progress());
            std::thread::sleep(Duration::from_millis(2));
        }
    }

    #[test]
    fn the_same_key_does_not_restart() {
        let s = settings(8);
        let key = RenderKey::new(scene().camera, &s);
        let mut acc = Accumulation::start(scene(), s, key).unwrap();
        assert!(!acc.set_key(key).unwrap());
        assert_eq!(acc.generation(), 0);
        wait_until(&acc, |p| p.finished);
        assert!(acc.is_done());
        assert_eq!(acc.film().spp_range(), (8, 8));
    }

    #[test]
    fn every_estimate_changing_field_restarts_from_zero() {
        let s = settings(1_000_000);
        let key = RenderKey::new(scene().camera, &s);
        let moved = CameraDesc { look_at: Vec3::Z, ..key.camera };
        let changes = [
            RenderKey { camera: moved, ..key },
            RenderKey { strategy: Strategy::Bsdf, ..key },
            RenderKey { sampler: SamplerKind::Sobol, ..key },
            RenderKey { max_depth: 3, ..key },
        ];
        let mut acc = Accumulation::start(scene(), s, key).unwrap();
        for (i, next) in changes.into_iter().enumerate() {
            wait_until(&acc, |p| p.spp_done >= 4);
            let before_restart = Instant::now();
            assert!(acc.set_key(next).unwrap(), "{next:?}");
            assert_eq!(acc.generation(), i as u64 + 1);
            assert_eq!(*acc.key(), next);
            // Nothing of the old estimate survives: no kept film, and the running session started
            // after the restart. (Counting spp here would race: a 16×16 furnace renders a dozen
            // spp in the few milliseconds a loaded CI machine takes between two statements.)
            assert!(acc.kept.is_none() && acc.kept_features.is_none());
            let progress = acc.progress();
            assert!(progress.elapsed <= before_restart.elapsed(), "{progress:?}");
        }
        assert_eq!(acc.settings().path.max_depth, 3);
    }

    #[test]
    fn a_bad_camera_is_refused_and_the_last_good_view_keeps_rendering() {
        let s = settings(16);
        let key = RenderKey::new(scene().camera, &s);
        let mut acc = Accumulation::start(scene(), s, key).unwrap();
        let bad = RenderKey { camera: CameraDesc { look_at: key.camera.look_from, ..key.camera }, ..key };
        assert!(acc.set_key(bad).is_err());
        assert_eq!(*acc.key(), key);
        wait_until(&acc, |p| p.finished);
        assert_eq!(acc.film().spp_range(), (16, 16));
    }

    #[test]
    fn pause_keeps_samples_and_resume_reaches_the_target() {
        let s = settings(2_000);
        let key = RenderKey::new(scene().camera, &s);
        let mut acc = Accumulation::start(scene(), s, key).unwrap();
        wait_until(&acc, |p| p.spp_done >= 2);
        acc.toggle_pause().unwrap();
        assert!(acc.is_paused() && !acc.is_done());
        let kept = acc.progress().spp_done;
        assert!(kept >= 2);
        std::thread::sleep(Duration::from_millis(20));
        assert_eq!(acc.progress().spp_done, kept, "a paused render must not progress");
        acc.toggle_pause().unwrap();
        wait_until(&acc, |p| p.finished);
        assert!(acc.is_done());
        let film = acc.film();
        // A pause mid-wave leaves some pixels a few samples ahead; none falls short.
        assert_eq!(film.spp_range().0, 2_000);
        // Merged segments are still an unbiased estimate of L = E/(1−a) = 2.
        let est = film.region_estimate(0, 0, 16, 16);
        assert!(est.max_z_score_against([2.0; 3]) < 4.5, "{:?}", est.mean);
    }
}
