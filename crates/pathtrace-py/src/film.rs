//! `pathtrace.Film`: a finished (or cancelled) render's accumulation buffer, with numpy views of
//! its image, per-pixel variance and sample counts, its feature buffers (with `aov=True`) and
//! their denoised image, and writing to PNG/EXR/PFM as the CLI does.

use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray2, PyArray3};
use pathtrace::film::{engine_build, render_key, FeatureBuffers, Image, RangedFilm, ToneMap, ToneMapSettings};
use pathtrace::{RenderOutcome, RenderSettings, SampleRange};
use pathtrace_scene::image_io::{write_image, ImageFormat};
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyType};
use std::path::PathBuf;

/// Which samples of which render a session takes, known before it starts.
#[derive(Clone, Copy, Debug)]
pub struct Origin {
    key: u64,
    spp: u32,
    range: SampleRange,
    /// Uniform sampling (adaptive renders choose samples from the film: not a sample range).
    uniform: bool,
}

impl Origin {
    pub fn new(scene_key: u64, settings: &RenderSettings) -> Self {
        Self {
            key: render_key(scene_key, settings),
            spp: settings.spp,
            range: settings.samples(),
            uniform: settings.adaptive.is_none(),
        }
    }
}

/// A render's result: per pixel, the sample count and exact sums of the samples and their
/// squares; with the render it belongs to and its sample ranges when it holds whole ones, and
/// the feature buffers (exact sums too) of a render with `aov=True`.
#[pyclass(frozen, module = "pathtrace")]
pub struct Film {
    inner: RangedFilm,
    /// Whether `inner.ranges` is true: false for a cancelled render (which holds part of a
    /// wave), whose film cannot be merged or saved.
    whole_ranges: bool,
}

impl Film {
    /// The film of a finished (or cancelled) session started with `origin`.
    pub fn finished(outcome: RenderOutcome, origin: Origin) -> Self {
        let p = &outcome.progress;
        let whole = origin.uniform && origin.spp > 0 && !p.cancelled && p.spp_done == origin.range.len();
        let inner = RangedFilm::new(outcome.film, origin.key, engine_build(), origin.spp, origin.range)
            .with_features(outcome.features);
        let mut film = Self { inner, whole_ranges: whole };
        if !whole {
            film.inner.ranges.clear();
        }
        film
    }

    fn mergeable(&self, what: &str) -> PyResult<&RangedFilm> {
        if self.whole_ranges {
            Ok(&self.inner)
        } else {
            Err(PyValueError::new_err(format!(
                "{what}: this film does not hold whole sample ranges (its render was cancelled or adaptive)"
            )))
        }
    }

    fn features(&self) -> PyResult<&FeatureBuffers> {
        self.inner.features.as_ref().ok_or_else(|| {
            PyValueError::new_err("this film has no feature buffers: render with aov=True (every part, for a sum)")
        })
    }

    /// The engine's film.
    pub fn film(&self) -> &pathtrace::film::Film {
        &self.inner.film
    }
}

/// An image as a float32 (H, W, 3) array, row 0 at the top.
pub fn image_array<'py>(py: Python<'py>, image: &Image) -> Bound<'py, PyArray3<f32>> {
    let data: Vec<f32> = image.pixels.iter().flat_map(|p| [p.r, p.g, p.b]).collect();
    let shape = (image.height as usize, image.width as usize, 3);
    // The buffer holds exactly height × width × 3 values by construction.
    Array3::from_shape_vec(shape, data).expect("image buffer matches its size").into_pyarray(py)
}

#[pymethods]
impl Film {
    /// The image: each pixel's mean radiance, linear RGB, float32 (H, W, 3), row 0 at the top.
    fn image<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f32>> {
        image_array(py, &self.inner.film.image())
    }

    /// The estimated variance of each pixel's mean (s²/n per channel), float32 (H, W, 3).
    fn variance<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f32>> {
        image_array(py, &self.inner.film.variance_image())
    }

    /// Mean albedo of the first non-specular surface seen, float32 (H, W, 3) (needs `aov=True`).
    fn albedo<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f32>>> {
        Ok(image_array(py, &self.features()?.albedo()))
    }

    /// Mean world-space shading normal there, components in [-1, 1], float32 (H, W, 3).
    fn normal<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f32>>> {
        Ok(image_array(py, &self.features()?.normal()))
    }

