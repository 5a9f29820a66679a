//! The museum environment map of the shared matpreview scenes (with its own to_world and
//! scale 3), seen directly by a camera in five directions, against Mitsuba 3: only the map's
//! lookup, orientation and scale decide these means, so they check that the lat-long
//! conventions are Mitsuba's. References from
//! `.venv-peers/bin/python benches/peers/envmap_mitsuba.py --out /tmp/envmap-check` (Mitsuba
//! 3, `scalar_rgb`, 64 spp; the same XML as below); agreement measured within 0.5%, asserted
//! within 1% per channel. Skipped when ../shared/scenes is absent.

use pathtrace::{render, RenderSettings};
use pathtrace_scene::mitsuba::load_mitsuba;
use std::path::Path;
use std::sync::Arc;

/// (camera target from the origin, Mitsuba's mean RGB).
const VIEWS: [([f32; 3], [f64; 3]); 5] = [
    ([0.0, 0.0, 1.0], [0.76674, 0.52998, 0.42667]),
    ([1.0, 0.2, 0.3], [0.73170, 0.34054, 0.17383]),
    ([-1.0, 0.5, -0.2], [2.34355, 2.06651, 1.84467]),
    ([0.2, -0.6, -1.0], [0.31880, 0.14926, 0.09540]),
    ([0.3, 1.0, 0.1], [0.84651, 0.40323, 0.21785]),
];

fn scene_xml(target: [f32; 3], exr: &Path) -> String {
    let up = if target[1].abs() > 0.9 { "0, 0, 1" } else { "0, 1, 0" };
    format!(
        r#"<scene version="3.0.0">
  <integrator type="path"/>
  <sensor type="perspective">
    <float name="fov" value="70"/>
    <transform name="to_world"><lookat origin="0, 0, 0" target="{}, {}, {}" up="{up}"/></transform>
    <sampler type="independent"><integer name="sample_count" value="64"/></sampler>
    <film type="hdrfilm"><integer name="width" value="48"/><integer name="height" value="32"/>
      <rfilter type="box"/></film>
  </sensor>
  <emitter type="envmap">
    <string name="filename" value="{}"/>
    <transform name="to_world">
      <rotate y="1" angle="-180"/>
      <matrix value="-0.224951 -0.000001 -0.974370 0.000000 -0.974370 0.000000 0.224951 0.000000 0.000000 1.000000 -0.000001 8.870000 0.000000 0.000000 0.000000 1.000000 "/>
    </transform>
    <float name="scale" value="3"/>
  </emitter>
  <shape type="sphere"><point name="center" x="0" y="-1000" z="0"/><float name="radius" value="0.01"/></shape>
</scene>
"#,
        target[0],
        target[1],
        target[2],
        exr.display()
    )
}

#[test]
fn the_museum_map_looks_as_in_mitsuba() {
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes");
    let exr = scenes.join("matpreview/common/textures/museum.exr");
    if !exr.is_file() {
        eprintln!("skipped: {} is absent", exr.display());
        return;
    }
    let exr = exr.canonicalize().unwrap();
    let dir = std::env::temp_dir().join(format!("pathtrace-envmap-mitsuba-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (k, (target, reference)) in VIEWS.iter().enumerate() {
        let path = dir.join(format!("view{k}.xml"));
        std::fs::write(&path, scene_xml(*target, &exr)).unwrap();
        let (loaded, warnings) = load_mitsuba(&path, &[]).unwrap();
        assert!(warnings.is_empty(), "{warnings:?}");
        let mut s = RenderSettings { width: 48, height: 32, spp: 256, seed: 1, ..Default::default() };
        s.filter = loaded.defaults.filter.unwrap_or_default();
        let out = render(Arc::new(loaded.scene), s).unwrap();
        let est = out.film.region_estimate(0, 0, 48, 32);
        eprintln!("view{k} {target:?}: ours {:.5?}, Mitsuba {reference:.5?}", est.mean);
        for (c, &theirs) in reference.iter().enumerate() {
            let ours = est.mean[c];
            assert!(
                (ours - theirs).abs() <= 0.01 * theirs,
                "view{k} channel {c}: ours {ours:.5} vs Mitsuba {theirs:.5}"
            );
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}
