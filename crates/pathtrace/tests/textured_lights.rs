//! Emissive meshes whose radiance is a texture (`SceneBuilder::set_emission_texture`): a light
//! sample carries the radiance a ray hitting the same point sees (the sampled point's uv found
//! from its place on the triangle agrees with the hit's interpolated uv); light sampling and
//! direction sampling estimate the same irradiance (the textured light is sampled uniformly by
//! area, which stays unbiased); power-based selection weighs the texture's mean; only meshes and
//! quads may carry such a light. Each is checked on a mesh panel and on a quad panel.

use pathtrace::light::{Emission, Light};
use pathtrace::material::{Lambertian, Material};
use pathtrace::math::{Frame, Ray, Rgb, Transform, Vec2, Vec3};
use pathtrace::sampling::warp;
use pathtrace::shape::{Quad, Shape, Sphere, TriangleMesh};
use pathtrace::texture::{Bitmap, Texture};
use pathtrace::{Scene, SceneBuilder};
use pathtrace_testkit::TestRng;

/// A 4 × 4 image of strongly varying colours (one black texel).
fn image() -> Bitmap {
    let texels = (0..16)
        .map(|i| {
            let f = i as f32 / 15.0;
            if i == 5 {
                Rgb::BLACK
            } else {
                Rgb::new(0.2 + f, 1.5 * (1.0 - f) + 0.1, if i % 3 == 0 { 2.0 } else { 0.3 })
            }
        })
        .collect();
    Bitmap::new(4, 4, texels).unwrap()
}

/// A floor and a tilted emissive panel whose radiance is `scale` × the image: two triangles with
/// uvs not aligned with the edges, or (`quad`) a quad shape, whose uv is its (a, b).
fn scene(scale: Rgb, quad: bool) -> Scene {
    let mut b = SceneBuilder::new();
    let floor = b.material(Material::Lambertian(Lambertian { albedo: Rgb::splat(0.5) }));
    let lamp = b.material_with_emission(Material::Black, Emission { radiance: scale, two_sided: false });
    let t = b.texture(Texture::Bitmap(image()));
    b.set_emission_texture(lamp, t).unwrap();
    let floor_mesh = TriangleMesh {
        positions: vec![Vec3::new(-3.0, 0.0, -3.0), Vec3::new(3.0, 0.0, -3.0), Vec3::new(3.0, 0.0, 3.0)],
        indices: vec![[0, 2, 1]],
        normals: None,
        uvs: None,
        tangents: None,
    };
    b.mesh(&floor_mesh, floor, &Transform::IDENTITY).unwrap();
    let panel = TriangleMesh {
        positions: vec![
            Vec3::new(-1.0, 0.5, 1.0),
            Vec3::new(1.0, 0.3, 1.2),
            Vec3::new(1.0, 1.8, 0.7),
            Vec3::new(-1.0, 1.6, 0.5),
        ],
        // Facing −z, towards the reference points.
        indices: vec![[0, 2, 1], [0, 3, 2]],
        normals: None,
        uvs: Some(vec![Vec2::new(0.1, 0.9), Vec2::new(1.3, 0.8), Vec2::new(1.1, -0.2), Vec2::new(0.0, 0.05)]),
        tangents: None,
    };
    if quad {
        // Facing −z and a little down (u × v), towards the reference points.
        let q = Quad::new(Vec3::new(-1.0, 0.5, 1.0), Vec3::new(0.0, 1.1, -0.5), Vec3::new(2.0, -0.2, 0.2)).unwrap();
        b.shape(Shape::Quad(q), lamp, &Transform::IDENTITY).unwrap();
    } else {
        b.mesh(&panel, lamp, &Transform::IDENTITY).unwrap();
    }
    b.build().unwrap()
}

#[test]
fn a_light_sample_carries_the_radiance_a_ray_sees_there() {
    for quad in [false, true] {
        a_light_sample_carries_the_radiance_a_ray_sees_there_on(quad);
    }
}

fn a_light_sample_carries_the_radiance_a_ray_sees_there_on(quad: bool) {
    let s = scene(Rgb::new(2.0, 1.0, 3.0), quad);
    let mut rng = TestRng::new(11);
    let mut checked = 0;
    for _ in 0..2000 {
        let p = Vec3::new(rng.next_f32() * 2.0 - 1.0, 0.05 + rng.next_f32(), -1.5 + rng.next_f32());
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        let Some(ls) = s.lights.sample(p, rng.next_f32(), u) else { continue };
        let ray = Ray::new(p, ls.wi);
        let hit = s.intersect(&ray, f32::INFINITY).expect("the sampled point is hit");
        let it = s.interaction(&ray, &hit);
        let light = s.lights.get(it.light).expect("an emitter");
        let seen = light.emitted(it.surface.n_geometric, -ls.wi, it.surface.uv);
        let diff = seen.to_array().iter().zip(ls.radiance.to_array()).map(|(a, b)| (a - b).abs()).fold(0.0, f32::max);
        assert!(diff <= 1e-3 * seen.max_component().max(1e-3), "{seen:?} vs {:?}", ls.radiance);
        checked += 1;
    }
    assert!(checked > 1500, "{checked}");
}

