//! Renders depend only on (scene, settings, seed): the number of threads changes nothing, not
//! even the last bit.

use pathtrace::integrator::Strategy;
use pathtrace::light::Emission;
use pathtrace::material::{Dielectric, Lambertian, Material};
use pathtrace::math::{Rgb, Transform, Vec3};
use pathtrace::sampling::SamplerKind;
use pathtrace::shape::{Quad, Shape, Sphere};
use pathtrace::{render, AdaptiveSettings, CameraDesc, RenderSettings, Scene, SceneBuilder};
use std::sync::Arc;

fn scene() -> Arc<Scene> {
    let mut b = SceneBuilder::new();
    let white = b.material(Material::Lambertian(Lambertian { albedo: Rgb::splat(0.7) }));
    let glass = b.material(Material::Dielectric(Dielectric { ior: 1.5, tint: Rgb::WHITE }));
    let light = b.emissive(Emission { radiance: Rgb::splat(10.0), two_sided: false });
    let floor = Quad::new(Vec3::new(-5.0, 0.0, -5.0), Vec3::new(0.0, 0.0, 10.0), Vec3::new(10.0, 0.0, 0.0)).unwrap();
    b.shape(Shape::Quad(floor), white, &Transform::IDENTITY).unwrap();
    b.shape(Shape::Sphere(Sphere::new(Vec3::new(0.0, 1.0, 0.0), 1.0).unwrap()), glass, &Transform::IDENTITY).unwrap();
    let lamp = Quad::new(Vec3::new(-1.0, 4.0, -1.0), Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 2.0)).unwrap();
    b.shape(Shape::Quad(lamp), light, &Transform::IDENTITY).unwrap();
    b.camera(CameraDesc {
        look_from: Vec3::new(0.0, 2.0, -6.0),
        look_at: Vec3::new(0.0, 1.0, 0.0),
        ..Default::default()
    });
    Arc::new(b.build().unwrap())
}

#[test]
fn one_and_two_threads_give_bit_identical_films() {
    for (strategy, sampler) in [
        (Strategy::Mis, SamplerKind::Independent),
        (Strategy::Mixture, SamplerKind::Stratified),
        (Strategy::Bsdf, SamplerKind::Sobol),
    ] {
        let mut s =
            RenderSettings { width: 40, height: 30, spp: 19, seed: 5, sampler, tile_size: 7, ..Default::default() };
        s.path.strategy = strategy;
        let one = render(scene(), RenderSettings { threads: 1, ..s.clone() }).unwrap().film;
        let two = render(scene(), RenderSettings { threads: 2, ..s.clone() }).unwrap().film;
        assert_eq!(one, two, "{strategy}/{sampler}");
        // And a different seed does change the image.
        let other = render(scene(), RenderSettings { threads: 2, seed: 6, ..s }).unwrap().film;
        assert_ne!(one, other);
    }
}

#[test]
fn adaptive_renders_are_bit_identical_for_one_and_two_threads() {
    for sampler in [SamplerKind::Independent, SamplerKind::Sobol] {
        let s = RenderSettings {
            width: 40,
            height: 30,
            spp: 24,
            seed: 5,
            sampler,
            tile_size: 7,
            adaptive: Some(AdaptiveSettings { min_spp: 4, ..Default::default() }),
            ..Default::default()
        };
        let one = render(scene(), RenderSettings { threads: 1, ..s.clone() }).unwrap().film;
        let two = render(scene(), RenderSettings { threads: 2, ..s.clone() }).unwrap().film;
        assert_eq!(one, two, "{sampler}");
        // Adaptation happened: pixels hold different counts, 24 on average.
        let (lo, hi) = one.spp_range();
        assert!(lo >= 4 && hi > 24, "{lo}..{hi}");
        assert_eq!(one.total_samples() + one.dropped_samples, 40 * 30 * 24);
    }
}
