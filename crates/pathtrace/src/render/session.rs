//! A render running on background threads. The caller polls [`RenderSession::progress`], takes
//! [`RenderSession::snapshot`]s of the current image, may [`RenderSession::cancel`], and
//! finally [`RenderSession::wait`]s for the film. The engine never prints: the CLI's progress
//! bar and a live window are both thin consumers of this.
//!
//! Work proceeds in waves of samples per pixel (1, then `max_wave_spp` or more at a time:
//! `RenderSettings::next_wave`), each wave a parallel loop over tiles, so a first image is ready
//! quickly. Each pixel merges its waves in order, so the
//! result is bit-identical whatever the number of threads. With adaptive sampling, waves after
//! the uniform start give each pixel its own number of samples (`adaptive.rs`), decided between
//! waves from the merged film, so that stays bit-identical too.

use super::adaptive::{allocate, AdaptiveSettings};
use super::sample_range::SampleRange;
use super::settings::RenderSettings;
use super::tile::{render_tile, tiles, Tile, TileJob, TileResult, WaveSamples};
use crate::camera::{Camera, CameraDesc, CameraError};
use crate::film::{FeatureBuffers, Film, FilmTooLarge, Image};
use crate::integrator::PathStats;
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::wide::{Kernel, WideScene};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicU32, AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// Why a render cannot start.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error(transparent)]
    Camera(#[from] CameraError),
    #[error("could not start worker threads: {0}")]
    Threads(String),
    #[error("nothing to render: give a sample count, a time limit or a target error")]
    NoBudget,
    #[error(transparent)]
    Film(#[from] FilmTooLarge),
    #[error("sample range {range} is not within the render's 0..{spp} samples per pixel: give a range inside it")]
    SampleRangeOutside { range: SampleRange, spp: u32 },
    #[error("a sample range cannot be combined with adaptive sampling (whose choices depend on every sample so far): render uniformly, or the whole range")]
    SampleRangeAdaptive,
}

impl RenderError {
    /// True when the request itself cannot be rendered (a bad setting for this scene or machine),
    /// false when the system failed (threads could not start).
    pub fn is_bad_request(&self) -> bool {
        !matches!(self, RenderError::Threads(_))
    }
}

/// A snapshot of how far a render is.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Progress {
    /// Samples per pixel completed by every pixel (whole waves); with adaptive sampling, the
    /// average over pixels.
    pub spp_done: u32,
    /// The target (0 for open-ended renders; the range's length when rendering a sample range).
    pub spp_target: u32,
    /// Pixel samples finished, counting partly done waves.
    pub samples: u64,
    pub elapsed: Duration,
    pub samples_per_second: f64,
    pub rays_per_second: f64,
    pub rays: PathStats,
    pub dropped_samples: u64,
    /// The film's estimated relative RMS error after the last whole wave
    /// (`Film::relative_rms_error_estimate`); `None` before every pixel has two samples.
    pub error_estimate: Option<f64>,
    /// The adaptive target error, if any.
    pub target_error: Option<f64>,
    pub finished: bool,
    pub cancelled: bool,
}

/// What a finished (or cancelled) render produced.
#[derive(Clone, Debug)]
pub struct RenderOutcome {
    pub film: Film,
    /// The feature buffers, averaged over the film's samples (when `RenderSettings::features`).
    pub features: Option<FeatureBuffers>,
    pub progress: Progress,
}

/// How often the error estimate shown while rendering is refreshed, at most.
const DISPLAY_ESTIMATE_INTERVAL: Duration = Duration::from_millis(500);

struct Shared {
    film: Mutex<Film>,
    /// Kept apart from the film (and locked after it) so the film stays as it is.
    features: Mutex<Option<FeatureBuffers>>,
    cancel: AtomicBool,
    finished: AtomicBool,
    spp_done: AtomicU32,
    samples: AtomicU64,
    camera_rays: AtomicU64,
    extension_rays: AtomicU64,
    shadow_rays: AtomicU64,
    dropped: AtomicU64,
    /// `f64` bits of the last error estimate; NaN for none.
    error_estimate: AtomicU64,
    /// When the error estimate was last computed (see [`Shared::refresh_error_estimate`]).
    estimated_at: Mutex<Option<Instant>>,
    start: Instant,
    end: Mutex<Option<Instant>>,
    /// Notified (with `end` set) when the render ends, so waiters wake at once rather than
    /// polling.
    ended: Condvar,
    spp_target: u32,
    target_error: Option<f64>,
}

