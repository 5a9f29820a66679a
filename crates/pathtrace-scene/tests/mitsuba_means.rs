//! Acceptance: the public Mitsuba scenes that use only supported plugins load without a single
//! warning and render to the same mean colour as Mitsuba 3 itself, within 2% per channel.
//!
//! References: Mitsuba 3.9.1, `scalar_rgb`, each scene as written but with a 64 × 64 film,
//! 4096 spp (standard error < 0.1%), from
//! `.venv-peers/bin/python benches/peers/scene_means.py --size 64 --spp 4096`
//! (see benches/peers/README.md). Skipped with a note when ../shared/scenes is absent.

use pathtrace::{render, RenderSettings};
use pathtrace_scene::mitsuba::load_mitsuba;
use std::path::Path;
use std::sync::Arc;

const SIZE: u32 = 64;

/// (scene, Mitsuba's mean RGB at 64², 4096 spp).
const REFERENCES: [(&str, [f64; 3]); 4] = [
    ("cbox/cbox.xml", CBOX),
    ("cornell-box-bitterli/scene_v3.xml", BITTERLI),
    ("teapot-simple/simple.xml", TEAPOT),
    ("cbox-classic/docs/scenes/integrator_depth_inf.xml", CBOX_CLASSIC),
];
const CBOX: [f64; 3] = [0.33072, 0.19966, 0.08600];
const BITTERLI: [f64; 3] = [0.19645, 0.12766, 0.03614];
const TEAPOT: [f64; 3] = [0.06793, 0.06793, 0.0];
const CBOX_CLASSIC: [f64; 3] = [0.22645, 0.11616, 0.02652];

#[test]
fn supported_public_scenes_load_cleanly_and_match_mitsuba_within_two_percent() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes");
    if !dir.is_dir() {
        eprintln!("skipped: {} is absent", dir.display());
        return;
    }
    for (scene, reference) in REFERENCES {
        let (loaded, warnings) = load_mitsuba(&dir.join(scene), &[]).unwrap_or_else(|e| panic!("{scene}: {e}"));
        assert!(warnings.is_empty(), "{scene}: {warnings:#?}");
        let d = loaded.defaults;
        let mut s = RenderSettings { width: SIZE, height: SIZE, spp: 512, seed: 1, ..Default::default() };
        s.filter = d.filter.unwrap_or_default();
        s.path.max_depth = d.max_depth;
        let out = render(Arc::new(loaded.scene), s).unwrap();
        assert_eq!(out.progress.dropped_samples, 0, "{scene}: NaN samples");
        let est = out.film.region_estimate(0, 0, SIZE, SIZE);
        let sd = est.variance_of_mean.map(f64::sqrt);
        eprintln!("{scene}: ours {:.5?} ± {sd:.6?}, Mitsuba {reference:.5?}", est.mean);
        for (k, &theirs) in reference.iter().enumerate() {
            let ours = est.mean[k];
            // 2% of the channel, and a floor for channels that are black in both.
            assert!(
                (ours - theirs).abs() <= 0.02 * theirs + 1e-4,
                "{scene} channel {k}: ours {ours:.5} vs Mitsuba {theirs:.5} ({:+.2}%)",
                100.0 * (ours / theirs - 1.0)
            );
            // The estimate must be precise enough for the 2% test to mean something.
            assert!(est.variance_of_mean[k].sqrt() <= 0.004 * theirs + 1e-5, "{scene}: too noisy");
        }
    }
}
