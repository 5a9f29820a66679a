//! `pathtrace.RenderJob`: a render running in the background, as returned by `start`.

use crate::film::{image_array, Film, Origin};
use crate::progress::Progress;
use crate::render::{wait_for_end, POLL};
use numpy::PyArray3;
use pathtrace::render::EndSignal;
use pathtrace::{RenderOutcome, RenderSession};
use pyo3::prelude::*;
use std::sync::{Mutex, MutexGuard};
use std::time::{Duration, Instant};

/// A job holds its session while it runs, and the session's outcome once waited for.
struct State {
    session: Option<RenderSession>,
    outcome: Option<RenderOutcome>,
}

/// A render in progress. The lock is only ever held briefly and never while waiting without
/// the GIL, so another Python thread asking for progress cannot deadlock a waiting one.
#[pyclass(frozen, module = "pathtrace")]
pub struct RenderJob {
    state: Mutex<State>,
    /// Waits for the render's end outside the lock.
    end: EndSignal,
    origin: Origin,
}

impl RenderJob {
    pub fn new(session: RenderSession, origin: Origin) -> Self {
        let end = session.end_signal();
        Self { state: Mutex::new(State { session: Some(session), outcome: None }), end, origin }
    }

    fn lock(&self) -> MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    fn is_finished(&self) -> bool {
        self.lock().session.as_ref().is_none_or(RenderSession::is_finished)
    }

    /// The outcome of a render whose workers have ended (joining them is then immediate).
    fn outcome(&self) -> RenderOutcome {
        let mut state = self.lock();
        if let Some(session) = state.session.take() {
            state.outcome = Some(session.wait());
        }
        state.outcome.clone().expect("a job holds its session or, once waited for, its outcome")
    }

    /// The session's progress, or the final progress once waited for.
    fn current<T>(&self, running: impl Fn(&RenderSession) -> T, done: impl Fn(&RenderOutcome) -> T) -> T {
        let state = self.lock();
        match (&state.session, &state.outcome) {
            (Some(session), _) => running(session),
            (None, Some(outcome)) => done(outcome),
            (None, None) => unreachable!("a job holds its session or, once waited for, its outcome"),
        }
    }
}

#[pymethods]
impl RenderJob {
    /// How far the render is.
    fn progress(&self) -> Progress {
        self.current(|s| s.progress(), |o| o.progress).into()
    }

    /// The current image (each pixel's mean so far), float32 (H, W, 3).
    fn snapshot<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f32>> {
        let image = self.current(RenderSession::snapshot, |o| o.film.image());
        image_array(py, &image)
    }

    /// Asks the render to stop after the tiles it is on; `wait()` then returns what was done.
    fn cancel(&self) {
        if let Some(session) = &self.lock().session {
            session.cancel();
        }
    }

    /// True once the render has ended (finished or cancelled).
    fn done(&self) -> bool {
        self.is_finished()
    }

    /// Waits for the render to end and returns its film, or None if `timeout` seconds pass
    /// first. Ctrl-C raises KeyboardInterrupt here and leaves the job running.
    #[pyo3(signature = (timeout=None))]
    fn wait(&self, py: Python<'_>, timeout: Option<f64>) -> PyResult<Option<Film>> {
        let deadline = match timeout {
            Some(t) if !(t >= 0.0 && t.is_finite()) => {
                return Err(pyo3::exceptions::PyValueError::new_err("timeout must be a finite number of seconds ≥ 0"))
            }
            Some(t) => Some(Instant::now() + Duration::from_secs_f64(t)),
            None => None,
        };
        loop {
            let window = Instant::now() + POLL;
            let until = deadline.map_or(window, |d| d.min(window));
            if wait_for_end(py, &self.end, until) {
                return Ok(Some(Film::finished(self.outcome(), self.origin)));
            }
            py.check_signals()?;
            if deadline.is_some_and(|d| Instant::now() >= d) {
                return Ok(None);
            }
        }
    }

    fn __enter__(slf: Py<Self>) -> Py<Self> {
        slf
    }

    /// Leaving the `with` block cancels the render if it is still running and waits for it.
    fn __exit__(
        &self,
        py: Python<'_>,
        _exc_type: Option<Bound<'_, PyAny>>,
        _exc: Option<Bound<'_, PyAny>>,
        _traceback: Option<Bound<'_, PyAny>>,
    ) -> bool {
        self.cancel();
        // Cancelled workers stop after the tiles they are on: a short wait.
        while !wait_for_end(py, &self.end, Instant::now() + POLL) {}
        self.outcome();
        false
    }

    fn __repr__(&self) -> String {
        let p = self.progress();
        let state = if p.cancelled {
            "cancelled"
        } else if p.finished {
            "done"
        } else {
            "running"
        };
        format!("<pathtrace.RenderJob {state}, {}/{} spp>", p.spp_done, p.spp_target)
    }
}
