//! `render` (blocking) and `start` (a background job). The calling thread sleeps with the GIL
//! released while the engine's worker threads render, waking every poll interval to run Python
//! signal handlers (Ctrl-C) and the progress callback.

use crate::film::{Film, Origin};
use crate::job::RenderJob;
use crate::options;
use crate::progress::Progress;
use crate::scene::Scene;
use pathtrace::render::EndSignal;
use pathtrace::RenderSession;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::time::{Duration, Instant};

/// How often a waiting caller takes the GIL back to run signal handlers and report progress,
/// as the CLI wakes for its progress bar and Ctrl-C.
pub const POLL: Duration = Duration::from_millis(100);

/// Waits without the GIL until the render ends or `until`; true if it has ended. Wakes as soon
/// as the render ends (the engine signals it), as the CLI does.
pub fn wait_for_end(py: Python<'_>, end: &EndSignal, until: Instant) -> bool {
    py.detach(|| end.wait(until.saturating_duration_since(Instant::now())))
}

/// Starts the engine's render session for `scene` with the caller's keyword arguments.
fn start_session(scene: &Scene, options: Option<&Bound<'_, PyDict>>) -> PyResult<(RenderSession, Origin)> {
    let settings = options::settings(scene, options)?;
    let origin = Origin::new(scene.source_key, &settings);
    let bad_range = matches!(
        settings.sample_range,
        Some(r) if r.is_empty() || r.end > settings.spp
    );
    let session = RenderSession::start(scene.scene.clone(), settings).map_err(|e| {
        if bad_range {
            PyValueError::new_err(e.to_string())
        } else {
            PyRuntimeError::new_err(e.to_string())
        }
    })?;
    Ok((session, origin))
}

/// Cancels the session and waits (without the GIL) for its workers to stop.
fn stop(py: Python<'_>, session: RenderSession) {
    session.cancel();
    py.detach(move || drop(session.wait()));
}

/// Renders `scene` and returns the film; see the Python docstring of `pathtrace.render`.
#[pyfunction]
#[pyo3(signature = (scene, *, progress=None, **options))]
pub fn render(
    py: Python<'_>,
    scene: &Scene,
    progress: Option<Bound<'_, PyAny>>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<Film> {
    let (session, origin) = start_session(scene, options)?;
    loop {
        let finished = wait_for_end(py, &session.end_signal(), Instant::now() + POLL);
        // A KeyboardInterrupt from Ctrl-C, or an exception in the callback, cancels the render.
        let reported = py.check_signals().and_then(|()| match (&progress, finished) {
            (Some(callback), false) => callback.call1((Progress::from(session.progress()),)).map(drop),
            _ => Ok(()),
        });
        if let Err(e) = reported {
            stop(py, session);
            return Err(e);
        }
        if finished {
            break;
        }
    }
    let outcome = py.detach(move || session.wait());
    if let Some(callback) = &progress {
        callback.call1((Progress::from(outcome.progress),))?;
    }
    Ok(Film::finished(outcome, origin))
}

/// Starts rendering `scene` in the background; see the Python docstring of `pathtrace.start`.
#[pyfunction]
#[pyo3(signature = (scene, **options))]
pub fn start(scene: &Scene, options: Option<&Bound<'_, PyDict>>) -> PyResult<RenderJob> {
    let (session, origin) = start_session(scene, options)?;
    Ok(RenderJob::new(session, origin))
}

/// The key films of `scene` rendered with these options record (hex): the driver of a
/// distributed render checks a checkpoint film against it before trusting its ranges.
#[pyfunction]
#[pyo3(signature = (scene, **options))]
pub fn render_key(scene: &Scene, options: Option<&Bound<'_, PyDict>>) -> PyResult<String> {
    let settings = options::settings(scene, options)?;
    Ok(format!("{:016x}", pathtrace::film::render_key(scene.source_key, &settings)))
}