#[test]
fn light_sampling_and_direction_sampling_estimate_the_same_irradiance() {
    for quad in [false, true] {
        light_sampling_and_direction_sampling_estimate_the_same_irradiance_on(quad);
    }
}

fn light_sampling_and_direction_sampling_estimate_the_same_irradiance_on(quad: bool) {
    let s = scene(Rgb::new(2.0, 1.0, 3.0), quad);
    let p = Vec3::new(0.1, 0.2, -1.0);
    let n = Vec3::new(0.0, 0.3, 1.0).normalize();
    let frame = Frame::from_normal(n);
    let n_samples = 400_000;
    let mut rng = TestRng::new(5);
    // E = ∫ L cos θ dω, by light sampling: L cos θ / pdf.
    let mut by_light = [0.0f64; 3];
    let rgb = |c: Rgb, w: f64, acc: &mut [f64; 3]| {
        for (a, v) in acc.iter_mut().zip(c.to_array()) {
            *a += v as f64 * w;
        }
    };
    for _ in 0..n_samples {
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        let Some(ls) = s.lights.sample(p, rng.next_f32(), u) else { continue };
        let cos = n.dot(ls.wi);
        if cos <= 0.0 {
            continue;
        }
        let blocked = s.intersect(&Ray::new(p, ls.wi), ls.dist * 0.999).is_some();
        if !blocked {
            rgb(ls.radiance, (cos / ls.pdf) as f64, &mut by_light);
        }
    }
    // By cosine-weighted directions and what they hit: L cos θ / (cos θ / π) = π L.
    let mut by_direction = [0.0f64; 3];
    for _ in 0..n_samples {
        let wi = frame.to_world(warp::square_to_cosine_hemisphere(Vec2::new(rng.next_f32(), rng.next_f32())));
        let ray = Ray::new(p, wi);
        let Some(hit) = s.intersect(&ray, f32::INFINITY) else { continue };
        let it = s.interaction(&ray, &hit);
        if let Some(light) = s.lights.get(it.light) {
            rgb(light.emitted(it.surface.n_geometric, -wi, it.surface.uv), std::f64::consts::PI, &mut by_direction);
        }
    }
    for k in 0..3 {
        let (a, b) = (by_light[k] / n_samples as f64, by_direction[k] / n_samples as f64);
        assert!(a > 0.05, "channel {k}: {a}");
        assert!((a - b).abs() < 0.02 * b, "channel {k}: light sampling {a} vs direction sampling {b}");
    }
}

#[test]
fn selection_power_uses_the_texture_mean_and_only_meshes_and_quads_take_a_texture() {
    let mean = image().mean() * Rgb::new(2.0, 1.0, 3.0);
    for quad in [false, true] {
        let s = scene(Rgb::new(2.0, 1.0, 3.0), quad);
        for light in s.lights.lights() {
            let Light::Area(l) = light else { continue };
            let expected = mean.luminance_f64() * l.area() as f64 * std::f64::consts::PI;
            assert!((l.power() / expected - 1.0).abs() < 1e-5, "{} vs {expected}", l.power());
            assert!(l.texture().is_some());
        }
    }
    // A sphere cannot carry a radiance texture.
    let mut b = SceneBuilder::new();
    let lamp = b.material_with_emission(Material::Black, Emission { radiance: Rgb::WHITE, two_sided: false });
    let t = b.texture(Texture::Bitmap(image()));
    b.set_emission_texture(lamp, t).unwrap();
    b.shape(Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0).unwrap()), lamp, &Transform::IDENTITY).unwrap();
    let e = b.build().expect_err("an error").to_string();
    assert!(e.contains("meshes and quads only"), "{e}");
    // Nor can a material that does not emit.
    let mut b = SceneBuilder::new();
    let grey = b.material(Material::Lambertian(Lambertian { albedo: Rgb::splat(0.5) }));
    let t = b.texture(Texture::Bitmap(image()));
    assert!(b.set_emission_texture(grey, t).is_err());
}
