//! Shading frames. Anisotropic roughness follows ∂p/∂u (from texture coordinates on meshes,
//! from the parameterisation on spheres), so it turns with the object: a scene rotated as a
//! whole renders the same image. Meshes without texture coordinates take Mitsuba's fallback.
//! Strongly perturbed vertex normals give no NaNs and no energy gain.

use pathtrace::light::{Emission, EnvironmentLight};
use pathtrace::material::{Lambertian, Material, Microfacet, MicrofacetKind, RoughConductor};
use pathtrace::math::{Frame, Ray, Rgb, Transform, Vec2, Vec3};
use pathtrace::shape::{Quad, Shape, Sphere, TriangleMesh};
use pathtrace::{render, CameraDesc, RenderSettings, SceneBuilder};
use pathtrace_testkit::TestRng;
use std::sync::Arc;

/// A 4×4 square in the xz-plane (normal +y) whose u axis runs at 30° from +x.
fn square(uvs: bool) -> TriangleMesh {
    let positions = vec![
        Vec3::new(-2.0, 0.0, -2.0),
        Vec3::new(2.0, 0.0, -2.0),
        Vec3::new(2.0, 0.0, 2.0),
        Vec3::new(-2.0, 0.0, 2.0),
    ];
    let (s, c) = 30f32.to_radians().sin_cos();
    // u = (x cos 30° + z sin 30°)/4, v = (−x sin 30° + z cos 30°)/4: ∂p/∂u ∥ (cos 30°, 0, sin 30°).
    let uv = |p: Vec3| Vec2::new((p.x * c + p.z * s) / 4.0, (-p.x * s + p.z * c) / 4.0);
    let uvs = uvs.then(|| positions.iter().map(|&p| uv(p)).collect());
    TriangleMesh { positions, indices: vec![[0, 2, 1], [0, 3, 2]], normals: None, uvs, tangents: None }
}

fn surface_below(b: SceneBuilder, origin: Vec3) -> pathtrace::shape::SurfacePoint {
    let scene = b.build().unwrap();
    let ray = Ray::new(origin, -Vec3::Y);
    let hit = scene.intersect(&ray, f32::INFINITY).expect("the ray hits the square");
    scene.interaction(&ray, &hit).surface
}

#[test]
fn mesh_tangents_follow_uv_derivatives_and_turn_with_the_mesh() {
    let rot = Transform::rotate_y(47.0).then(&Transform::rotate_x(8.0));
    let expected_local = Vec3::new(30f32.to_radians().cos(), 0.0, 30f32.to_radians().sin());
    for (t, name) in [(Transform::IDENTITY, "unrotated"), (rot, "rotated")] {
        let mut b = SceneBuilder::new();
        b.allow_no_lights(true);
        let m = b.material(Material::Lambertian(Lambertian { albedo: Rgb::splat(0.5) }));
        b.mesh(&square(true), m, &t).unwrap();
        let sp = surface_below(b, t.point(Vec3::new(0.3, 0.0, -0.2)) + Vec3::Y * 3.0);
        let frame = Frame::from_normal_tangent(sp.n_shading, sp.tangent());
        let expected = t.vector(expected_local).normalize();
        assert!((frame.s - expected).length() < 1e-4, "{name}: tangent {} vs {expected}", frame.s);
        assert!((frame.s.cross(frame.t) - frame.n).length() < 1e-4, "{name}: right-handed");
    }
    // Without texture coordinates: the geometric normal's Duff et al. basis (Mitsuba's fallback).
    let mut b = SceneBuilder::new();
    b.allow_no_lights(true);
    let m = b.material(Material::Lambertian(Lambertian { albedo: Rgb::splat(0.5) }));
    b.mesh(&square(false), m, &Transform::IDENTITY).unwrap();
    let sp = surface_below(b, Vec3::new(0.3, 3.0, -0.2));
    assert_eq!(sp.dpdu, Vec3::ZERO);
    assert!((sp.tangent() - Frame::from_normal(sp.n_geometric).s).length() < 1e-6);
}

