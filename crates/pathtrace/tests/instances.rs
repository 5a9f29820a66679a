//! Instances (two-level BVH) against the flattened scene: the same shape group copied and
//! transformed into the world. Hits, any-hit queries and renders must agree, and a thousand
//! instances of a large mesh must cost one mesh's memory plus a little per instance.

use pathtrace::light::Emission;
use pathtrace::material::{Diffuse, Material};
use pathtrace::math::{offset_ray_origin, Mat4, Ray, Rgb, Transform, Vec2, Vec3};
use pathtrace::scene::{BuildError, PrimRef};
use pathtrace::shape::{Disk, Plane, Quad, Shape, Sphere, Triangle, TriangleMesh};
use pathtrace::{render, CameraDesc, MaterialId, RenderSettings, Scene, SceneBuilder, ShapeGroup};
use pathtrace_testkit::TestRng;
use std::sync::Arc;

/// A bumpy `n`×`n` height field over [-1, 1]² with vertex normals and texture coordinates.
fn bumpy_mesh(n: usize) -> TriangleMesh {
    let h = |x: f32, y: f32| 0.25 * (3.0 * x).sin() * (2.0 * y).cos();
    let mut m =
        TriangleMesh { positions: vec![], indices: vec![], normals: Some(vec![]), uvs: Some(vec![]), tangents: None };
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (2.0 * i as f32 / n as f32 - 1.0, 2.0 * j as f32 / n as f32 - 1.0);
            m.positions.push(Vec3::new(x, y, h(x, y)));
            // Normal of z = h(x, y): (−∂h/∂x, −∂h/∂y, 1).
            let dx = 0.75 * (3.0 * x).cos() * (2.0 * y).cos();
            let dy = -0.5 * (3.0 * x).sin() * (2.0 * y).sin();
            m.normals.as_mut().unwrap().push(Vec3::new(-dx, -dy, 1.0).normalize());
            m.uvs.as_mut().unwrap().push(Vec2::new(i as f32 / n as f32, j as f32 / n as f32));
        }
    }
    let at = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    for j in 0..n {
        for i in 0..n {
            m.indices.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            m.indices.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    m
}

/// What a group holds, so the same contents can be added to a group or flattened into a scene.
enum Item {
    Mesh(TriangleMesh, Transform),
    Shape(Shape, Transform),
}

struct Group {
    items: Vec<(Item, usize)>,
}

fn test_group() -> Group {
    let tilt = Transform::rotate_x(20.0).then(&Transform::translate(Vec3::new(0.0, 0.0, 0.6)));
    Group {
        items: vec![
            (Item::Mesh(bumpy_mesh(14), Transform::IDENTITY), 0),
            (Item::Shape(Shape::Quad(Quad::new(Vec3::new(-1.0, -1.0, -0.8), Vec3::X, Vec3::Y).unwrap()), tilt), 1),
            (Item::Shape(Shape::Sphere(Sphere::new(Vec3::new(0.5, 0.5, 0.9), 0.35).unwrap()), Transform::IDENTITY), 2),
            (Item::Shape(Shape::Disk(Disk::round(Vec3::new(-0.5, 0.4, -0.5), Vec3::Y, 0.4).unwrap()), tilt), 1),
            (
                Item::Shape(
                    Shape::Triangle(
                        Triangle::new(
                            Vec3::new(0.2, -0.9, -0.3),
                            Vec3::new(0.9, -0.9, -0.2),
                            Vec3::new(0.5, -0.2, -0.6),
                            Triangle::FLAT,
                        )
                        .unwrap(),
                    ),
                    Transform::IDENTITY,
                ),
                2,
            ),
        ],
    }
}

/// A random placement: rotation, scale (sometimes non-uniform, sometimes mirroring) and
/// translation within [-6, 6]³.
/// The group built as one shape group, item `k` with material `mats[m]`.
fn shape_group(group: &Group, mats: &[MaterialId]) -> ShapeGroup {
    let mut g = ShapeGroup::new();
    for (item, m) in &group.items {
        match item {
            Item::Mesh(mesh, t) => drop(g.mesh(mesh, mats[*m], t).unwrap()),
            Item::Shape(s, t) => g.shape(s.clone(), mats[*m], t).unwrap(),
        }
    }
    g
}

fn random_transform(rng: &mut TestRng, k: usize) -> Transform {
    let mut r = || rng.next_f32();
    let s = 0.6 + 1.2 * r();
    let scale = match k % 4 {
        0 => Vec3::splat(s),
        1 => Vec3::new(s, 0.6 + 1.2 * r(), 0.6 + 1.2 * r()),
        2 => Vec3::new(-s, s, s),
        _ => Vec3::new(s, s, -0.6 - 1.2 * r()),
    };
    let rot = Transform::rotate_x(360.0 * r())
        .then(&Transform::rotate_y(360.0 * r()))
        .then(&Transform::rotate_z(360.0 * r()));
    let t = Vec3::new(12.0 * r() - 6.0, 12.0 * r() - 6.0, 12.0 * r() - 6.0);
    Transform::scale(scale).unwrap().then(&rot).then(&Transform::translate(t))
}

/// The instanced scene and its flattened copy: `count` placements of the test group (every
/// third with a material override), a floor plane and a box of quads outside the group.
fn scenes(count: usize, seed: u64) -> (Scene, Scene) {
    let mut rng = TestRng::new(seed);
    let placements: Vec<Transform> = (0..count).map(|k| random_transform(&mut rng, k)).collect();
    let group = test_group();
    let build = |instanced: bool| {
        let mut b = SceneBuilder::new();
        b.allow_no_lights(true);
        let mats: Vec<MaterialId> = (0..5)
            .map(|k| b.material(Material::Diffuse(Diffuse { albedo: Rgb::splat(0.1 + 0.15 * k as f32) })))
            .collect();
        let floor = Plane::new(Vec3::new(0.0, -9.0, 0.0), Vec3::Y).unwrap();
        b.shape(Shape::Plane(floor), mats[3], &Transform::IDENTITY).unwrap();
        b.add_box(Vec3::splat(-1.0), Vec3::splat(1.0), mats[4], &Transform::translate(Vec3::new(7.0, 7.0, 7.0)))
            .unwrap();
        let override_of = |k: usize| (k % 3 == 2).then_some(mats[4]);
        if instanced {
            let id = b.group(shape_group(&group, &mats)).unwrap();
            for (k, t) in placements.iter().enumerate() {
                b.instance(id, t, override_of(k)).unwrap();
            }
        } else {
            for (k, place) in placements.iter().enumerate() {
                for (item, m) in &group.items {
                    let m = override_of(k).unwrap_or(mats[*m]);
                    match item {
                        Item::Mesh(mesh, t) => drop(b.mesh(mesh, m, &t.then(place)).unwrap()),
                        Item::Shape(s, t) => b.shape(s.clone(), m, &t.then(place)).unwrap(),
                    }
                }
            }
        }
        b.build().unwrap()
    };
    (build(true), build(false))
}

fn uniform_in_box(rng: &mut TestRng, half: f32) -> Vec3 {
    Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * (2.0 * half) - Vec3::splat(half)
}

fn unit_vector(rng: &mut TestRng) -> Vec3 {
    loop {
        let v = uniform_in_box(rng, 1.0);
        if v.length_squared() > 1e-4 && v.length_squared() <= 1.0 {
            return v.normalize();
        }
    }
}

/// Rays of three kinds, a third each: between random points around the scene; leaving a
/// surface of the flattened scene in a random direction; and from outside, away from it.
fn rays(flat: &Scene, count: usize, seed: u64) -> Vec<Ray> {
    let mut rng = TestRng::new(seed);
    let mut out = Vec::with_capacity(count);
    while out.len() < count {
        let a = uniform_in_box(&mut rng, 10.0);
        let b = uniform_in_box(&mut rng, 10.0);
        let ray = Ray::new(a, (b - a).normalize());
        match out.len() % 3 {
            0 => out.push(ray),
            1 => {
                if let Some(hit) = flat.intersect(&ray, f32::INFINITY) {
                    let s = flat.interaction(&ray, &hit).surface;
                    let dir = unit_vector(&mut rng);
                    out.push(Ray::new(offset_ray_origin(s.p, s.n_geometric, dir), dir));
                }
            }
            _ => {
                let dir = unit_vector(&mut rng);
                out.push(Ray::new(dir * 30.0 + 0.5 * uniform_in_box(&mut rng, 1.0), dir));
            }
        }
    }
    out
}

#[test]
fn two_level_hits_equal_the_flattened_scenes_hits() {
    let (inst, flat) = scenes(60, 7);
    assert_eq!(inst.instance_count(), 60);
    let rays = rays(&flat, 300_000, 11);
    let (mut hits, mut instance_hits, mut misses) = (0, 0, 0);
    let mut disagreements = Vec::new();
    for ray in &rays {
        let (a, b) = (inst.intersect(ray, f32::INFINITY), flat.intersect(ray, f32::INFINITY));
        match (a, b) {
            (None, None) => misses += 1,
            (Some(a), Some(b)) => {
                hits += 1;
                instance_hits += matches!(a.prim, PrimRef::Instance { .. }) as usize;
                let (sa, sb) = (inst.interaction(ray, &a), flat.interaction(ray, &b));
                // Relative to t, and for short rays to the scene's unit size: the two scenes round
                // their placed vertices differently, by a few ulps of the coordinates (up to
                // ~10 here), whatever the length of the ray.
                let t_ok = (a.hit.t - b.hit.t).abs() <= 1e-4 * b.hit.t.max(1.0);
                // Under a non-uniform scale (placements 1 and 3 of every 4) the shading normal
                // differs slightly by design: an instance interpolates its group's vertex
                // normals and then transforms the result, while the flattened mesh transforms
                // and renormalises each vertex normal before interpolating (docs/bvh.md).
                let non_uniform = matches!(a.prim, PrimRef::Instance { instance, .. } if instance % 2 == 1);
                let shading_eps = if non_uniform { 1e-3 } else { 1e-4 };
                let n_ok = sa.surface.n_geometric.dot(sb.surface.n_geometric) > 1.0 - 1e-4
                    && sa.surface.n_shading.dot(sb.surface.n_shading) > 1.0 - shading_eps;
                let p_ok = (sa.surface.p - sb.surface.p).length() <= 1e-4 * (1.0 + sb.surface.p.abs().max_element());
                if !(t_ok && n_ok && p_ok && sa.material == sb.material) {
                    disagreements.push(format!("{ray:?}: {a:?} {:?} vs {b:?} {:?}", sa.surface, sb.surface));
                }
            }
            _ => disagreements.push(format!("{ray:?}: {a:?} vs {b:?}")),
        }
    }
    eprintln!(
        "{} rays: {hits} hits ({instance_hits} on instances), {misses} misses, {} disagreements",
        rays.len(),
        disagreements.len()
    );
    assert!(instance_hits > 50_000 && misses > 100_000, "the rays exercise both hits and misses");
    // Rays that graze an edge or a crossing of two instances could go either way under the
    // rounding of the object-space transform: a handful in 300,000 at most (0 measured).
    assert!(
        disagreements.len() <= 10,
        "{}:\n{}",
        disagreements.len(),
        disagreements[..disagreements.len().min(10)].join("\n")
    );
}

#[test]
fn any_hit_agrees_with_closest_hit_and_the_top_level_with_testing_every_instance() {
    let (inst, flat) = scenes(60, 8);
    let rays = rays(&flat, 200_000, 12);
    let mut rng = TestRng::new(3);
    let mut occluded = 0;
    for ray in &rays {
        let closest = inst.intersect(ray, f32::INFINITY);
        // The top-level BVH finds exactly what testing every instance finds.
        let brute = inst.intersect_brute_force(ray, f32::INFINITY);
        assert_eq!(closest.map(|h| h.hit.t), brute.map(|h| h.hit.t), "{ray:?}");
        // A shadow ray of random length: blocked exactly when a closest hit lies within it.
        let t_max = closest.map_or(30.0, |h| 2.0 * h.hit.t) * rng.next_f32();
        let blocked = inst.occluded(ray, t_max);
        assert_eq!(blocked, inst.intersect(ray, t_max).is_some(), "{ray:?} t_max {t_max}");
        occluded += blocked as usize;
    }
    assert!(occluded > 20_000 && occluded < rays.len() - 20_000, "{occluded}");
}

/// The two scenes of `render_agrees_with_the_flattened_scene`: a lit floor and a few
/// instances of the group, with a camera.
fn lit_scenes() -> (Arc<Scene>, Arc<Scene>) {
    let group = test_group();
    let placements = [
        Transform::rotate_x(-90.0).then(&Transform::translate(Vec3::new(-1.2, 0.5, 0.0))),
        Transform::scale(Vec3::new(0.7, 1.2, 0.8))
            .unwrap()
            .then(&Transform::rotate_y(40.0))
            .then(&Transform::translate(Vec3::new(1.3, 1.0, 0.5))),
        Transform::scale(Vec3::new(-0.8, 0.8, 0.8)).unwrap().then(&Transform::translate(Vec3::new(0.0, 1.5, 2.0))),
    ];
    let build = |instanced: bool| {
        let mut b = SceneBuilder::new();
        let mats: Vec<MaterialId> = (0..3)
            .map(|k| b.material(Material::Diffuse(Diffuse { albedo: Rgb::new(0.8, 0.3 + 0.2 * k as f32, 0.2) })))
            .collect();
        let lamp = b.emissive(Emission { radiance: Rgb::splat(6.0), two_sided: false });
        let floor =
            Quad::new(Vec3::new(-6.0, -0.5, -6.0), Vec3::new(0.0, 0.0, 12.0), Vec3::new(12.0, 0.0, 0.0)).unwrap();
        b.shape(Shape::Quad(floor), mats[0], &Transform::IDENTITY).unwrap();
        let light = Quad::new(Vec3::new(-1.5, 5.0, -1.5), Vec3::new(3.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 3.0)).unwrap();
        b.shape(Shape::Quad(light), lamp, &Transform::IDENTITY).unwrap();
        if instanced {
            let id = b.group(shape_group(&group, &mats)).unwrap();
            for t in &placements {
                b.instance(id, t, None).unwrap();
            }
        } else {
            for place in &placements {
                for (item, m) in &group.items {
                    match item {
                        Item::Mesh(mesh, t) => drop(b.mesh(mesh, mats[*m], &t.then(place)).unwrap()),
                        Item::Shape(s, t) => b.shape(s.clone(), mats[*m], &t.then(place)).unwrap(),
                    }
                }
            }
        }
        b.camera(CameraDesc {
            look_from: Vec3::new(0.0, 3.0, -7.0),
            look_at: Vec3::new(0.0, 0.8, 0.5),
            ..Default::default()
        });
        Arc::new(b.build().unwrap())
    };
    (build(true), build(false))
}

#[test]
fn render_agrees_with_the_flattened_scene() {
    let (inst, flat) = lit_scenes();
    let settings = RenderSettings { width: 48, height: 36, spp: 64, ..Default::default() };
    // Independent seeds: the two estimates must agree within their confidence intervals.
    let a = render(inst, RenderSettings { seed: 1, ..settings.clone() }).unwrap().film;
    let b = render(flat, RenderSettings { seed: 2, ..settings }).unwrap().film;
    let mut worst: f64 = 0.0;
    for (y, x) in (0..36).step_by(6).flat_map(|y| (0..48).step_by(6).map(move |x| (y, x))) {
        let z = a.region_estimate(x, y, x + 6, y + 6).max_z_score(&b.region_estimate(x, y, x + 6, y + 6));
        worst = worst.max(z);
    }
    eprintln!("largest |z| over 48 regions (3 channels each): {worst:.2}");
    // 144 comparisons: |z| > 4.5 has probability ~1e-3 overall if the images agree.
    assert!(worst < 4.5, "{worst}");
}

#[test]
fn emissive_instances_are_rejected() {
    let mut b = SceneBuilder::new();
    let lamp = b.emissive(Emission { radiance: Rgb::splat(1.0), two_sided: false });
    let grey = b.material(Material::Diffuse(Diffuse { albedo: Rgb::splat(0.5) }));
    let quad = || Shape::Quad(Quad::new(Vec3::ZERO, Vec3::X, Vec3::Y).unwrap());
    b.shape(quad(), lamp, &Transform::translate(Vec3::Z * 5.0)).unwrap();
    let mut g = ShapeGroup::new();
    g.shape(quad(), lamp, &Transform::IDENTITY).unwrap();
    let emissive = b.group(g).unwrap();
    let mut g = ShapeGroup::new();
    g.shape(quad(), grey, &Transform::IDENTITY).unwrap();
    let plain = b.group(g).unwrap();
    // Overriding an emissive group's material with a non-emissive one is fine.
    let mut ok = b.clone();
    ok.instance(emissive, &Transform::IDENTITY, Some(grey)).unwrap();
    ok.instance(plain, &Transform::IDENTITY, None).unwrap();
    assert!(ok.build().is_ok());
    let mut bad = b.clone();
    bad.instance(emissive, &Transform::IDENTITY, None).unwrap();
    assert!(matches!(bad.build(), Err(BuildError::Instance(_))));
    let mut bad = b.clone();
    bad.instance(plain, &Transform::IDENTITY, Some(lamp)).unwrap();
    assert!(matches!(bad.build(), Err(BuildError::Instance(_))));
    // A plane cannot be grouped; a missing group cannot be placed.
    let plane = Shape::Plane(Plane::new(Vec3::ZERO, Vec3::Y).unwrap());
    assert!(ShapeGroup::new().shape(plane, grey, &Transform::IDENTITY).is_err());
    let mut bad = b.clone();
    assert!(bad.instance(pathtrace::GroupId(9), &Transform::IDENTITY, None).is_err());
    let infinite = Transform { matrix: Mat4::from_scale(Vec3::splat(f32::INFINITY)), inverse: Mat4::ZERO };
    assert!(bad.instance(plain, &infinite, None).is_err());
}

/// A UV sphere of about `2 · stacks · slices` triangles with shared vertices.
fn uv_sphere(stacks: usize, slices: usize) -> TriangleMesh {
    let mut m = TriangleMesh { positions: vec![], indices: vec![], normals: None, uvs: None, tangents: None };
    for i in 0..=stacks {
        let theta = std::f32::consts::PI * i as f32 / stacks as f32;
        for j in 0..slices {
            let phi = 2.0 * std::f32::consts::PI * j as f32 / slices as f32;
            m.positions.push(Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin()));
        }
    }
    let at = |i: usize, j: usize| (i * slices + j % slices) as u32;
    for i in 0..stacks {
        for j in 0..slices {
            m.indices.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            m.indices.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    m
}

#[test]
fn a_thousand_instances_of_a_100k_triangle_mesh_cost_one_mesh_and_render() {
    let mesh = uv_sphere(200, 250); // 100,000 triangles, minus the degenerate ones at the poles
    let mut b = SceneBuilder::new();
    let grey = b.material(Material::Diffuse(Diffuse { albedo: Rgb::splat(0.6) }));
    let lamp = b.emissive(Emission { radiance: Rgb::splat(4.0), two_sided: false });
    let light = Quad::new(Vec3::new(-20.0, 30.0, -20.0), Vec3::new(40.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 40.0)).unwrap();
    b.shape(Shape::Quad(light), lamp, &Transform::IDENTITY).unwrap();
    // The same mesh once, as an ordinary object: what one copy costs.
    let mut single = b.clone();
    single.mesh(&mesh, grey, &Transform::IDENTITY).unwrap();
    let single = single.build().unwrap();
    let one_copy = single.memory_bytes();
    let mut g = ShapeGroup::new();
    g.mesh(&mesh, grey, &Transform::IDENTITY).unwrap();
    let id = b.group(g).unwrap();
    for k in 0..1000 {
        let (x, z) = ((k % 40) as f32 * 2.5 - 50.0, (k / 40) as f32 * 2.5 - 30.0);
        b.instance(id, &Transform::rotate_y(k as f32).then(&Transform::translate(Vec3::new(x, 0.0, z))), None).unwrap();
    }
    b.camera(CameraDesc { look_from: Vec3::new(0.0, 20.0, -60.0), look_at: Vec3::ZERO, ..Default::default() });
    let scene = Arc::new(b.build().unwrap());
    let bytes = scene.instance_memory_bytes();
    let per_instance = (bytes as f64 - one_copy as f64) / 1000.0;
    eprintln!(
        "one copy: {one_copy} bytes ({:.1} per triangle); 1000 instances: {bytes} bytes ({:.3}× one copy; \
         1000 copies would be {}); {per_instance:.0} bytes per instance beyond one copy",
        one_copy as f64 / 99_500.0,
        bytes as f64 / one_copy as f64,
        1000 * one_copy
    );
    assert!((bytes as f64) < 1.1 * one_copy as f64 + 1000.0 * 256.0, "{bytes} vs {one_copy}");
    // A tiny render: every instance is traced through the top level.
    let settings = RenderSettings { width: 32, height: 24, spp: 2, ..Default::default() };
    let film = render(scene, settings).unwrap().film;
    let lit = film.pixels().iter().filter(|p| p.mean_rgb().max_component() > 0.0).count();
    assert!(lit > 32 * 24 / 4, "{lit} pixels lit");
}