impl Shared {
    fn lock_film(&self) -> MutexGuard<'_, Film> {
        // A worker panicking mid-merge would poison the lock; the film is still usable.
        self.film.lock().unwrap_or_else(|e| e.into_inner())
    }

    fn lock_features(&self) -> MutexGuard<'_, Option<FeatureBuffers>> {
        self.features.lock().unwrap_or_else(|e| e.into_inner())
    }

    fn record(&self, r: &TileResult) {
        let mut film = self.lock_film();
        film.merge_block(r.tile.x0, r.tile.y0, r.tile.w, &r.pixels);
        if let Some(block) = &r.splat {
            film.merge_splat_block(block);
        }
        drop(film);
        if let (Some(buffers), Some(block)) = (self.lock_features().as_mut(), &r.features) {
            buffers.merge_block(r.tile.x0, r.tile.y0, r.tile.w, block);
        }
        let n: u64 = r.pixels.iter().map(|p| p.count as u64).sum::<u64>() + r.dropped;
        self.samples.fetch_add(n, Ordering::Relaxed);
        self.camera_rays.fetch_add(r.stats.camera_rays, Ordering::Relaxed);
        self.extension_rays.fetch_add(r.stats.extension_rays, Ordering::Relaxed);
        self.shadow_rays.fetch_add(r.stats.shadow_rays, Ordering::Relaxed);
        self.dropped.fetch_add(r.dropped, Ordering::Relaxed);
    }

    fn stop_requested(&self, deadline: Option<Instant>) -> bool {
        self.cancel.load(Ordering::Relaxed) || deadline.is_some_and(|d| Instant::now() >= d)
    }

    /// Updates the error estimate from the film (after a whole wave) and returns it.
    fn update_error_estimate(&self) -> Option<f64> {
        let e = self.lock_film().relative_rms_error_estimate();
        self.error_estimate.store(e.unwrap_or(f64::NAN).to_bits(), Ordering::Relaxed);
        *self.estimated_at.lock().unwrap_or_else(|e| e.into_inner()) = Some(Instant::now());
        e
    }

    /// Updates the error estimate, for display only, unless it was computed less than
    /// [`DISPLAY_ESTIMATE_INTERVAL`] ago. The estimate is a pass over every pixel that runs
    /// between waves, while the render threads wait: after each of a fast render's many waves it
    /// took 4% of a teapot render's time. Renders that stop on it (adaptive) update every wave.
    /// Returns whether it did.
    fn refresh_error_estimate(&self) -> bool {
        let last = *self.estimated_at.lock().unwrap_or_else(|e| e.into_inner());
        let due = last.is_none_or(|t| t.elapsed() >= DISPLAY_ESTIMATE_INTERVAL);
        if due {
            self.update_error_estimate();
        }
        due
    }
}

/// What a render computes once before its waves: the camera, and the scene's lane-parallel
/// forms.
struct Prepared {
    camera: Camera,
    lanes: WideScene,
}

/// A render in progress.
pub struct RenderSession {
    shared: Arc<Shared>,
    handle: Option<JoinHandle<()>>,
}

impl RenderSession {
    /// Starts rendering `scene` on background threads.
    pub fn start(scene: Arc<Scene>, settings: RenderSettings) -> Result<Self, RenderError> {
        let camera = scene.camera;
        Self::start_with_camera(scene, &camera, settings)
    }

