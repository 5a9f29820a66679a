//! The estimator runs in groups of SIMD lanes (16 with AVX2, 32 with AVX-512, 8 in the portable build) or one path at a time (`Kernel::Scalar`,
//! its one-lane instance). Both are the same code on the same random numbers, so every camera
//! sample gets the same value to the last bit: at one sample per pixel (where a pixel's film
//! entry is its one sample, whatever the order samples finish in) the images are identical.
//!
//! This checks the lane machinery — masks, per-lane state, path regeneration, the split
//! between SIMD-shaded and lane-by-lane-shaded lanes — on scenes that use every material,
//! light, texture, strategy and sampler the repository's scenes hold, every camera,
//! participating media, and glTF's textured emission, roughness and metallic and mesh tangents.

use pathtrace::film::Image;
use pathtrace::integrator::Strategy;
use pathtrace::sampling::SamplerKind;
use pathtrace::wide::Kernel;
use pathtrace::{render, RenderSettings, Scene};
use pathtrace_scene::mitsuba::load_mitsuba;
use pathtrace_scene::native::load_file;
use std::path::{Path, PathBuf};
use std::sync::Arc;

fn repo_scene(rel: &str) -> Arc<Scene> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..").join(rel);
    Arc::new(load_file(&path).unwrap_or_else(|e| panic!("{rel}: {e}")).scene)
}

/// The public Mitsuba scenes with textures, environment maps, microfacets, meshes with vertex
/// normals, spheres and point lights (skipped when ../shared/scenes is absent).
fn shared_scenes() -> Vec<(String, Arc<Scene>)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes");
    if !dir.is_dir() {
        eprintln!("note: {} is absent; the public scenes are skipped", dir.display());
        return Vec::new();
    }
    let files = [
        ("bunny/docs/scenes/shape_ply_bunny.xml", &[][..]),
        ("matpreview/docs/scenes/bsdf_roughconductor_copper.xml", &[][..]),
        ("matpreview/docs/scenes/bsdf_dielectric_glass.xml", &[][..]),
        ("cbox/cbox.xml", &[][..]),
        ("teapot-simple/simple.xml", &[][..]),
        ("veach-mis-bitterli/scene_v3.xml", &[("integrator", "path")][..]),
        ("veach-mis/docs/scenes/integrator_direct_both.xml", &[][..]),
    ];
    files
        .iter()
        .filter_map(|(rel, defines)| {
            let path = dir.join(rel);
            path.is_file().then(|| {
                let (loaded, _) = load_mitsuba(&path, defines).unwrap_or_else(|e| panic!("{rel}: {e}"));
                (rel.to_string(), Arc::new(loaded.scene))
            })
        })
        .collect()
}

/// The image's values, then the feature buffers' (albedo, normal, depth), recorded with it.
fn one_spp(scene: &Arc<Scene>, kernel: Kernel, strategy: Strategy, sampler: SamplerKind) -> (Vec<f32>, Vec<f32>) {
    let mut s = RenderSettings {
        width: 48,
        height: 36,
        spp: 1,
        seed: 9,
        sampler,
        kernel,
        threads: 1,
        features: true,
        ..Default::default()
    };
    s.path.strategy = strategy;
    s.path.max_depth = 12;
    let out = render(Arc::clone(scene), s).unwrap();
    let values = |img: &Image| img.pixels.iter().flat_map(|p| p.to_array()).collect::<Vec<f32>>();
    let f = out.features.expect("features were asked for");
    (values(&out.film.image()), [values(&f.albedo()), values(&f.normal()), values(&f.depth())].concat())
}

