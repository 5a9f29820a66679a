//! The built-in Cornell box is now a scene file (scenes/cornell-box.toml). This keeps the
//! SceneBuilder version it replaced and checks that both render the same film, bit for bit.

use pathtrace::film::Film;
use pathtrace::light::Emission;
use pathtrace::material::{Lambertian, Material};
use pathtrace::math::{Rgb, Transform, Vec3};
use pathtrace::shape::{Quad, Shape};
use pathtrace::{render, CameraDesc, RenderSettings, Scene, SceneBuilder};
use std::sync::Arc;

/// The Cornell box as the Rust code built it before it became a file.
fn reference() -> Scene {
    let quad = |q: [f32; 3], u: [f32; 3], v: [f32; 3]| {
        Shape::Quad(Quad::new(Vec3::from(q), Vec3::from(u), Vec3::from(v)).unwrap())
    };
    let mut b = SceneBuilder::new();
    let lambert = |r, g, bl| Material::Lambertian(Lambertian { albedo: Rgb::new(r, g, bl) });
    let red = b.material(lambert(0.65, 0.05, 0.05));
    let white = b.material(lambert(0.73, 0.73, 0.73));
    let green = b.material(lambert(0.12, 0.45, 0.15));
    let light = b.emissive(Emission { radiance: Rgb::splat(15.0), two_sided: false });
    let id = Transform::IDENTITY;

    b.shape(quad([555.0, 0.0, 0.0], [0.0, 555.0, 0.0], [0.0, 0.0, 555.0]), green, &id).unwrap();
    b.shape(quad([0.0, 0.0, 0.0], [0.0, 555.0, 0.0], [0.0, 0.0, 555.0]), red, &id).unwrap();
    b.shape(quad([343.0, 554.0, 332.0], [-130.0, 0.0, 0.0], [0.0, 0.0, -105.0]), light, &id).unwrap();
    b.shape(quad([0.0, 0.0, 0.0], [555.0, 0.0, 0.0], [0.0, 0.0, 555.0]), white, &id).unwrap();
    b.shape(quad([555.0, 555.0, 555.0], [-555.0, 0.0, 0.0], [0.0, 0.0, -555.0]), white, &id).unwrap();
    b.shape(quad([0.0, 0.0, 555.0], [555.0, 0.0, 0.0], [0.0, 555.0, 0.0]), white, &id).unwrap();

    let tall = Transform::rotate_y(15.0).then(&Transform::translate(Vec3::new(265.0, 0.0, 295.0)));
    b.add_box(Vec3::ZERO, Vec3::new(165.0, 330.0, 165.0), white, &tall).unwrap();
    let short = Transform::rotate_y(-18.0).then(&Transform::translate(Vec3::new(130.0, 0.0, 65.0)));
    b.add_box(Vec3::ZERO, Vec3::splat(165.0), white, &short).unwrap();

    b.camera(CameraDesc {
        look_from: Vec3::new(278.0, 278.0, -800.0),
        look_at: Vec3::new(278.0, 278.0, 0.0),
        up: Vec3::Y,
        vfov_degrees: 40.0,
        focal_length: 1.0,
        ..Default::default()
    });
    b.build().unwrap()
}

fn film(scene: Scene) -> Film {
    let s = RenderSettings { width: 32, height: 32, spp: 16, seed: 7, ..Default::default() };
    render(Arc::new(scene), s).unwrap().film
}

#[test]
fn the_file_renders_exactly_like_the_rust_built_scene() {
    let loaded = pathtrace_scene::builtin::load("cornell-box").unwrap().unwrap();
    let (a, b) = (film(loaded.scene), film(reference()));
    for y in 0..32 {
        for x in 0..32 {
            assert_eq!(a.pixel(x, y), b.pixel(x, y), "pixel ({x}, {y})");
        }
    }
    let d = loaded.defaults;
    assert_eq!((d.width, d.height, d.spp, d.max_depth), (512, 512, 256, -1));
    assert_eq!((d.strategy, d.sampler, d.seed), (None, None, None));
}

#[test]
fn the_repository_file_is_the_embedded_one() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/cornell-box.toml");
    let from_disk = pathtrace_scene::native::load_file(path.as_ref()).unwrap();
    assert_eq!(from_disk.scene.primitive_count(), 18);
}
