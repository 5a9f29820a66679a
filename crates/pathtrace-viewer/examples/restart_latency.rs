//! How fast accumulation restarts after a camera move: the time from the change to the first
//! new image (the first whole 1-spp wave), on the built-in Cornell box.
//!
//! cargo run --release -p pathtrace-viewer --example restart_latency -- [SIZE] [RESTARTS]

use pathtrace::RenderSettings;
use pathtrace_viewer::accumulation::{Accumulation, RenderKey};
use pathtrace_viewer::camera_control::orbit;
use std::sync::Arc;
use std::time::{Duration, Instant};

fn main() {
    let mut args = std::env::args().skip(1);
    let size: u32 = args.next().and_then(|a| a.parse().ok()).unwrap_or(256);
    let restarts: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(50);
    let loaded = match pathtrace_scene::builtin::load("cornell-box") {
        Some(Ok(l)) => l,
        _ => return eprintln!("error: the built-in cornell-box did not load"),
    };
    let settings = RenderSettings { width: size, height: size, spp: 1 << 20, ..RenderSettings::default() };
    let mut key = RenderKey::new(loaded.scene.camera, &settings);
    let mut acc = match Accumulation::start(Arc::new(loaded.scene), settings, key) {
        Ok(a) => a,
        Err(e) => return eprintln!("error: {e}"),
    };
    let mut first_image = Vec::new();
    for i in 0..restarts {
        // Let the old render get going, as when the user moves the camera mid-render.
        std::thread::sleep(Duration::from_millis(30));
        key.camera = orbit(&key.camera, if i % 2 == 0 { 0.01 } else { -0.01 }, 0.0);
        let t = Instant::now();
        if let Err(e) = acc.set_key(key) {
            return eprintln!("error: {e}");
        }
        while acc.progress().spp_done < 1 {
            std::thread::sleep(Duration::from_micros(200));
        }
        first_image.push(t.elapsed().as_secs_f64() * 1e3);
    }
    first_image.sort_by(f64::total_cmp);
    let pct = |p: f64| first_image[((first_image.len() - 1) as f64 * p).round() as usize];
    println!(
        "{size}x{size} cornell-box, {restarts} camera moves: first new image after median {:.1} ms, 90th percentile \
         {:.1} ms, max {:.1} ms",
        pct(0.5),
        pct(0.9),
        pct(1.0)
    );
}
