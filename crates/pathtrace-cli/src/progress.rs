//! The progress bar: spp done, samples/s and ETA, drawn on stderr only when it is a terminal.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use pathtrace::Progress;
use std::time::Duration;

/// A progress bar over pixel samples (or seconds, for timed renders).
pub struct Bar {
    bar: ProgressBar,
    pixels: u64,
    timed: bool,
}

impl Bar {
    pub fn new(pixels: u64, spp: u32, time_limit: Option<Duration>, quiet: bool) -> Self {
        let timed = time_limit.is_some();
        // Open-ended renders (a target error and no cap) have no length: a spinner.
        let len = match time_limit {
            Some(t) => Some(t.as_millis() as u64),
            None => (spp > 0).then_some(pixels * spp as u64),
        };
        let bar = ProgressBar::with_draw_target(
            len,
            if quiet { ProgressDrawTarget::hidden() } else { ProgressDrawTarget::stderr() },
        );
        let template = if len.is_none() {
            "{spinner} {msg} · {elapsed_precise}"
        } else if timed {
            "{spinner} [{bar:30}] {msg} · {elapsed_precise}"
        } else {
            "{spinner} [{bar:30}] {msg} · ETA {eta}"
        };
        if let Ok(style) = ProgressStyle::with_template(template) {
            bar.set_style(style.progress_chars("=> "));
        }
        Self { bar, pixels, timed }
    }

    pub fn update(&self, p: &Progress) {
        if self.timed {
            self.bar.set_position(p.elapsed.as_millis() as u64);
        } else {
            self.bar.set_position(p.samples);
        }
        let spp = p.samples as f64 / self.pixels.max(1) as f64;
        let target = if p.spp_target > 0 { format!("/{}", p.spp_target) } else { String::new() };
        // With a target error, how close the estimate is: "error 3.10% → 2.00%".
        let error = match (p.error_estimate, p.target_error) {
            (Some(e), Some(t)) => format!(" · error {:.2}% → {:.2}%", 100.0 * e, 100.0 * t),
            (None, Some(t)) => format!(" · error ? → {:.2}%", 100.0 * t),
            _ => String::new(),
        };
        self.bar
            .set_message(format!("{spp:.1}{target} spp · {}{error}", format_rate(p.samples_per_second, "samples/s")));
    }

    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

/// "1.23 M samples/s".
pub fn format_rate(per_second: f64, unit: &str) -> String {
    if per_second >= 1e6 {
        format!("{:.2} M {unit}", per_second / 1e6)
    } else if per_second >= 1e3 {
        format!("{:.1} k {unit}", per_second / 1e3)
    } else {
        format!("{per_second:.0} {unit}")
    }
}