#[test]
fn sphere_and_quad_tangents_follow_their_parameterisation() {
    // Sphere: u runs around +y; at the point (1, 0, 0) of a unit sphere ∂p/∂u ∥ (0, 0, −1).
    let s = Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0).unwrap());
    let ray = Ray::new(Vec3::new(3.0, 0.0, 0.0), -Vec3::X);
    let sp = s.surface(&ray, &s.intersect(&ray, 0.0, f32::INFINITY).unwrap(), &[]);
    assert!((sp.dpdu.normalize() - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-5, "{}", sp.dpdu);
    // Finite difference of the uv mapping agrees: moving along dpdu increases u.
    let ray2 = Ray::new(Vec3::new(3.0, 0.0, -0.01), -Vec3::X);
    let sp2 = s.surface(&ray2, &s.intersect(&ray2, 0.0, f32::INFINITY).unwrap(), &[]);
    assert!(sp2.uv.x > sp.uv.x, "u grows along dpdu");
    // Quad: ∂p/∂u is its first edge.
    let q = Quad::new(Vec3::new(-1.0, 0.0, -1.0), Vec3::new(2.0, 0.0, 0.5), Vec3::new(0.0, 0.0, 2.0)).unwrap();
    let shape = Shape::Quad(q);
    let ray = Ray::new(Vec3::new(0.1, 2.0, 0.1), -Vec3::Y);
    let sp = shape.surface(&ray, &shape.intersect(&ray, 0.0, f32::INFINITY).unwrap(), &[]);
    assert!((sp.dpdu - Vec3::new(2.0, 0.0, 0.5)).length() < 1e-6);
}

/// An anisotropic rough metal floor (UV-mapped mesh) and sphere under a small lamp, everything —
/// camera included — placed by `t`.
fn anisotropic_scene(t: &Transform, alpha: (f32, f32)) -> Arc<pathtrace::Scene> {
    let mut b = SceneBuilder::new();
    let metal = b.material(Material::RoughConductor(RoughConductor {
        distribution: Microfacet::new(MicrofacetKind::Ggx, alpha.0, alpha.1),
        eta: Rgb::new(0.2, 0.4, 1.4),
        k: Rgb::new(3.9, 2.4, 2.2),
        reflectance: Rgb::WHITE,
    }));
    let lamp = b.emissive(Emission { radiance: Rgb::splat(30.0), two_sided: false });
    b.mesh(&square(true), metal, t).unwrap();
    b.shape(Shape::Sphere(Sphere::new(Vec3::new(0.8, 0.6, 0.6), 0.6).unwrap()), metal, t).unwrap();
    let lamp_quad = Quad::new(Vec3::new(-0.3, 2.5, 1.2), Vec3::new(0.0, 0.0, 0.4), Vec3::new(0.4, 0.0, 0.0)).unwrap();
    b.shape(Shape::Quad(lamp_quad), lamp, t).unwrap();
    b.environment(EnvironmentLight::constant(Rgb::splat(0.1))).unwrap();
    b.camera(CameraDesc {
        look_from: t.point(Vec3::new(0.0, 2.0, -3.0)),
        look_at: t.point(Vec3::new(0.0, 0.0, 0.8)),
        up: t.vector(Vec3::Y),
        ..Default::default()
    });
    Arc::new(b.build().unwrap())
}

fn render_blocks(scene: Arc<pathtrace::Scene>, seed: u64) -> Vec<pathtrace::film::RegionEstimate> {
    let size = 32;
    let mut s = RenderSettings { width: size, height: size, spp: 128, seed, ..Default::default() };
    s.path.max_depth = 4;
    let film = render(scene, s).unwrap().film;
    (0..64).map(|i| (i % 8 * 4, i / 8 * 4)).map(|(x, y)| film.region_estimate(x, y, x + 4, y + 4)).collect()
}

fn max_z(a: &[pathtrace::film::RegionEstimate], b: &[pathtrace::film::RegionEstimate]) -> f64 {
    a.iter().zip(b).map(|(a, b)| a.max_z_score(b)).fold(0.0, f64::max)
}

#[test]
fn anisotropic_highlights_turn_with_the_scene() {
    // A rotation about the floor's normal (+y): an arbitrary tangent basis of the normal would
    // stay put while the scene turns, and the highlights would change shape.
    let alpha = (0.04, 0.5);
    let base = render_blocks(anisotropic_scene(&Transform::IDENTITY, alpha), 1);
    let turned = render_blocks(anisotropic_scene(&Transform::rotate_y(50.0), alpha), 2);
    let z = max_z(&base, &turned);
    println!("rotated scene vs original: max |z| over 64 blocks × 3 channels = {z:.2}");
    assert!(z < 4.5, "the rotated scene renders differently: z = {z:.2}");
    // The test can tell: swapping the two roughnesses changes the image far beyond the noise.
    let swapped = render_blocks(anisotropic_scene(&Transform::IDENTITY, (alpha.1, alpha.0)), 3);
    let z_swapped = max_z(&base, &swapped);
    println!("roughness axes swapped: max |z| = {z_swapped:.2}");
    assert!(z_swapped > 8.0, "anisotropy is not visible in this scene (z = {z_swapped:.2})");
}

