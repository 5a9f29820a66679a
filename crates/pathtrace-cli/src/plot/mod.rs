//! Line plots written as SVG and PNG from one description, drawn with `plotters`.
//!
//! A [`LinePlot`] holds a title, axis labels, a linear or logarithmic scale per axis and any
//! number of labelled [`Series`]; [`LinePlot::write_svg`] and [`LinePlot::write_png`] draw the
//! same chart. Text is set in DejaVu Sans, embedded in the binary (the `dejavu` crate, Bitstream
//! Vera licence), so PNGs come out the same on machines without any system font.
//!
//! Used by `pathtrace converge` for error-vs-spp and error-vs-time curves; meant for any
//! log–log analysis plot (several series, legend).

mod draw;
mod font;

use std::path::Path;

/// One labelled line of a plot.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    pub label: String,
    /// `(x, y)` points in drawing order. On a logarithmic axis, points with a non-positive
    /// coordinate are left out; non-finite points are always left out.
    pub points: Vec<(f64, f64)>,
}

/// A chart of several lines with a legend.
#[derive(Clone, Debug, PartialEq)]
pub struct LinePlot {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub log_x: bool,
    pub log_y: bool,
    pub series: Vec<Series>,
}

/// Pixel size of written plots (SVG user units and PNG pixels alike).
pub const PLOT_SIZE: (u32, u32) = (800, 520);

/// Why a plot could not be written.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    #[error("cannot draw the plot: {0}")]
    Draw(String),
    #[error("cannot write {path}: {message}")]
    Write { path: String, message: String },
}

impl LinePlot {
    /// A log–log plot (the usual shape of a convergence or scaling curve).
    pub fn log_log(title: impl Into<String>, x_label: impl Into<String>, y_label: impl Into<String>) -> Self {
        Self {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            log_x: true,
            log_y: true,
            series: Vec::new(),
        }
    }

    /// The plot as an SVG document.
    pub fn to_svg(&self) -> Result<String, PlotError> {
        let mut svg = String::new();
        draw::svg(self, &mut svg)?;
        Ok(svg)
    }

    /// The plot as 8-bit RGB pixels, row by row, `PLOT_SIZE.0 × PLOT_SIZE.1`.
    pub fn to_rgb(&self) -> Result<Vec<u8>, PlotError> {
        let (w, h) = PLOT_SIZE;
        let mut rgb = vec![0u8; w as usize * h as usize * 3];
        draw::bitmap(self, &mut rgb)?;
        Ok(rgb)
    }

    pub fn write_svg(&self, path: &Path) -> Result<(), PlotError> {
        let svg = self.to_svg()?;
        std::fs::write(path, svg).map_err(|e| write_error(path, e))
    }

    pub fn write_png(&self, path: &Path) -> Result<(), PlotError> {
        let rgb = self.to_rgb()?;
        let (w, h) = PLOT_SIZE;
        image::save_buffer_with_format(path, &rgb, w, h, image::ExtendedColorType::Rgb8, image::ImageFormat::Png)
            .map_err(|e| write_error(path, e))
    }

    /// The points of every series that the axes can show.
    fn visible_points(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.series.iter().flat_map(|s| s.points.iter().copied()).filter(|&p| self.shows(p))
    }

    fn shows(&self, (x, y): (f64, f64)) -> bool {
        x.is_finite() && y.is_finite() && (!self.log_x || x > 0.0) && (!self.log_y || y > 0.0)
    }
}

fn write_error(path: &Path, e: impl std::fmt::Display) -> PlotError {
    PlotError::Write { path: path.display().to_string(), message: e.to_string() }
}

#[cfg(test)]
mod tests;
