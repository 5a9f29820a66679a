//! The estimator in groups of SIMD lanes (`Kernel::Wide`) against its one-lane instance
//! (`Kernel::Scalar`) at many samples per pixel (samples of a pixel finish in a different
//! order): the same images within confidence intervals, for both intersectors (brute force
//! over a small scene's polygons, the BVH for larger ones), every sampler, quad and triangle
//! lights; and a furnace with a known answer. (At one sample per pixel the two are
//! bit-identical: `pathtrace-scene/tests/lanes_exact.rs`.)

use pathtrace::integrator::Strategy;
use pathtrace::light::Emission;
use pathtrace::material::{Lambertian, Material};
use pathtrace::math::{Rgb, Transform, Vec3};
use pathtrace::sampling::SamplerKind;
use pathtrace::shape::{Quad, Shape, TriangleMesh};
use pathtrace::wide::{Kernel, WideScene, MAX_FLAT_POLYGONS};
use pathtrace::{render, CameraDesc, RenderSettings, Scene, SceneBuilder};
use std::sync::Arc;

fn lambertian(r: f32, g: f32, b: f32) -> Material {
    Material::Lambertian(Lambertian { albedo: Rgb::new(r, g, b) })
}

/// A quad split into `n × n` smaller quads, as a triangle mesh (two triangles each).
fn subdivided(quads: &[Quad], n: u32) -> TriangleMesh {
    let mut mesh =
        TriangleMesh { positions: Vec::new(), indices: Vec::new(), normals: None, uvs: None, tangents: None };
    for q in quads {
        let base = mesh.positions.len() as u32;
        for j in 0..=n {
            for i in 0..=n {
                mesh.positions.push(q.point_at(i as f32 / n as f32, j as f32 / n as f32));
            }
        }
        let at = |i: u32, j: u32| base + j * (n + 1) + i;
        for j in 0..n {
            for i in 0..n {
                // Counter-clockwise seen from the front (along u × v), like the quad.
                mesh.indices.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                mesh.indices.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
    }
    mesh
}

/// The Cornell box of `scenes/cornell-box.toml` in unit size. With `meshes`, the two boxes are
/// subdivided triangle meshes (too many polygons for brute force: the wide kernel uses the
/// BVH) and the light is a two-triangle emissive mesh (two triangle lights).
fn cornell(meshes: bool) -> Scene {
    let mut b = SceneBuilder::new();
    let red = b.material(lambertian(0.65, 0.05, 0.05));
    let white = b.material(lambertian(0.73, 0.73, 0.73));
    let green = b.material(lambertian(0.12, 0.45, 0.15));
    let light = b.emissive(Emission { radiance: Rgb::splat(15.0), two_sided: false });
    let s = 1.0 / 555.0;
    let v = |x: f32, y: f32, z: f32| Vec3::new(x, y, z) * s;
    let mut quad = |q: Vec3, u: Vec3, w: Vec3, m| {
        b.shape(Shape::Quad(Quad::new(q, u, w).unwrap()), m, &Transform::IDENTITY).unwrap();
    };
    quad(v(555.0, 0.0, 0.0), v(0.0, 555.0, 0.0), v(0.0, 0.0, 555.0), green);
    quad(v(0.0, 0.0, 0.0), v(0.0, 555.0, 0.0), v(0.0, 0.0, 555.0), red);
    quad(v(0.0, 0.0, 0.0), v(555.0, 0.0, 0.0), v(0.0, 0.0, 555.0), white);
    quad(v(555.0, 555.0, 555.0), v(-555.0, 0.0, 0.0), v(0.0, 0.0, -555.0), white);
    quad(v(0.0, 0.0, 555.0), v(555.0, 0.0, 0.0), v(0.0, 555.0, 0.0), white);
    let lamp = Quad::new(v(343.0, 554.0, 332.0), v(-130.0, 0.0, 0.0), v(0.0, 0.0, -105.0)).unwrap();
    if meshes {
        b.mesh(&subdivided(&[lamp], 1), light, &Transform::IDENTITY).unwrap();
    } else {
        b.shape(Shape::Quad(lamp), light, &Transform::IDENTITY).unwrap();
    }
    let boxes =
        [(v(165.0, 330.0, 165.0), 15.0, v(265.0, 0.0, 295.0)), (v(165.0, 165.0, 165.0), -18.0, v(130.0, 0.0, 65.0))];
    for (size, angle, at) in boxes {
        let place = Transform::rotate_y(angle).then(&Transform::translate(at));
        let faces = Quad::box_faces(Vec3::ZERO, size, &place).unwrap();
        if meshes {
            b.mesh(&subdivided(&faces, 3), white, &Transform::IDENTITY).unwrap();
        } else {
            for f in faces {
                b.shape(Shape::Quad(f), white, &Transform::IDENTITY).unwrap();
            }
        }
    }
    b.camera(CameraDesc {
        look_from: v(278.0, 278.0, -800.0),
        look_at: v(278.0, 278.0, 0.0),
        up: Vec3::Y,
        vfov_degrees: 40.0,
        focal_length: 1.0,
        ..Default::default()
    });
    b.build().unwrap()
}

fn settings(kernel: Kernel, sampler: SamplerKind, size: u32, spp: u32, seed: u64) -> RenderSettings {
    let mut s = RenderSettings { width: size, height: size, spp, seed, sampler, kernel, ..Default::default() };
    s.path.max_depth = 8;
    s
}

/// Renders `scene` with both kernels and compares the whole image and 4×4-pixel blocks.
fn assert_kernels_agree(scene: Scene, sampler: SamplerKind, spp: u32) {
    let scene = Arc::new(scene);
    let size = 32;
    let wide = render(Arc::clone(&scene), settings(Kernel::Wide, sampler, size, spp, 5)).unwrap();
    let scalar = render(scene, settings(Kernel::Scalar, sampler, size, spp, 6)).unwrap();
    assert_eq!(wide.progress.dropped_samples + scalar.progress.dropped_samples, 0);
    let (w, s) = (&wide.film, &scalar.film);
    let (whole, worst) = z_scores(w, s, size);
    assert!(whole < 4.0, "{sampler}: image means differ, z = {whole:.2}");
    // 64 blocks × 3 channels: max |z| < 4.5 has p ≈ 1e-3 under agreement.
    assert!(worst < 4.5, "{sampler}: a block differs, z = {worst:.2}");
    // The comparison must be sharp enough to see a 2% bias on the image mean.
    let est = w.region_estimate(0, 0, size, size);
    assert!(est.variance_of_mean[0].sqrt() < 0.01 * est.mean[0], "too noisy to judge: {est:?}");
    // Same ray bookkeeping: one camera ray per sample.
    assert_eq!(wide.progress.rays.camera_rays, (size * size * spp) as u64);
}

#[test]
fn small_scenes_are_intersected_by_brute_force_and_larger_ones_by_the_bvh() {
    let settings = settings(Kernel::Wide, SamplerKind::Independent, 8, 1, 0).path;
    assert!(WideScene::new(&cornell(false), &settings).brute_force());
    let meshes = cornell(true);
    assert!(!WideScene::new(&meshes, &settings).brute_force(), "> {MAX_FLAT_POLYGONS} polygons");
}

/// An octahedron subdivided once onto the unit sphere (32 triangles, outward), with the
/// sphere's normals at its vertices when `smooth`.
fn ball(smooth: bool) -> TriangleMesh {
    let mut triangles = Vec::new();
    for corner in 0..8 {
        let s = |bit: u32| if corner >> bit & 1 == 0 { 1.0 } else { -1.0 };
        let (x, y, z) = (Vec3::X * s(0), Vec3::Y * s(1), Vec3::Z * s(2));
        // Counter-clockwise seen from outside: (x, y, z) is when the octant's signs multiply to +1.
        let (a, b, c) = if s(0) * s(1) * s(2) > 0.0 { (x, y, z) } else { (x, z, y) };
        let (ab, bc, ca) = ((a + b).normalize(), (b + c).normalize(), (c + a).normalize());
        triangles.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
    }
    let positions: Vec<Vec3> = triangles.iter().flatten().copied().collect();
    TriangleMesh {
        indices: (0..triangles.len() as u32).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect(),
        normals: smooth.then(|| positions.clone()),
        positions,
        uvs: None,
        tangents: None,
    }
}

/// The ball on a floor under a quad light, and `specks` tiny quads far below the floor (which
/// no path meets in practice; they only make the scene too large for brute force).
fn ball_scene(smooth: bool, specks: u32) -> Scene {
    let mut b = SceneBuilder::new();
    let white = b.material(lambertian(0.8, 0.8, 0.8));
    let grey = b.material(lambertian(0.5, 0.5, 0.5));
    let light = b.emissive(Emission { radiance: Rgb::splat(10.0), two_sided: false });
    b.mesh(&ball(smooth), white, &Transform::scale(Vec3::splat(0.5)).unwrap()).unwrap();
    let mut quad = |q: Vec3, u: Vec3, v: Vec3, m| {
        b.shape(Shape::Quad(Quad::new(q, u, v).unwrap()), m, &Transform::IDENTITY).unwrap();
    };
    quad(Vec3::new(-2.0, -0.5, -2.0), Vec3::Z * 4.0, Vec3::X * 4.0, grey);
    quad(Vec3::new(-0.5, 2.0, -0.5), Vec3::X, Vec3::Z, light);
    for k in 0..specks {
        quad(Vec3::new(0.01 * k as f32, -100.0, 0.0), Vec3::X * 1e-3, Vec3::Z * 1e-3, grey);
    }
    b.camera(CameraDesc {
        look_from: Vec3::new(0.0, 0.8, 2.5),
        look_at: Vec3::ZERO,
        up: Vec3::Y,
        vfov_degrees: 30.0,
        focal_length: 1.0,
        ..Default::default()
    });
    b.build().unwrap()
}

/// Largest z-score of two films' means over the whole image and over its 4×4-pixel blocks.
fn z_scores(a: &pathtrace::film::Film, b: &pathtrace::film::Film, size: u32) -> (f64, f64) {
    let whole = a.region_estimate(0, 0, size, size).max_z_score(&b.region_estimate(0, 0, size, size));
    let mut worst = 0.0f64;
    for y0 in (0..size).step_by(4) {
        for x0 in (0..size).step_by(4) {
            let z = a.region_estimate(x0, y0, x0 + 4, y0 + 4).max_z_score(&b.region_estimate(x0, y0, x0 + 4, y0 + 4));
            worst = worst.max(z);
        }
    }
    (whole, worst)
}

/// A small scene with a smooth-shaded mesh takes the brute-force intersector, whose hits
/// interpolate the mesh's vertex normals as the BVH's do: the same image as the scene made
/// too large for brute force, and not the faceted ball's.
#[test]
fn brute_force_interpolates_vertex_normals_as_the_bvh_does() {
    let path = settings(Kernel::Wide, SamplerKind::Independent, 8, 1, 0).path;
    let small = ball_scene(true, 0);
    let polygons = 32 + 2;
    let specked = ball_scene(true, MAX_FLAT_POLYGONS as u32 + 1 - polygons);
    assert!(WideScene::new(&small, &path).brute_force());
    assert!(!WideScene::new(&specked, &path).brute_force());
    let size = 32;
    let film = |scene: Scene, seed| {
        render(Arc::new(scene), settings(Kernel::Wide, SamplerKind::Independent, size, 256, seed)).unwrap().film
    };
    let (brute, bvh, faceted) = (film(small, 1), film(specked, 2), film(ball_scene(false, 0), 3));
    let (whole, worst) = z_scores(&brute, &bvh, size);
    assert!(whole < 4.0 && worst < 4.5, "brute force vs BVH: z = {whole:.2} (image), {worst:.2} (block)");
    let (_, faceted) = z_scores(&brute, &faceted, size);
    assert!(faceted > 8.0, "the comparison must tell smooth from faceted shading: block z = {faceted:.2}");
}

#[test]
fn wide_and_scalar_kernels_render_the_same_cornell_box() {
    assert_kernels_agree(cornell(false), SamplerKind::Independent, 512);
}

#[test]
fn wide_kernel_keeps_the_samplers_dimensions() {
    // Stratified and Sobol samples are only well distributed if each dimension is used for the
    // same decision in every sample: a mismatch would show as disagreement or bias.
    assert_kernels_agree(cornell(false), SamplerKind::Stratified, 256);
    assert_kernels_agree(cornell(false), SamplerKind::Sobol, 256);
}

#[test]
fn wide_kernel_through_the_bvh_with_triangle_lights_matches_the_scalar_kernel() {
    assert_kernels_agree(cornell(true), SamplerKind::Independent, 512);
}

#[test]
fn wide_kernel_renders_the_same_image_on_any_number_of_threads() {
    let scene = Arc::new(cornell(false));
    let mut one = settings(Kernel::Wide, SamplerKind::Independent, 24, 8, 3);
    one.threads = 1;
    let two = RenderSettings { threads: 2, ..one.clone() };
    let a = render(Arc::clone(&scene), one).unwrap().film.image();
    let b = render(scene, two).unwrap().film.image();
    assert!(a.pixels == b.pixels, "images differ between 1 and 2 threads");
}

/// A closed box whose six walls (each split into `n × n` quads) emit E from both faces and
/// reflect with albedo a: the radiance is E / (1 − a) everywhere.
fn furnace_box(n: u32, albedo: f32, emission: f32) -> Scene {
    let mut b = SceneBuilder::new();
    let wall = b.material_with_emission(
        lambertian(albedo, albedo, albedo),
        Emission { radiance: Rgb::splat(emission), two_sided: true },
    );
    for face in Quad::box_faces(Vec3::splat(-1.0), Vec3::splat(1.0), &Transform::IDENTITY).unwrap() {
        for j in 0..n {
            for i in 0..n {
                let (u, v) = (face.u / n as f32, face.v / n as f32);
                let q = face.q + u * i as f32 + v * j as f32;
                b.shape(Shape::Quad(Quad::new(q, u, v).unwrap()), wall, &Transform::IDENTITY).unwrap();
            }
        }
    }
    b.camera(CameraDesc {
        look_from: Vec3::new(0.1, 0.2, 0.3),
        look_at: Vec3::new(1.0, 0.0, 0.0),
        up: Vec3::Y,
        vfov_degrees: 90.0,
        focal_length: 1.0,
        ..Default::default()
    });
    b.build().unwrap()
}

#[test]
fn wide_kernel_passes_the_furnace_test_with_either_intersector() {
    let (albedo, emission) = (0.6f32, 0.5f32);
    let expected = (emission / (1.0 - albedo)) as f64;
    for n in [1, 4] {
        let scene = furnace_box(n, albedo, emission);
        let path = settings(Kernel::Wide, SamplerKind::Independent, 8, 1, 0).path;
        let mut s = settings(Kernel::Wide, SamplerKind::Independent, 24, 256, 7);
        s.path.max_depth = -1;
        assert_eq!(WideScene::new(&scene, &path).brute_force(), 6 * n * n <= MAX_FLAT_POLYGONS as u32);
        for strategy in [Strategy::Mis, Strategy::MisBalance] {
            s.path.strategy = strategy;
            let out = render(Arc::new(furnace_box(n, albedo, emission)), s.clone()).unwrap();
            let est = out.film.region_estimate(0, 0, 24, 24);
            let z = est.max_z_score_against([expected; 3]);
            assert!(z < 4.5, "{n}×{n} walls, {strategy}: mean {:?} vs E/(1-a) = {expected}, z = {z:.2}", est.mean);
            assert!(est.variance_of_mean[0].sqrt() < 0.02 * expected, "too noisy to judge");
        }
    }
}