/// A unit sphere as a 24 × 12 mesh with its vertex normals tilted at random by up to `tilt`
/// degrees.
fn bumpy_sphere(tilt: f32, rng: &mut TestRng) -> TriangleMesh {
    let (nu, nv) = (24u32, 12u32);
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    for j in 0..=nv {
        for i in 0..=nu {
            let (theta, phi) =
                (std::f32::consts::PI * j as f32 / nv as f32, std::f32::consts::TAU * i as f32 / nu as f32);
            let p = Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin());
            positions.push(p);
            let f = Frame::from_normal(p.normalize());
            let (a, r) = (std::f32::consts::TAU * rng.next_f32(), tilt.to_radians() * rng.next_f32().sqrt());
            normals.push(f.to_world(Vec3::new(r.sin() * a.cos(), r.sin() * a.sin(), r.cos())));
        }
    }
    let mut indices = Vec::new();
    let id = |i: u32, j: u32| j * (nu + 1) + i;
    for j in 0..nv {
        for i in 0..nu {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            // Outward winding (counter-clockwise seen from outside).
            indices.push([a, b, c]);
            indices.push([a, c, d]);
        }
    }
    TriangleMesh { positions, indices, normals: Some(normals), uvs: None, tangents: None }
}

#[test]
fn perturbed_vertex_normals_give_no_nans_and_no_energy_gain() {
    // A white furnace: a convex object of albedo a under a uniform sky of radiance 1 reflects at
    // most a (it sees only the sky); shading normals must not push it above that, nor NaN.
    let mut rng = TestRng::new(17);
    let albedo = 0.8;
    for (material, name) in [
        (Material::Lambertian(Lambertian { albedo: Rgb::splat(albedo) }), "lambertian"),
        (
            // A perfect reflector: η → 0, k large gives Fresnel reflectance ≈ 1.
            Material::RoughConductor(RoughConductor {
                distribution: Microfacet::new(MicrofacetKind::Ggx, 0.1, 0.3),
                eta: Rgb::splat(0.01),
                k: Rgb::splat(100.0),
                reflectance: Rgb::WHITE,
            }),
            "white anisotropic metal",
        ),
    ] {
        let mut b = SceneBuilder::new();
        let m = b.material(material);
        let mesh = bumpy_sphere(60.0, &mut rng);
        assert!(b.mesh(&mesh, m, &Transform::IDENTITY).unwrap() <= 2 * 24, "only pole triangles are degenerate");
        b.environment(EnvironmentLight::constant(Rgb::WHITE)).unwrap();
        b.camera(CameraDesc {
            look_from: Vec3::new(0.0, 0.5, -3.2),
            look_at: Vec3::ZERO,
            vfov_degrees: 36.0,
            ..Default::default()
        });
        let mut s = RenderSettings { width: 24, height: 24, spp: 256, seed: 5, ..Default::default() };
        s.path.max_depth = -1;
        let out = render(Arc::new(b.build().unwrap()), s).unwrap();
        assert_eq!(out.progress.dropped_samples, 0, "{name}: NaN or infinite samples");
        let bound = if name == "lambertian" { albedo as f64 } else { 1.0 };
        let (mut worst, mut darkest) = (f64::MIN, f64::MAX);
        // The central 8×8 pixels all see the object.
        for y in 8..16 {
            for x in 8..16 {
                let e = out.film.region_estimate(x, y, x + 1, y + 1);
                let se = e.variance_of_mean[0].sqrt();
                worst = worst.max((e.mean[0] - bound) / se.max(1e-9));
                darkest = darkest.min(e.mean[0]);
            }
        }
        println!("{name}: max (pixel − {bound})/σ = {worst:.2}, darkest pixel {darkest:.3}");
        assert!(worst < 4.5, "{name}: a pixel is brighter than the energy bound (z = {worst:.2})");
        if name == "lambertian" {
            // Measured 0.69 of 0.8: cosine sampling about a tilted normal loses only what enters the
            // object. (The mirror-like metal goes much darker, 0.14, where the viewer falls below
            // the tilted shading hemisphere; not asserted: see docs/materials.md.)
            assert!(darkest > 0.5 * albedo as f64, "{name}: a black spot ({darkest:.3})");
        }
    }
}

