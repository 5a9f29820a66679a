//! `pathtrace.Progress`: how far a render is, as the engine's `RenderSession::progress` says.

use pyo3::prelude::*;

/// How far a render is: whole samples per pixel done and the target, speed, and the estimated
/// relative RMS error of the image so far.
#[pyclass(frozen, get_all, module = "pathtrace")]
#[derive(Clone)]
pub struct Progress {
    /// Samples per pixel every pixel has (whole waves).
    pub spp_done: u32,
    /// Samples per pixel to reach.
    pub spp_target: u32,
    /// Pixel samples finished, counting partly done waves.
    pub samples: u64,
    /// Seconds since the render started.
    pub elapsed: f64,
    pub samples_per_second: f64,
    pub rays_per_second: f64,
    /// NaN/Inf samples dropped so far.
    pub dropped_samples: u64,
    /// Estimated relative RMS error of the image (None before every pixel has two samples).
    pub error_estimate: Option<f64>,
    pub finished: bool,
    pub cancelled: bool,
}

impl From<pathtrace::Progress> for Progress {
    fn from(p: pathtrace::Progress) -> Self {
        Self {
            spp_done: p.spp_done,
            spp_target: p.spp_target,
            samples: p.samples,
            elapsed: p.elapsed.as_secs_f64(),
            samples_per_second: p.samples_per_second,
            rays_per_second: p.rays_per_second,
            dropped_samples: p.dropped_samples,
            error_estimate: p.error_estimate,
            finished: p.finished,
            cancelled: p.cancelled,
        }
    }
}

#[pymethods]
impl Progress {
    /// Fraction of the target done, in [0, 1].
    #[getter]
    fn fraction(&self) -> f64 {
        if self.spp_target == 0 {
            return 0.0;
        }
        (self.spp_done as f64 / self.spp_target as f64).min(1.0)
    }

    fn __repr__(&self) -> String {
        let error = self.error_estimate.map_or("n/a".to_string(), |e| format!("{:.2}%", 100.0 * e));
        format!(
            "<pathtrace.Progress {}/{} spp, {:.3} M samples/s, error {error}, {:.2} s{}>",
            self.spp_done,
            self.spp_target,
            self.samples_per_second / 1e6,
            self.elapsed,
            if self.cancelled {
                ", cancelled"
            } else if self.finished {
                ", finished"
            } else {
                ""
            }
        )
    }
}
