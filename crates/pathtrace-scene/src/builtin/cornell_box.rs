//! The classic Cornell box in its 555-unit form (as in "Ray Tracing: The Next Week"): red and
//! green side walls, white floor, ceiling and back wall, a 130 × 105 area light of radiance 15
//! just below the ceiling, and two white boxes rotated about y.

use crate::{LoadedScene, RenderDefaults};
use pathtrace::light::Emission;
use pathtrace::material::{Lambertian, Material};
use pathtrace::math::{Rgb, Transform, Vec3};
use pathtrace::scene::BuildError;
use pathtrace::shape::{Quad, Shape};
use pathtrace::{CameraDesc, SceneBuilder};

fn quad(q: [f32; 3], u: [f32; 3], v: [f32; 3]) -> Result<Shape, BuildError> {
    Quad::new(Vec3::from(q), Vec3::from(u), Vec3::from(v)).map(Shape::Quad).ok_or(BuildError::Degenerate("quad"))
}

pub(super) fn build() -> Result<LoadedScene, BuildError> {
    let mut b = SceneBuilder::new();
    let lambert = |r, g, bl| Material::Lambertian(Lambertian { albedo: Rgb::new(r, g, bl) });
    let red = b.material(lambert(0.65, 0.05, 0.05));
    let white = b.material(lambert(0.73, 0.73, 0.73));
    let green = b.material(lambert(0.12, 0.45, 0.15));
    let light = b.emissive(Emission { radiance: Rgb::splat(15.0), two_sided: false });
    let id = Transform::IDENTITY;

    b.shape(quad([555.0, 0.0, 0.0], [0.0, 555.0, 0.0], [0.0, 0.0, 555.0])?, green, &id)?;
    b.shape(quad([0.0, 0.0, 0.0], [0.0, 555.0, 0.0], [0.0, 0.0, 555.0])?, red, &id)?;
    // The light's u × v = (0, -13650, 0): it faces down into the box.
    b.shape(quad([343.0, 554.0, 332.0], [-130.0, 0.0, 0.0], [0.0, 0.0, -105.0])?, light, &id)?;
    b.shape(quad([0.0, 0.0, 0.0], [555.0, 0.0, 0.0], [0.0, 0.0, 555.0])?, white, &id)?;
    b.shape(quad([555.0, 555.0, 555.0], [-555.0, 0.0, 0.0], [0.0, 0.0, -555.0])?, white, &id)?;
    b.shape(quad([0.0, 0.0, 555.0], [555.0, 0.0, 0.0], [0.0, 555.0, 0.0])?, white, &id)?;

    let tall = Transform::rotate_y(15.0).then(&Transform::translate(Vec3::new(265.0, 0.0, 295.0)));
    b.add_box(Vec3::ZERO, Vec3::new(165.0, 330.0, 165.0), white, &tall)?;
    let short = Transform::rotate_y(-18.0).then(&Transform::translate(Vec3::new(130.0, 0.0, 65.0)));
    b.add_box(Vec3::ZERO, Vec3::splat(165.0), white, &short)?;

    b.camera(CameraDesc {
        look_from: Vec3::new(278.0, 278.0, -800.0),
        look_at: Vec3::new(278.0, 278.0, 0.0),
        up: Vec3::Y,
        vfov_degrees: 40.0,
        focal_length: 1.0,
    });
    Ok(LoadedScene { scene: b.build()?, defaults: RenderDefaults { width: 512, height: 512, spp: 256, max_depth: -1 } })
}
