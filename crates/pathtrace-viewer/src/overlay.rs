//! Text of the status bar and of the help overlay.

use pathtrace::Progress;

/// Keyboard and mouse shortcuts: (keys, what they do). Listed by F1 / ? and in docs/viewer.md.
pub const SHORTCUTS: [(&str, &str); 26] = [
    ("left drag / arrows", "orbit the camera around its look-at point"),
    ("right drag", "pan the camera (eye and look-at move together)"),
    ("scroll", "zoom: change the field of view"),
    ("W A S D / Q E", "fly forward, left, back, right / down, up"),
    ("R", "reset the camera to the scene's"),
    ("O I", "open / close the aperture (depth of field; closed fully: a pinhole)"),
    ("K L", "move the plane of focus nearer / farther"),
    ("double-click", "focus on the surface under the cursor"),
    ("M", "next strategy (mis, mis-balance, bsdf, mixture, light)"),
    ("N", "next sampler (independent, stratified, sobol)"),
    ("[ ]", "maximum depth down / up (below 1: unlimited)"),
    ("- =", "exposure down / up by half a stop"),
    ("T", "tone map: clamp / aces"),
    ("V", "view: render, std. error, albedo, normals, depth, difference"),
    ("G", "toggle the difference image (with --reference)"),
    ("X", "denoise the current snapshot (Open Image Denoise, if installed) / back to the live render"),
    ("Ctrl + scroll", "magnify the picture (nearest pixel)"),
    ("middle drag", "move the picture"),
    ("1", "picture at one pixel per screen pixel, centred"),
    ("Space", "pause / resume rendering"),
    ("Ctrl+S", "save the image as NAME-view.png and NAME-view.exr"),
    ("C", "save the camera into NAME-view.toml"),
    ("H", "hide / show the status bar"),
    ("F1 / ?", "this help"),
    ("Esc", "close the help, else quit"),
    ("", "any change of camera, strategy, sampler or depth restarts accumulation"),
];

/// "1.23 M" style numbers.
pub fn si(v: f64) -> String {
    match v {
        v if v >= 1e9 => format!("{:.2} G", v / 1e9),
        v if v >= 1e6 => format!("{:.2} M", v / 1e6),
        v if v >= 1e3 => format!("{:.1} k", v / 1e3),
        v => format!("{v:.0} "),
    }
}

/// The progress part of the status bar.
pub fn progress_line(p: &Progress, paused: bool, noise: Option<f64>) -> String {
    let target = if p.spp_target > 0 { format!("/{}", p.spp_target) } else { String::new() };
    let state = if paused {
        " · paused"
    } else if p.finished {
        " · done"
    } else {
        ""
    };
    let noise = noise.map_or(String::from("–"), |n| format!("{:.2}%", 100.0 * n));
    format!(
        "{}{target} spp · {}samples/s · {:.1} s · noise ≈ {noise} · NaN dropped {}{state}",
        p.spp_done,
        si(p.samples_per_second),
        p.elapsed.as_secs_f64(),
        p.dropped_samples,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn the_status_line_shows_every_figure() {
        let p = Progress {
            spp_done: 16,
            spp_target: 64,
            samples_per_second: 2.5e6,
            elapsed: Duration::from_millis(1500),
            dropped_samples: 3,
            ..Default::default()
        };
        let line = progress_line(&p, false, Some(0.0123));
        for part in ["16/64 spp", "2.50 Msamples/s", "1.5 s", "1.23%", "NaN dropped 3"] {
            assert!(line.contains(part), "{line} lacks {part}");
        }
        assert!(progress_line(&p, true, None).contains("paused"));
    }

    #[test]
    fn docs_list_every_shortcut() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/viewer.md");
        let Ok(doc) = std::fs::read_to_string(path) else {
            return eprintln!("SKIP docs_list_every_shortcut: {path} not found");
        };
        for (keys, what) in SHORTCUTS.iter().filter(|(k, _)| !k.is_empty()) {
            assert!(doc.contains(&format!("| `{keys}` | {what} |")), "docs/viewer.md lacks the row for {keys}");
        }
    }
}
