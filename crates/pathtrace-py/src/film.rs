//! `pathtrace.Film`: a finished (or cancelled) render's accumulation buffer, with numpy views of
//! its image, per-pixel variance and sample counts, its feature buffers (with `aov=True`) and
//! their denoised image, and writing to PNG/EXR/PFM as the CLI does.

use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray2, PyArray3};
use pathtrace::film::{FeatureBuffers, Image, ToneMap, ToneMapSettings};
use pathtrace_scene::image_io::{write_image, ImageFormat};
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use std::path::PathBuf;

/// A render's result: per pixel, the sample count and the running mean and variance.
#[pyclass(frozen, module = "pathtrace")]
pub struct Film {
    film: pathtrace::film::Film,
    features: Option<FeatureBuffers>,
}

impl Film {
    pub fn new(film: pathtrace::film::Film, features: Option<FeatureBuffers>) -> Self {
        Self { film, features }
    }

    fn features(&self) -> PyResult<&FeatureBuffers> {
        self.features
            .as_ref()
            .ok_or_else(|| PyValueError::new_err("this film has no feature buffers: render with aov=True"))
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
        image_array(py, &self.film.image())
    }

    /// The estimated variance of each pixel's mean (s²/n per channel), float32 (H, W, 3).
    fn variance<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f32>> {
        image_array(py, &self.film.variance_image())
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
        let (image, albedo, normal) = (self.film.image(), f.albedo(), f.normal());
        let denoised = py
            .detach(|| pathtrace_denoise::denoise(&image, &albedo, &normal))
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        Ok(image_array(py, &denoised))
    }

    /// Samples accumulated in each pixel, uint32 (H, W).
    fn counts<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<u32>> {
        let counts: Vec<u32> = self.film.pixels().iter().map(|p| p.count).collect();
        let shape = (self.film.height() as usize, self.film.width() as usize);
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
        self.film.spp_range().0
    }

    #[getter]
    fn width(&self) -> u32 {
        self.film.width()
    }

    #[getter]
    fn height(&self) -> u32 {
        self.film.height()
    }

    /// NaN/Inf samples rejected before accumulation.
    #[getter]
    fn dropped_samples(&self) -> u64 {
        self.film.dropped_samples
    }

    /// The image's estimated relative RMS error, the number the CLI prints as "estimated
    /// error": √((1/3N) Σ (s²/n) / (mean² + 0.01)) over pixels and channels; None before every
    /// pixel has two samples.
    #[getter]
    fn relative_error_estimate(&self) -> Option<f64> {
        self.film.relative_rms_error_estimate()
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
        let image = self.film.image();
        py.detach(|| write_image(&path, &image, &settings)).map_err(|e| PyOSError::new_err(e.to_string()))
    }

    fn __repr__(&self) -> String {
        let (lo, hi) = self.film.spp_range();
        let spp = if lo == hi { format!("{lo}") } else { format!("{lo}-{hi}") };
        format!("<pathtrace.Film {}x{}, {spp} spp>", self.film.width(), self.film.height())
    }
}