#[test]
fn lanes_and_one_lane_give_every_sample_the_same_value() {
    let scenes = [
        "scenes/cornell-box.toml",
        "scenes/bench/glass-metal-spheres.toml",
        "scenes/converge/veach-mis.toml",
        "scenes/gallery/01-red-sphere.toml",
        "scenes/gallery/05-cornell-mirror-glossy.toml",
        "scenes/gallery/07-cornell-glass.toml",
        "scenes/gallery/08-sky-point-thin-glass.toml",
    ];
    let strategies = [Strategy::Mis, Strategy::MisBalance, Strategy::Bsdf, Strategy::Mixture, Strategy::Light];
    let samplers = [SamplerKind::Independent, SamplerKind::Stratified, SamplerKind::Sobol];
    let mut all: Vec<(String, Arc<Scene>)> = scenes.iter().map(|rel| (rel.to_string(), repo_scene(rel))).collect();
    all.extend(shared_scenes());
    // The thin-lens camera draws a second 2D point per camera sample; the orthographic one none.
    // The normal- and bump-mapped surfaces (shaded lane by lane in a perturbed frame), the
    // opacity masks (rays passing cut-outs), and media: a camera inside null-bounded fog under
    // a directional light, and a glass sphere filled with a scattering medium (free flights,
    // medium vertices, null crossings).
    for rel in [
        "tests/data/thinlens_box.xml",
        "tests/data/orthographic_box.xml",
        "tests/data/v06/scene.xml",
        "tests/data/maps/normal_bump.xml",
        "tests/data/maps/mask.xml",
        "tests/data/maps/roughness.xml",
        "tests/data/maps/plastic_alpha.xml",
        "tests/data/maps/emitter_texture.xml",
        "tests/data/smooth_edges/scene.xml",
        "tests/data/media/fog_shafts.xml",
        "tests/data/media/jelly_sphere.xml",
    ] {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(rel);
        let (loaded, _) = load_mitsuba(&path, &[]).unwrap_or_else(|e| panic!("{rel}: {e}"));
        all.push((rel.to_string(), Arc::new(loaded.scene)));
    }
    // glTF: a light whose radiance is a texture (sampled lane by lane through the light set), a
    // roughness texture, a metallic texture (a blend of two models), and a normal map in the frame of the mesh's own tangents (carried per
    // lane, with a negative bitangent sign).
    for rel in [
        "tests/data/maps/emissive.glb",
        "tests/data/maps/metal_rough.gltf",
        "tests/data/maps/metallic.gltf",
        "tests/data/maps/normal_map_tangents.gltf",
    ] {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(rel);
        let (loaded, _) = pathtrace_scene::gltf::load_gltf(&path, &[]).unwrap_or_else(|e| panic!("{rel}: {e}"));
        all.push((rel.to_string(), Arc::new(loaded.scene)));
    }
    for (k, (rel, scene)) in all.iter().enumerate() {
        // Every strategy once and every sampler once per scene, in rotation.
        let mut lit = false;
        for (j, strategy) in strategies.iter().enumerate() {
            let sampler = samplers[(j + k) % samplers.len()];
            let (wide, wide_features) = one_spp(scene, Kernel::Wide, *strategy, sampler);
            let (one, one_features) = one_spp(scene, Kernel::Scalar, *strategy, sampler);
            let differ = wide.iter().zip(&one).filter(|(a, b)| a.to_bits() != b.to_bits()).count();
            assert_eq!(differ, 0, "{rel} {strategy} {sampler}: {differ} of {} values differ", wide.len());
            let differ = wide_features.iter().zip(&one_features).filter(|(a, b)| a.to_bits() != b.to_bits()).count();
            assert_eq!(differ, 0, "{rel} {strategy} {sampler}: {differ} feature values differ");
            lit |= wide.iter().any(|&v| v > 0.0);
        }
        // (Point lights are black under the strategies that cannot sample them.)
        assert!(lit, "{rel}: black images prove nothing");
    }
}

/// Filters wider than the pixel splat every sample into its neighbours (film/splat.rs): the
/// splatted sums are exact integers too, so lanes and one lane (and hence any order in which a
/// tile's samples finish) give the same film, sums and image, at several samples per pixel.
#[test]
fn splatting_filters_give_the_same_film_with_lanes_and_one_lane() {
    use pathtrace::film::PixelFilter;
    let filters = [PixelFilter::by_name("gaussian").unwrap(), PixelFilter::Tent { radius: 1.5 }];
    for (k, rel) in ["scenes/cornell-box.toml", "scenes/gallery/08-sky-point-thin-glass.toml"].iter().enumerate() {
        let scene = repo_scene(rel);
        let film = |kernel: Kernel| {
            let mut s = RenderSettings {
                width: 30,
                height: 22,
                spp: 3,
                seed: 4,
                sampler: [SamplerKind::Sobol, SamplerKind::Independent][k],
                kernel,
                threads: 1,
                tile_size: 8,
                filter: filters[k].clone(),
                ..Default::default()
            };
            s.path.max_depth = 8;
            render(Arc::clone(&scene), s).unwrap().film
        };
        let (wide, one) = (film(Kernel::Wide), film(Kernel::Scalar));
        assert!(wide.splat_pixels().is_some(), "{rel}: a splatting film");
        assert_eq!(wide, one, "{rel}: the films differ");
        assert!(wide.image().pixels.iter().any(|p| p.r > 0.0), "{rel}: black images prove nothing");
    }
}
