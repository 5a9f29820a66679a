use super::draw::{axis_range, tick_label};
use super::*;

fn example() -> LinePlot {
    let mut plot = LinePlot::log_log("Convergence <test>", "samples per pixel", "relative MSE");
    plot.series
        .push(Series { label: "bsdf & independent".into(), points: vec![(1.0, 1.0), (10.0, 0.1), (100.0, 0.01)] });
    plot.series.push(Series { label: "mis".into(), points: vec![(1.0, 0.2), (100.0, 0.0), (1000.0, 2e-4)] });
    plot
}

#[test]
fn svg_has_every_series_label_and_escapes_text() {
    let svg = example().to_svg().unwrap();
    assert!(svg.starts_with("<svg") || svg.starts_with("<?xml"), "{}", &svg[..60]);
    assert!(svg.contains("bsdf &amp; independent"));
    assert!(svg.contains("Convergence &lt;test&gt;"));
    assert!(svg.contains("\nmis\n"));
    assert!(svg.contains("samples per pixel") && svg.contains("relative MSE"));
    assert!(svg.matches("<polyline").count() >= 2);
}

#[test]
fn png_has_text_drawn_with_the_embedded_font() {
    let rgb = example().to_rgb().unwrap();
    let (w, h) = PLOT_SIZE;
    // The title band (above the plot area) is white except for the title's glyphs: if no font
    // were available it would stay blank.
    let band = |y0: u32, y1: u32| {
        (y0..y1)
            .flat_map(|y| (0..w).map(move |x| ((y * w + x) * 3) as usize))
            .filter(|&i| rgb[i] < 128 && rgb[i + 1] < 128 && rgb[i + 2] < 128)
            .count()
    };
    assert!(band(0, 40) > 100, "no dark title pixels");
    // Both series colours appear.
    let has = |c: [u8; 3]| rgb.chunks(3).any(|p| p == c);
    assert!(has([31, 119, 180]) && has([214, 39, 40]));
    assert_eq!(rgb.len(), (w * h * 3) as usize);
}

#[test]
fn writes_both_files() {
    let dir = std::env::temp_dir().join(format!("pathtrace-plot-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let plot = example();
    plot.write_svg(&dir.join("p.svg")).unwrap();
    plot.write_png(&dir.join("p.png")).unwrap();
    let png = std::fs::read(dir.join("p.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let err = plot.write_png(&dir.join("missing/p.png")).unwrap_err();
    assert!(err.to_string().contains("missing"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn axes_cover_whole_decades_or_pad_linear_data() {
    assert_eq!(axis_range([0.02, 3.0].into_iter(), true), (0.01, 10.0));
    assert_eq!(axis_range([5.0].into_iter(), true), (1.0, 10.0));
    assert_eq!(axis_range(std::iter::empty(), true), (1.0, 10.0));
    let (a, b) = axis_range([0.0, 10.0].into_iter(), false);
    assert!((a + 0.5).abs() < 1e-12 && (b - 10.5).abs() < 1e-12);
    assert_eq!(tick_label(0.25), "0.25");
    assert_eq!(tick_label(100.0), "100");
    assert_eq!(tick_label(1e-5), "1e-5");
}

#[test]
fn linear_axes_and_empty_plots_draw() {
    let mut plot = example();
    plot.log_x = false;
    plot.log_y = false;
    assert!(plot.to_svg().is_ok() && plot.to_rgb().is_ok());
    plot.series.clear();
    assert!(plot.to_svg().is_ok());
}
