//! Spot lights against Mitsuba 3: tests/data/spot.xml (two `spot` emitters, one with the default
//! beam width and a lookat, one with an explicit beam width and a rotate + translate, over a
//! diffuse floor, wall and sphere; path tracing to depth 4) must load without a warning and
//! render to Mitsuba's mean colour.
//!
//! Measured with the same script and `--pathtrace target/release/pathtrace` (4 × 4096 spp each):
//! ours / Mitsuba = 1.00045, 1.00061, 1.00079 (z = 1.7, 2.9, 4.1): a 0.05–0.08% excess, beyond
//! the noise at that precision but far below it here; the test asserts agreement within 0.5%
//! at 1024 spp, where our own standard error is about 0.15%.
//!
//! Reference: Mitsuba 3.9.1, `scalar_rgb`, 64 × 48, 4 runs × 4096 spp (standard error ≤ 0.03%),
//! from
//! `.venv-peers/bin/python benches/peers/scene_means.py crates/pathtrace-scene/tests/data/spot.xml --spp 4096 --runs 4 --digits 6`.

use pathtrace::light::Light;
use pathtrace::{render, RenderSettings};
use pathtrace_scene::mitsuba::load_mitsuba;
use std::path::Path;
use std::sync::Arc;

/// Mitsuba's image mean (R, G, B) and its standard error.
const MITSUBA: [f64; 3] = [0.039016, 0.032680, 0.026631];
const MITSUBA_SE: [f64; 3] = [0.000007, 0.000004, 0.000003];

#[test]
fn spot_lights_match_mitsuba() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/spot.xml");
    let (loaded, warnings) = load_mitsuba(&path, &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    assert_eq!(loaded.scene.lights.lights().iter().filter(|l| matches!(l, Light::Spot(_))).count(), 2);
    let d = loaded.defaults;
    let mut s = RenderSettings { width: d.width, height: d.height, spp: 1024, seed: 5, ..Default::default() };
    s.path.max_depth = d.max_depth;
    let out = render(Arc::new(loaded.scene), s).unwrap();
    assert_eq!(out.progress.dropped_samples, 0);
    let est = out.film.region_estimate(0, 0, d.width, d.height);
    for k in 0..3 {
        let (ours, theirs) = (est.mean[k], MITSUBA[k]);
        let sigma = (est.variance_of_mean[k] + MITSUBA_SE[k] * MITSUBA_SE[k]).sqrt();
        let z = (ours - theirs) / sigma;
        eprintln!(
            "channel {k}: ours {ours:.6} vs Mitsuba {theirs:.6} ({:+.2}%, z = {z:.2})",
            100.0 * (ours / theirs - 1.0)
        );
        assert!(
            (ours - theirs).abs() < 0.005 * theirs,
            "channel {k}: ours {ours:.6} vs Mitsuba {theirs:.6} (z = {z:.2})"
        );
        assert!(sigma < 0.002 * theirs, "too noisy to judge");
    }
}