    /// Mean distance from the camera to the first hit (0 where rays escape), float32 (H, W).
    fn depth<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        let depth = self.features()?.depth();
        let values: Vec<f32> = depth.pixels.iter().map(|p| p.r).collect();
        let shape = (depth.height as usize, depth.width as usize);
        Ok(Array2::from_shape_vec(shape, values).expect("one depth per pixel").into_pyarray(py))
    }

    /// The image denoised by Intel Open Image Denoise 2 with the albedo and normal buffers,
    /// float32 (H, W, 3) (needs `aov=True`; the library is found at run time: docs/denoising.md).
    fn denoise<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f32>>> {
        let f = self.features()?;
        let (image, albedo, normal) = (self.inner.film.image(), f.albedo(), f.normal());
        let denoised = py
            .detach(|| pathtrace_denoise::denoise(&image, &albedo, &normal))
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        Ok(image_array(py, &denoised))
    }

    /// Samples accumulated in each pixel, uint32 (H, W).
    fn counts<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<u32>> {
        let counts: Vec<u32> = self.inner.film.pixels().iter().map(|p| p.count).collect();
        let shape = (self.inner.film.height() as usize, self.inner.film.width() as usize);
        Array2::from_shape_vec(shape, counts).expect("one count per pixel").into_pyarray(py)
    }

    /// `np.asarray(film)`: the image, as `image()` (converted if a dtype is asked for).
    #[pyo3(signature = (dtype=None, copy=None))]
    fn __array__<'py>(
        &self,
        py: Python<'py>,
        dtype: Option<Bound<'py, PyAny>>,
        copy: Option<bool>,
    ) -> PyResult<Bound<'py, PyAny>> {
        // Every call builds a fresh array, so any `copy` request is honoured.
        let _ = copy;
        let image = self.image(py).into_any();
        match dtype {
            Some(dtype) => image.call_method1("astype", (dtype,)),
            None => Ok(image),
        }
    }

    /// Samples per pixel: the fewest any pixel holds (every pixel's count for a finished
    /// uniform render; the whole waves done for a cancelled one).
    #[getter]
    fn spp(&self) -> u32 {
        self.inner.film.spp_range().0
    }

    #[getter]
    fn width(&self) -> u32 {
        self.inner.film.width()
    }

    #[getter]
    fn height(&self) -> u32 {
        self.inner.film.height()
    }

    /// NaN/Inf samples rejected before accumulation.
    #[getter]
    fn dropped_samples(&self) -> u64 {
        self.inner.film.dropped_samples
    }

    /// The image's estimated relative RMS error, the number the CLI prints as "estimated
    /// error": √((1/3N) Σ (s²/n) / (mean² + 0.01)) over pixels and channels; None before every
    /// pixel has two samples.
    #[getter]
    fn relative_error_estimate(&self) -> Option<f64> {
        self.inner.film.relative_rms_error_estimate()
    }

    /// Writes the image as the CLI's `-o` does: PNG tone mapped (`exposure` in stops, `tonemap`
    /// "clamp" or "aces") and sRGB encoded; EXR and PFM linear.
    #[pyo3(signature = (path, exposure=0.0, tonemap="clamp"))]
    fn write(&self, py: Python<'_>, path: PathBuf, exposure: f32, tonemap: &str) -> PyResult<()> {
        ImageFormat::from_path(&path).map_err(|e| PyValueError::new_err(e.to_string()))?;
        if !exposure.is_finite() {
            return Err(PyValueError::new_err("exposure must be a finite number of stops"));
        }
        let tone_map: ToneMap = tonemap.parse().map_err(|e| PyValueError::new_err(format!("tonemap: {e}")))?;
        let settings = ToneMapSettings { exposure, tone_map };
        let image = self.inner.film.image();
        py.detach(|| write_image(&path, &image, &settings)).map_err(|e| PyOSError::new_err(e.to_string()))
    }

    fn __repr__(&self) -> String {
        let (lo, hi) = self.inner.film.spp_range();
        let spp = if lo == hi { format!("{lo}") } else { format!("{lo}-{hi}") };
        let ranges = if self.whole_ranges {
            let list: Vec<String> = self.inner.ranges.iter().map(|r| r.to_string()).collect();
            format!(", samples {} of {}", list.join(", "), self.inner.spp)
        } else {
            String::new()
        };
        format!("<pathtrace.Film {}x{}, {spp} spp{ranges}>", self.inner.film.width(), self.inner.film.height())
    }

    /// The sample ranges the film holds, as ``(start, end)`` pairs (end exclusive), sorted.
    #[getter]
    fn sample_ranges(&self) -> Vec<(u32, u32)> {
        self.inner.ranges.iter().map(|r| (r.start, r.end)).collect()
    }

    /// The ranges of ``0..total_spp`` the film does not hold yet.
    #[getter]
    fn missing_ranges(&self) -> Vec<(u32, u32)> {
        if !self.whole_ranges {
            return vec![(0, self.inner.spp)];
        }
        self.inner.missing().iter().map(|r| (r.start, r.end)).collect()
    }

    /// The key of the render (scene and settings) the film belongs to, in hex.
    #[getter]
    fn key(&self) -> String {
        format!("{:016x}", self.inner.key)
    }

    /// The whole render's samples per pixel (of which this film may hold a part).
    #[getter]
    fn total_spp(&self) -> u32 {
        self.inner.spp
    }

    /// Whether the film holds every sample of its render.
    #[getter]
    fn complete(&self) -> bool {
        self.whole_ranges && self.inner.is_complete()
    }

    /// The film as bytes: the `.ptfilm` format `pathtrace merge` reads (docs/distributed.md).
    fn to_bytes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        let bytes = self.mergeable("to_bytes")?.to_bytes();
        Ok(PyBytes::new(py, &bytes))
    }

    /// A film from `to_bytes()` (or a `.ptfilm` file's contents); ValueError if they are not one.
    #[classmethod]
    fn from_bytes(_cls: &Bound<'_, PyType>, data: &[u8]) -> PyResult<Film> {
        let inner = RangedFilm::from_bytes(data).map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(Film { inner, whole_ranges: true })
    }

    /// Pickling goes through `to_bytes`.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, PyBytes>,))> {
        let from_bytes = slf.get_type().getattr("from_bytes")?;
        Ok((from_bytes, (slf.get().to_bytes(slf.py())?,)))
    }

    /// `a + b`: the film holding both films' samples, and their feature buffers' (exact: any order
    /// of additions gives the same bits). ValueError if they belong to different renders, share a
    /// sample range, or one has feature buffers and the other not.
    fn __add__(&self, other: &Film) -> PyResult<Film> {
        let mut sum = self.mergeable("+")?.clone();
        sum.merge(other.mergeable("+")?).map_err(|e| PyValueError::new_err(format!("cannot merge: {e}")))?;
        Ok(Film { inner: sum, whole_ranges: true })
    }

    /// Bit-for-bit equality of the samples, the feature buffers, the render key and the ranges.
    fn __eq__(&self, other: &Film) -> bool {
        self.inner == other.inner && self.whole_ranges == other.whole_ranges
    }
}
