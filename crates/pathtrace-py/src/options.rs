//! The keyword arguments of `render` and `start` (spp, seed, width, height, max_depth, rr_depth,
//! strategy, sampler, threads, aov), turned into render settings by the same rule as the CLI's options
//! (`RenderDefaults::settings` in the scene crate). Both functions take them as `**options`
//! and parse them here, so the option list lives in one place (and in the type stubs).

use crate::scene::Scene;
use pathtrace::{RenderSettings, SampleRange};
use pathtrace_scene::RenderOverrides;
use pyo3::conversion::FromPyObjectOwned;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::str::FromStr;

/// Parses a named choice as the CLI does, as a `ValueError` naming the argument.
fn parse<T: FromStr>(what: &str, value: Option<String>) -> PyResult<Option<T>>
where
    T::Err: std::fmt::Display,
{
    value.map(|v| T::from_str(&v).map_err(|e| PyValueError::new_err(format!("{what}: {e}")))).transpose()
}

/// A keyword argument's value, as a `TypeError` naming the argument if it has the wrong type.
fn value<'py, T: FromPyObjectOwned<'py>>(key: &str, v: &Bound<'py, PyAny>) -> PyResult<T> {
    v.extract::<T>().map_err(|e| {
        let e: PyErr = e.into();
        PyTypeError::new_err(format!("{key}: {}", e.value(v.py())))
    })
}

/// The engine's settings for rendering `scene` with the caller's keyword arguments; unknown
/// keywords are a `TypeError`, as for any Python function.
pub fn settings(scene: &Scene, options: Option<&Bound<'_, PyDict>>) -> PyResult<RenderSettings> {
    // Python's defaults: seed 0 (the CLI's default seed; None takes the scene's) and one thread
    // per core; every other option left unset takes the scene's value.
    let mut o = RenderOverrides { seed: Some(0), threads: Some(0), ..RenderOverrides::default() };
    let (mut width, mut height): (Option<u32>, Option<u32>) = (None, None);
    let mut features = false;
    let mut sample_range: Option<(u32, u32)> = None;
    for (key, v) in options.into_iter().flat_map(|d| d.iter()) {
        let key: String = key.extract()?;
        match key.as_str() {
            "spp" => o.spp = value(&key, &v)?,
            "seed" => o.seed = value(&key, &v)?,
            "width" => width = value(&key, &v)?,
            "height" => height = value(&key, &v)?,
            "max_depth" => o.max_depth = value(&key, &v)?,
            "rr_depth" => o.rr_depth = value(&key, &v)?,
            "strategy" => o.strategy = parse("strategy", value(&key, &v)?)?,
            "sampler" => o.sampler = parse("sampler", value(&key, &v)?)?,
            "threads" => o.threads = Some(value(&key, &v)?),
            "aov" => features = value(&key, &v)?,
            "sample_range" => sample_range = value(&key, &v)?,
            _ => return Err(PyTypeError::new_err(format!("unexpected keyword argument '{key}'"))),
        }
    }
    if o.spp == Some(0) {
        return Err(PyValueError::new_err("spp must be at least 1"));
    }
    if o.rr_depth == Some(0) {
        return Err(PyValueError::new_err("rr_depth must be at least 1"));
    }
    if width == Some(0) || height == Some(0) {
        return Err(PyValueError::new_err("width and height must be at least 1"));
    }
    let d = &scene.defaults;
    if width.is_some() || height.is_some() {
        o.size = Some((width.unwrap_or(d.width), height.unwrap_or(d.height)));
    }
    let mut settings = RenderSettings { features, ..d.settings(&o) };
    if let Some((start, end)) = sample_range {
        if end <= start {
            return Err(PyValueError::new_err(format!(
                "sample_range ({start}, {end}): end must be greater than start"
            )));
        }
        settings.sample_range = Some(SampleRange::new(start, end));
    }
    Ok(settings)
}