    /// Starts rendering `scene` seen through `camera` instead of the scene's own camera, so an
    /// interactive front end can move the view without rebuilding (or copying) the BVH.
    pub fn start_with_camera(
        scene: Arc<Scene>,
        camera: &CameraDesc,
        settings: RenderSettings,
    ) -> Result<Self, RenderError> {
        let target_error = settings.adaptive.and_then(|a| a.target_error);
        if settings.spp == 0 && settings.time_limit.is_none() && target_error.is_none() {
            return Err(RenderError::NoBudget);
        }
        if let Some(range) = settings.sample_range {
            if range.is_empty() || range.end > settings.spp {
                return Err(RenderError::SampleRangeOutside { range, spp: settings.spp });
            }
            if settings.adaptive.is_some() {
                return Err(RenderError::SampleRangeAdaptive);
            }
        }
        let camera = Camera::new(camera, settings.width, settings.height)?;
        let prep = Prepared { camera, lanes: WideScene::new(&scene, &settings.path) };
        let film = Film::try_new(settings.width, settings.height, settings.filter.splats())?;
        let features =
            if settings.features { Some(FeatureBuffers::try_new(settings.width, settings.height)?) } else { None };
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(settings.threads)
            .thread_name(|i| format!("pathtrace-worker-{i}"))
            .build()
            .map_err(|e| RenderError::Threads(e.to_string()))?;
        let shared = Arc::new(Shared {
            film: Mutex::new(film),
            features: Mutex::new(features),
            cancel: AtomicBool::new(false),
            finished: AtomicBool::new(false),
            spp_done: AtomicU32::new(0),
            samples: AtomicU64::new(0),
            camera_rays: AtomicU64::new(0),
            extension_rays: AtomicU64::new(0),
            shadow_rays: AtomicU64::new(0),
            dropped: AtomicU64::new(0),
            error_estimate: AtomicU64::new(f64::NAN.to_bits()),
            estimated_at: Mutex::new(None),
            start: Instant::now(),
            end: Mutex::new(None),
            ended: Condvar::new(),
            spp_target: if settings.spp > 0 { settings.samples().len() } else { 0 },
            target_error,
        });
        let worker_shared = Arc::clone(&shared);
        let handle = std::thread::Builder::new()
            .name("pathtrace-session".into())
            .spawn(move || {
                // Ends the render however the waves end: a panic in a worker (a bug) must wake
                // the waiters too, who would otherwise wait for ever.
                let ending = EndOnExit { end: &worker_shared.end, ended: &worker_shared.ended };
                pool.install(|| run_waves(&scene, &prep, &settings, &worker_shared));
                worker_shared.finished.store(true, Ordering::Release);
                drop(ending);
            })
            .map_err(|e| RenderError::Threads(e.to_string()))?;
        Ok(Self { shared, handle: Some(handle) })
    }

    /// How far the render is.
    pub fn progress(&self) -> Progress {
        let s = &self.shared;
        let end = s.end.lock().ok().and_then(|e| *e);
        let elapsed = end.unwrap_or_else(Instant::now) - s.start;
        let samples = s.samples.load(Ordering::Relaxed);
        let rays = PathStats {
            camera_rays: s.camera_rays.load(Ordering::Relaxed),
            extension_rays: s.extension_rays.load(Ordering::Relaxed),
            shadow_rays: s.shadow_rays.load(Ordering::Relaxed),
        };
        let secs = elapsed.as_secs_f64().max(1e-9);
        Progress {
            spp_done: s.spp_done.load(Ordering::Relaxed),
            spp_target: s.spp_target,
            samples,
            elapsed,
            samples_per_second: samples as f64 / secs,
            rays_per_second: rays.total_rays() as f64 / secs,
            rays,
            dropped_samples: s.dropped.load(Ordering::Relaxed),
            error_estimate: Some(f64::from_bits(s.error_estimate.load(Ordering::Relaxed))).filter(|e| !e.is_nan()),
            target_error: s.target_error,
            finished: s.finished.load(Ordering::Acquire),
            cancelled: s.cancel.load(Ordering::Relaxed),
        }
    }

    /// The current image (each pixel's mean so far).
    pub fn snapshot(&self) -> Image {
        self.shared.lock_film().image()
    }

    /// A copy of the accumulation buffer so far.
    pub fn film(&self) -> Film {
        self.shared.lock_film().clone()
    }

    /// A copy of the feature buffers so far (`None` unless the settings asked for them).
    pub fn features(&self) -> Option<FeatureBuffers> {
        self.shared.lock_features().clone()
    }

    /// Asks the workers to stop after the tiles they are on; what is done is kept.
    pub fn cancel(&self) {
        self.shared.cancel.store(true, Ordering::Relaxed);
    }

    pub fn is_finished(&self) -> bool {
        self.shared.finished.load(Ordering::Acquire)
    }