#[test]
fn disk_tangents_point_outwards() {
    let disk = pathtrace::shape::Disk::new(Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0)).unwrap();
    let shape = Shape::Disk(disk);
    for target in [Vec3::new(1.0, 0.0, 0.3), Vec3::new(-0.5, 0.0, -0.6)] {
        let ray = Ray::new(target + Vec3::Y, -Vec3::Y);
        let sp = shape.surface(&ray, &shape.intersect(&ray, 0.0, f32::INFINITY).unwrap(), &[]);
        // Along ∂p/∂u the radius u grows: a small step along it increases uv.x.
        let step = sp.p + 0.01 * sp.dpdu.normalize();
        let ray2 = Ray::new(step + Vec3::Y, -Vec3::Y);
        let sp2 = shape.surface(&ray2, &shape.intersect(&ray2, 0.0, f32::INFINITY).unwrap(), &[]);
        assert!(sp2.uv.x > sp.uv.x, "{target}: u does not grow along dpdu");
        assert!((sp2.uv.y - sp.uv.y).abs() < 1e-3, "{target}: the angle changes along dpdu");
    }
}

/// Finds a shape's surface along a ray.
type HitSurface = Box<dyn Fn(Ray) -> Option<pathtrace::shape::SurfacePoint>>;

/// ∂p/∂u and ∂p/∂v are the derivatives of each shape's parameterisation: a step of ε·∂p/∂v
/// across the surface moves uv by (0, ε), a step of ε·∂p/∂u by (ε, 0) (bump maps scale their
/// tilt by both).
#[test]
fn position_derivatives_match_the_uv_parameterisation() {
    use pathtrace::shape::{Disk, Triangle};
    let eps = 1e-3;
    let tri =
        Triangle::new(Vec3::new(-1.0, 0.2, -1.0), Vec3::new(1.5, 0.0, -0.5), Vec3::new(0.0, 0.1, 1.2), 0).unwrap();
    let tri_uvs = [Vec2::new(0.1, 0.2), Vec2::new(0.9, 0.3), Vec2::new(0.4, 0.8)];
    let shapes: Vec<(&str, HitSurface)> = vec![
        (
            "sphere",
            Box::new(|r: Ray| {
                let s = Shape::Sphere(Sphere::new(Vec3::new(0.0, -1.0, 0.0), 1.3).unwrap());
                s.intersect(&r, 0.0, f32::INFINITY).map(|h| s.surface(&r, &h, &[]))
            }),
        ),
        (
            "quad",
            Box::new(|r: Ray| {
                let q = Quad::new(Vec3::new(-1.0, 0.0, -1.0), Vec3::new(2.0, 0.3, 0.5), Vec3::new(0.0, 0.2, 2.0));
                let s = Shape::Quad(q.unwrap());
                s.intersect(&r, 0.0, f32::INFINITY).map(|h| s.surface(&r, &h, &[]))
            }),
        ),
        (
            "disk",
            Box::new(|r: Ray| {
                let d = Disk::new(Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.5)).unwrap();
                let s = Shape::Disk(d);
                s.intersect(&r, 0.0, f32::INFINITY).map(|h| s.surface(&r, &h, &[]))
            }),
        ),
        (
            "triangle",
            Box::new(move |r: Ray| {
                tri.intersect(&r, 0.0, f32::INFINITY).map(|h| tri.surface_with(&h, None, Some(tri_uvs)))
            }),
        ),
    ];
    for (name, hit) in &shapes {
        let down = |p: Vec3, n: Vec3| hit(Ray::new(p + n, -n)).unwrap_or_else(|| panic!("{name}: missed"));
        let sp = down(Vec3::new(0.3, 2.0, 0.2), Vec3::Y);
        assert!(sp.dpdv != Vec3::ZERO, "{name}: no ∂p/∂v");
        for (d, expected) in [(sp.dpdu, Vec2::new(eps, 0.0)), (sp.dpdv, Vec2::new(0.0, eps))] {
            let moved = down(sp.p + eps * d, sp.n_geometric).uv - sp.uv;
            assert!((moved - expected).length() < 0.05 * eps, "{name}: uv moved by {moved} for {expected}");
        }
    }
}
