//! Drawing a [`LinePlot`] on any plotters backend: axes (linear or log), grid, labelled ticks,
//! one coloured line with point markers per series, and a legend.

use super::{font, LinePlot, PlotError, PLOT_SIZE};
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::coord::Shift;
use plotters::prelude::*;

/// Line colours in order (the "tableau10" palette, distinguishable in print and on screen).
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

pub fn svg(plot: &LinePlot, out: &mut String) -> Result<(), PlotError> {
    font::ensure_registered().map_err(PlotError::Draw)?;
    let root = SVGBackend::with_string(out, PLOT_SIZE).into_drawing_area();
    on_area(plot, &root)
}

pub fn bitmap(plot: &LinePlot, rgb: &mut [u8]) -> Result<(), PlotError> {
    font::ensure_registered().map_err(PlotError::Draw)?;
    let root = BitMapBackend::with_buffer(rgb, PLOT_SIZE).into_drawing_area();
    on_area(plot, &root)
}

fn draw_error(e: impl std::fmt::Display) -> PlotError {
    PlotError::Draw(e.to_string())
}

fn on_area<DB: DrawingBackend>(plot: &LinePlot, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
    root.fill(&WHITE).map_err(draw_error)?;
    let (x0, x1) = axis_range(plot.visible_points().map(|p| p.0), plot.log_x);
    let (y0, y1) = axis_range(plot.visible_points().map(|p| p.1), plot.log_y);
    // Each scale combination is its own coordinate type, hence four calls of one generic function.
    match (plot.log_x, plot.log_y) {
        (true, true) => chart(plot, root, (x0..x1).log_scale(), (y0..y1).log_scale())?,
        (true, false) => chart(plot, root, (x0..x1).log_scale(), y0..y1)?,
        (false, true) => chart(plot, root, x0..x1, (y0..y1).log_scale())?,
        (false, false) => chart(plot, root, x0..x1, y0..y1)?,
    }
    root.present().map_err(draw_error)
}

fn chart<DB, X, Y>(plot: &LinePlot, root: &DrawingArea<DB, Shift>, x: X, y: Y) -> Result<(), PlotError>
where
    DB: DrawingBackend,
    X: AsRangedCoord<Value = f64>,
    Y: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let mut chart = ChartBuilder::on(root)
        .caption(&plot.title, (font::FAMILY, 22))
        .margin(16)
        .x_label_area_size(52)
        .y_label_area_size(76)
        .build_cartesian_2d(x, y)
        .map_err(draw_error)?;
    chart
        .configure_mesh()
        .x_desc(&plot.x_label)
        .y_desc(&plot.y_label)
        .label_style((font::FAMILY, 14))
        .axis_desc_style((font::FAMILY, 16))
        .x_label_formatter(&|v| tick_label(*v))
        .y_label_formatter(&|v| tick_label(*v))
        .light_line_style(RGBColor(240, 240, 240))
        .draw()
        .map_err(draw_error)?;
    for (i, series) in plot.series.iter().enumerate() {
        let style = ShapeStyle { color: PALETTE[i % PALETTE.len()].to_rgba(), filled: false, stroke_width: 2 };
        let points: Vec<(f64, f64)> = series.points.iter().copied().filter(|&p| plot.shows(p)).collect();
        chart
            .draw_series(LineSeries::new(points.iter().copied(), style))
            .map_err(draw_error)?
            .label(series.label.as_str())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], style));
        chart.draw_series(points.iter().map(|&p| Circle::new(p, 3, style.filled()))).map_err(draw_error)?;
    }
    if !plot.series.is_empty() {
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font((font::FAMILY, 14))
            .draw()
            .map_err(draw_error)?;
    }
    Ok(())
}

/// The axis extent: whole decades around the data on a log axis, the data plus a 5% margin on
/// a linear one; a unit range when there is nothing to show.
pub(super) fn axis_range(values: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    if lo > hi {
        return if log { (1.0, 10.0) } else { (0.0, 1.0) };
    }
    if log {
        let (a, b) = (lo.log10().floor(), hi.log10().ceil());
        (10f64.powf(a), 10f64.powf(b.max(a + 1.0)))
    } else if hi > lo {
        let pad = 0.05 * (hi - lo);
        (lo - pad, hi + pad)
    } else {
        (lo - 1.0, hi + 1.0)
    }
}

/// Tick text: plain decimals in [0.001, 10⁴), powers of ten as "1e-5" outside it.
pub(super) fn tick_label(v: f64) -> String {
    let a = v.abs();
    if v == 0.0 || (1e-3..1e4).contains(&a) {
        let s = format!("{v:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{v:.0e}")
    }
}