    /// Blocks until the render ends or `timeout` passes; true if it has ended. Returns as soon
    /// as the last tile is merged, so a front end can wake for progress every 100 ms yet
    /// finish without waiting out its interval.
    pub fn wait_finished(&self, timeout: Duration) -> bool {
        self.end_signal().wait(timeout)
    }

    /// A handle that waits for this render's end without borrowing the session (for a front end
    /// that keeps the session behind a lock it must not hold while waiting).
    pub fn end_signal(&self) -> EndSignal {
        EndSignal(Arc::clone(&self.shared))
    }

    /// Waits for the render to end (finished, timed out or cancelled) and returns the film.
    /// A panic in a worker (a bug) is raised again here rather than passed off as a film.
    pub fn wait(mut self) -> RenderOutcome {
        if let Some(h) = self.handle.take() {
            if let Err(panic) = h.join() {
                std::panic::resume_unwind(panic);
            }
        }
        let progress = self.progress();
        let mut film = self.shared.lock_film().clone();
        film.dropped_samples = progress.dropped_samples;
        let features = self.shared.lock_features().clone();
        RenderOutcome { film, features, progress }
    }
}

impl Drop for RenderSession {
    fn drop(&mut self) {
        if let Some(h) = self.handle.take() {
            self.cancel();
            let _ = h.join();
        }
    }
}

/// Marks the render ended and wakes its waiters when dropped, on return or unwinding.
struct EndOnExit<'a> {
    end: &'a Mutex<Option<Instant>>,
    ended: &'a Condvar,
}

impl Drop for EndOnExit<'_> {
    fn drop(&mut self) {
        let mut end = self.end.lock().unwrap_or_else(|e| e.into_inner());
        *end = Some(Instant::now());
        drop(end);
        self.ended.notify_all();
    }
}

/// Waits for the end of a [`RenderSession`]; see [`RenderSession::end_signal`].
#[derive(Clone)]
pub struct EndSignal(Arc<Shared>);

impl EndSignal {
    /// Blocks until the render ends or `timeout` passes; true if it has ended.
    pub fn wait(&self, timeout: Duration) -> bool {
        let end = self.0.end.lock().unwrap_or_else(|e| e.into_inner());
        let (end, _) =
            self.0.ended.wait_timeout_while(end, timeout, |end| end.is_none()).unwrap_or_else(|e| e.into_inner());
        end.is_some()
    }
}

/// Renders synchronously (start, then wait).
pub fn render(scene: Arc<Scene>, settings: RenderSettings) -> Result<RenderOutcome, RenderError> {
    Ok(RenderSession::start(scene, settings)?.wait())
}

fn run_waves(scene: &Scene, prep: &Prepared, settings: &RenderSettings, shared: &Shared) {
    match settings.adaptive {
        None => run_uniform(scene, prep, settings, shared),
        Some(adaptive) => run_adaptive(scene, prep, settings, &adaptive, shared),
    }
}

/// One wave: a parallel loop over tiles; tiles not started before a stop are skipped.
fn run_wave(
    scene: &Scene,
    prep: &Prepared,
    settings: &RenderSettings,
    shared: &Shared,
    tile_list: &[Tile],
    samples: WaveSamples,
) {
    let deadline = settings.time_limit.map(|t| shared.start + t);
    let job = TileJob {
        scene,
        camera: &prep.camera,
        lanes: &prep.lanes,
        one_lane: settings.kernel == Kernel::Scalar,
        avx2_kernel: settings.kernel == Kernel::Wide8,
        filter: &settings.filter,
        features: settings.features,
    };
    tile_list.par_iter().for_each_init(
        || Sampler::new(settings.sampler, settings.seed, settings.strata_count()),
        |sampler, &tile| {
            if shared.stop_requested(deadline) {
                return;
            }
            let result = render_tile(&job, sampler, tile, samples);
            shared.record(&result);
        },
    );
}

