//! Textured materials in full renders: a checkerboard-textured Lambertian square filling the
//! frame under a uniform white sky reflects exactly its albedo (∫ ρ/π · 1 · cos dω = ρ), so the
//! image mean is the texture's mean albedo and each check shows its own colour; and binding a
//! constant texture equal to a material's colour changes nothing, for every material model.

use pathtrace::film::PixelFilter;
use pathtrace::light::EnvironmentLight;
use pathtrace::material::{
    Conductor, Dielectric, Diffuse, Glossy, Lambertian, Material, Microfacet, MicrofacetKind, Mirror, Plastic,
    RoughConductor, RoughPlastic,
};
use pathtrace::math::{Rgb, Transform, Vec2, Vec3};
use pathtrace::shape::{Quad, Shape, Sphere};
use pathtrace::texture::{Checkerboard, ColourSlot, Texture, UvTransform};
use pathtrace::{render, CameraDesc, RenderSettings, SceneBuilder};
use std::sync::Arc;

const SIZE: u32 = 32;

/// The square [-1, 1]² in z = 0 (uv = ((x+1)/2, (y+1)/2)) seen from (0, 0, 1) with a 90° fov:
/// it fills the frame exactly, one uv unit per 32 pixels.
fn square_scene(material: Material, texture: Option<(ColourSlot, Texture)>) -> pathtrace::Scene {
    let mut b = SceneBuilder::new();
    let m = b.material(material);
    if let Some((slot, t)) = texture {
        let t = b.texture(t);
        b.bind_texture(m, slot, t).unwrap();
    }
    let quad = Quad::new(Vec3::new(-1.0, -1.0, 0.0), Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0)).unwrap();
    b.shape(Shape::Quad(quad), m, &Transform::IDENTITY).unwrap();
    b.environment(EnvironmentLight::constant(Rgb::WHITE)).unwrap();
    b.camera(CameraDesc {
        look_from: Vec3::new(0.0, 0.0, 1.0),
        look_at: Vec3::ZERO,
        up: Vec3::Y,
        vfov_degrees: 90.0,
        focal_length: 1.0,
        ..Default::default()
    });
    b.build().unwrap()
}

fn settings(spp: u32) -> RenderSettings {
    let mut s = RenderSettings { width: SIZE, height: SIZE, spp, seed: 3, ..Default::default() };
    // The pixel itself only, so no sample strays past the square's edge.
    s.filter = PixelFilter::with_radius("box", 0.5).unwrap();
    s.path.max_depth = -1;
    s
}

#[test]
fn textured_lambertian_under_a_white_sky_shows_its_mean_albedo() {
    let (c0, c1) = (Rgb::new(0.8, 0.2, 0.5), Rgb::new(0.2, 0.6, 0.1));
    // Scale 4: 4×4 periods of 2×2 checks over the square, 4×4 pixels per check.
    let board = Checkerboard { color0: c0, color1: c1, to_uv: UvTransform::scale(Vec2::splat(4.0)) };
    let mean_albedo = board.mean();
    let material = Material::Lambertian(Lambertian { albedo: mean_albedo });
    let scene = square_scene(material, Some((ColourSlot::Base, Texture::Checkerboard(board))));
    let out = render(Arc::new(scene), settings(64)).unwrap();
    let est = out.film.region_estimate(0, 0, SIZE, SIZE);
    let expected = mean_albedo.to_array().map(f64::from);
    let z = est.max_z_score_against(expected);
    eprintln!("mean {:.5?} ± {:.5?}, texture mean {expected:.5?}", est.mean, est.variance_of_mean.map(f64::sqrt));
    assert!(z < 4.5, "mean {:?} vs {expected:?} (z = {z:.2})", est.mean);
    assert!(est.variance_of_mean[0].sqrt() < 0.002, "too noisy to judge");
    // Pixel (1, 30) is near uv (0.05, 0.05), in a color0 check; (5, 30) near (0.17, 0.05),
    // in a color1 check.
    for (x, colour) in [(1, c0), (5, c1)] {
        let p = out.film.region_estimate(x, 30, x + 1, 31);
        let z = p.max_z_score_against(colour.to_array().map(f64::from));
        assert!(z < 4.5, "pixel ({x}, 30): {:?} vs {colour:?}", p.mean);
    }
}

#[test]
fn a_constant_texture_equal_to_the_colour_changes_nothing() {
    let c = Rgb::new(0.7, 0.4, 0.2);
    let ggx = Microfacet::new(MicrofacetKind::Ggx, 0.3, 0.3);
    let models = [
        (Material::Diffuse(Diffuse { albedo: c }), ColourSlot::Base),
        (Material::Lambertian(Lambertian { albedo: c }), ColourSlot::Base),
        (Material::Glossy(Glossy { albedo: c, exponent: 20.0 }), ColourSlot::Base),
        (Material::Mirror(Mirror { reflectance: c }), ColourSlot::Base),
        (Material::Dielectric(Dielectric { ior: 1.5, tint: c }), ColourSlot::Base),
        (Material::Conductor(Conductor { eta: Rgb::splat(0.2), k: Rgb::splat(3.0), reflectance: c }), ColourSlot::Base),
        (
            Material::RoughConductor(RoughConductor {
                distribution: ggx,
                eta: Rgb::splat(0.2),
                k: Rgb::splat(3.0),
                reflectance: c,
            }),
            ColourSlot::Base,
        ),
        (Material::Plastic(Plastic::new(c, Rgb::splat(0.9), 1.5, false)), ColourSlot::Base),
        (Material::Plastic(Plastic::new(Rgb::splat(0.5), c, 1.5, true)), ColourSlot::Specular),
        (Material::RoughPlastic(RoughPlastic::new(ggx, c, Rgb::WHITE, 1.5, true)), ColourSlot::Base),
    ];
    for (m, slot) in models {
        let plain = render(Arc::new(square_scene(m, None)), settings(4)).unwrap().film.image();
        let textured =
            render(Arc::new(square_scene(m, Some((slot, Texture::Constant(c))))), settings(4)).unwrap().film.image();
        assert!(plain.pixels == textured.pixels, "{}: a constant texture changed the image", m.name());
    }
}

#[test]
fn textures_bind_only_to_slots_a_material_has() {
    let mut b = SceneBuilder::new();
    let lambert = b.material(Material::Lambertian(Lambertian { albedo: Rgb::splat(0.5) }));
    let t = b.texture(Texture::Constant(Rgb::splat(0.5)));
    assert!(b.bind_texture(lambert, ColourSlot::Specular, t).is_err());
    assert!(b.bind_texture(lambert, ColourSlot::Base, pathtrace::texture::TextureId(7)).is_err());
    b.bind_texture(lambert, ColourSlot::Base, t).unwrap();
    b.shape(Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0).unwrap()), lambert, &Transform::IDENTITY).unwrap();
}
