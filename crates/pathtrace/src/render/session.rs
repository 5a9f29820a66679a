//! A render running on background threads. The caller polls [`RenderSession::progress`], takes
//! [`RenderSession::snapshot`]s of the current image, may [`RenderSession::cancel`], and
//! finally [`RenderSession::wait`]s for the film. The engine never prints: the CLI's progress
//! bar and a live window are both thin consumers of this.
//!
//! Work proceeds in waves of 1, 2, 4, … samples per pixel (capped), each wave a parallel loop
//! over tiles, so a first image is ready quickly. Each pixel merges its waves in order, so the
//! result is bit-identical whatever the number of threads.

use super::settings::RenderSettings;
use super::tile::{render_tile, tiles, TileResult};
use crate::camera::{Camera, CameraDesc, CameraError};
use crate::film::{Film, Image};
use crate::integrator::PathStats;
use crate::sampling::Sampler;
use crate::scene::Scene;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicU32, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// Why a render cannot start.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error(transparent)]
    Camera(#[from] CameraError),
    #[error("could not start worker threads: {0}")]
    Threads(String),
    #[error("nothing to render: give a sample count or a time limit")]
    NoBudget,
}

/// A snapshot of how far a render is.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Progress {
    /// Samples per pixel completed by every pixel (whole waves).
    pub spp_done: u32,
    /// The target (0 for open-ended renders).
    pub spp_target: u32,
    /// Pixel samples finished, counting partly done waves.
    pub samples: u64,
    pub elapsed: Duration,
    pub samples_per_second: f64,
    pub rays_per_second: f64,
    pub rays: PathStats,
    pub dropped_samples: u64,
    pub finished: bool,
    pub cancelled: bool,
}

/// What a finished (or cancelled) render produced.
#[derive(Clone, Debug)]
pub struct RenderOutcome {
    pub film: Film,
    pub progress: Progress,
}

struct Shared {
    film: Mutex<Film>,
    cancel: AtomicBool,
    finished: AtomicBool,
    spp_done: AtomicU32,
    samples: AtomicU64,
    camera_rays: AtomicU64,
    extension_rays: AtomicU64,
    shadow_rays: AtomicU64,
    dropped: AtomicU64,
    start: Instant,
    end: Mutex<Option<Instant>>,
    spp_target: u32,
}

impl Shared {
    fn lock_film(&self) -> MutexGuard<'_, Film> {
        // A worker panicking mid-merge would poison the lock; the film is still usable.
        self.film.lock().unwrap_or_else(|e| e.into_inner())
    }

    fn record(&self, r: &TileResult) {
        self.lock_film().merge_block(r.tile.x0, r.tile.y0, r.tile.w, &r.pixels);
        let n: u64 = r.pixels.iter().map(|p| p.count as u64).sum::<u64>() + r.dropped;
        self.samples.fetch_add(n, Ordering::Relaxed);
        self.camera_rays.fetch_add(r.stats.camera_rays, Ordering::Relaxed);
        self.extension_rays.fetch_add(r.stats.extension_rays, Ordering::Relaxed);
        self.shadow_rays.fetch_add(r.stats.shadow_rays, Ordering::Relaxed);
        self.dropped.fetch_add(r.dropped, Ordering::Relaxed);
    }
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
        if settings.spp == 0 && settings.time_limit.is_none() {
            return Err(RenderError::NoBudget);
        }
        let camera = Camera::new(camera, settings.width, settings.height)?;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(settings.threads)
            .thread_name(|i| format!("pathtrace-worker-{i}"))
            .build()
            .map_err(|e| RenderError::Threads(e.to_string()))?;
        let shared = Arc::new(Shared {
            film: Mutex::new(Film::new(settings.width, settings.height)),
            cancel: AtomicBool::new(false),
            finished: AtomicBool::new(false),
            spp_done: AtomicU32::new(0),
            samples: AtomicU64::new(0),
            camera_rays: AtomicU64::new(0),
            extension_rays: AtomicU64::new(0),
            shadow_rays: AtomicU64::new(0),
            dropped: AtomicU64::new(0),
            start: Instant::now(),
            end: Mutex::new(None),
            spp_target: settings.spp,
        });
        let worker_shared = Arc::clone(&shared);
        let handle = std::thread::Builder::new()
            .name("pathtrace-session".into())
            .spawn(move || {
                pool.install(|| run_waves(&scene, &camera, &settings, &worker_shared));
                if let Ok(mut end) = worker_shared.end.lock() {
                    *end = Some(Instant::now());
                }
                worker_shared.finished.store(true, Ordering::Release);
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

    /// Asks the workers to stop after the tiles they are on; what is done is kept.
    pub fn cancel(&self) {
        self.shared.cancel.store(true, Ordering::Relaxed);
    }

    pub fn is_finished(&self) -> bool {
        self.shared.finished.load(Ordering::Acquire)
    }

    /// Waits for the render to end (finished, timed out or cancelled) and returns the film.
    pub fn wait(mut self) -> RenderOutcome {
        if let Some(h) = self.handle.take() {
            // A panic in a worker is a bug; the film holds what was merged before it.
            let _ = h.join();
        }
        let progress = self.progress();
        let mut film = self.shared.lock_film().clone();
        film.dropped_samples = progress.dropped_samples;
        RenderOutcome { film, progress }
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

/// Renders synchronously (start, then wait).
pub fn render(scene: Arc<Scene>, settings: RenderSettings) -> Result<RenderOutcome, RenderError> {
    Ok(RenderSession::start(scene, settings)?.wait())
}

fn run_waves(scene: &Scene, camera: &Camera, settings: &RenderSettings, shared: &Shared) {
    let tile_list = tiles(settings.width, settings.height, settings.tile_size);
    let deadline = settings.time_limit.map(|t| shared.start + t);
    let out_of_time = || deadline.is_some_and(|d| Instant::now() >= d);
    let mut first = 0u32;
    for count in settings.waves() {
        if shared.cancel.load(Ordering::Relaxed) || out_of_time() {
            break;
        }
        tile_list.par_iter().for_each_init(
            || Sampler::new(settings.sampler, settings.seed, settings.strata_count()),
            |sampler, &tile| {
                if shared.cancel.load(Ordering::Relaxed) || out_of_time() {
                    return;
                }
                let result = render_tile(scene, camera, &settings.path, sampler, tile, first, count);
                shared.record(&result);
            },
        );
        if shared.cancel.load(Ordering::Relaxed) || out_of_time() {
            break;
        }
        first = first.saturating_add(count);
        shared.spp_done.store(first, Ordering::Relaxed);
    }
}