/// Every pixel gets the same samples, in the waves [`RenderSettings::next_wave`] sizes from
/// how long the last one took per sample per pixel (the film does not depend on the sizes).
fn run_uniform(scene: &Scene, prep: &Prepared, settings: &RenderSettings, shared: &Shared) {
    let tile_list = tiles(settings.width, settings.height, settings.tile_size);
    let deadline = settings.time_limit.map(|t| shared.start + t);
    let start = settings.samples().start;
    let mut first = start;
    let mut estimated = false;
    let mut seconds_per_spp = None;
    while let Some(count) = settings.next_wave(first - start, seconds_per_spp) {
        estimated = false;
        if shared.stop_requested(deadline) {
            break;
        }
        let began = Instant::now();
        run_wave(scene, prep, settings, shared, &tile_list, WaveSamples::Uniform { first, count });
        seconds_per_spp = Some(began.elapsed().as_secs_f64() / f64::from(count));
        if shared.stop_requested(deadline) {
            break;
        }
        first = first.saturating_add(count);
        shared.spp_done.store(first - start, Ordering::Relaxed);
        estimated = shared.refresh_error_estimate();
    }
    // The render's outcome reports the estimate of the film it returns.
    if !estimated {
        shared.update_error_estimate();
    }
}

/// `min_spp` uniform samples per pixel in doubling waves, then waves whose budget (the same
/// doubling, in samples per pixel on average) is shared out by [`allocate`]. Stops when the
/// budget (`spp` on average) is spent, the target error is reached, time is up or on cancel.
fn run_adaptive(
    scene: &Scene,
    prep: &Prepared,
    settings: &RenderSettings,
    adaptive: &AdaptiveSettings,
    shared: &Shared,
) {
    let tile_list = tiles(settings.width, settings.height, settings.tile_size);
    let deadline = settings.time_limit.map(|t| shared.start + t);
    let pixels = settings.width as u64 * settings.height as u64;
    let budget = (settings.spp > 0).then(|| settings.spp as u64 * pixels);
    let min_spp = match budget {
        Some(_) => adaptive.min_spp.clamp(1, settings.spp),
        None => adaptive.min_spp.max(1),
    };
    let cap = settings.max_wave_spp.max(1);
    let mut given = vec![0u32; pixels as usize];
    let (mut uniform_done, mut spent, mut wave_spp) = (0u32, 0u64, 1u32);
    loop {
        let remaining = budget.map_or(u64::MAX, |b| b - spent);
        if remaining == 0 || shared.stop_requested(deadline) {
            break;
        }
        let per_pixel = wave_spp.min(cap);
        wave_spp = wave_spp.saturating_mul(2);
        if uniform_done < min_spp {
            let count = per_pixel.min(min_spp - uniform_done);
            run_wave(scene, prep, settings, shared, &tile_list, WaveSamples::Uniform { first: uniform_done, count });
            uniform_done += count;
            given.iter_mut().for_each(|n| *n += count);
            spent += count as u64 * pixels;
        } else {
            let wave_budget = (per_pixel as u64 * pixels).min(remaining);
            let count = allocate(&shared.lock_film(), &given, wave_budget, adaptive.floor);
            let samples = WaveSamples::PerPixel { width: settings.width, first: &given, count: &count };
            run_wave(scene, prep, settings, shared, &tile_list, samples);
            given.iter_mut().zip(&count).for_each(|(n, c)| *n = n.saturating_add(*c));
            spent += wave_budget;
        }
        if shared.stop_requested(deadline) {
            break;
        }
        shared.spp_done.store((spent / pixels.max(1)) as u32, Ordering::Relaxed);
        let error = shared.update_error_estimate();
        if let (Some(target), Some(error)) = (adaptive.target_error, error) {
            if error <= target && uniform_done >= min_spp {
                break;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A worker that panics still ends the render: its waiters wake (they used to wait for ever).
    #[test]
    fn a_panicking_worker_wakes_the_waiters() {
        let state = Arc::new((Mutex::new(None), Condvar::new()));
        let worker = Arc::clone(&state);
        let handle = std::thread::spawn(move || {
            let _ending = EndOnExit { end: &worker.0, ended: &worker.1 };
            panic!("a bug in a worker");
        });
        let end = state.0.lock().unwrap_or_else(|e| e.into_inner());
        let (end, timeout) = state
            .1
            .wait_timeout_while(end, Duration::from_secs(60), |end| end.is_none())
            .unwrap_or_else(|e| e.into_inner());
        assert!(end.is_some() && !timeout.timed_out());
        assert!(handle.join().is_err(), "the panic reaches the joiner");
    }
}
