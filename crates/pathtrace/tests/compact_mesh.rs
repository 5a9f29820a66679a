//! Meshes kept in compact form (shared vertices + indices) still give every hit what a
//! per-triangle shape gave: the right triangle, its interpolated normal and texture
//! coordinates, and — for emissive meshes — the area light of exactly that triangle.

use pathtrace::light::{Emission, LightShape};
use pathtrace::material::Material;
use pathtrace::math::{Ray, Rgb, Transform, Vec2, Vec3};
use pathtrace::scene::Primitive;
use pathtrace::shape::TriangleMesh;
use pathtrace::SceneBuilder;

/// A unit square in z = 0 (two triangles), facing +z, with texture coordinates = (x, y).
fn square() -> TriangleMesh {
    TriangleMesh {
        positions: vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        normals: None,
        uvs: Some(vec![Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y]),
        tangents: None,
    }
}

#[test]
fn each_triangle_of_an_emissive_mesh_is_its_own_light() {
    let mut b = SceneBuilder::new();
    let lamp = b.emissive(Emission { radiance: Rgb::splat(2.0), two_sided: false });
    let grey = b.material(Material::Black);
    // A non-emissive mesh first, so the lamp's triangles are not the first primitives.
    b.mesh(&square(), grey, &Transform::translate(Vec3::new(5.0, 0.0, 0.0))).unwrap();
    let placed = Transform::translate(Vec3::new(0.0, 0.0, 2.0));
    b.mesh(&square(), lamp, &placed).unwrap();
    let scene = b.build().unwrap();
    assert_eq!(scene.lights.area_lights().count(), 2);
    let total_area: f32 = scene.lights.area_lights().map(|l| l.area()).sum();
    assert!((total_area - 1.0).abs() < 1e-6, "{total_area}");
    // Points inside the first and the second triangle, seen from above.
    for (x, y) in [(0.8, 0.3), (0.3, 0.8)] {
        let ray = Ray::new(Vec3::new(x, y, 5.0), -Vec3::Z);
        let hit = scene.intersect(&ray, f32::INFINITY).expect("the lamp is hit");
        let it = scene.interaction(&ray, &hit);
        assert_ne!(it.light, Primitive::NO_LIGHT);
        let light = scene.lights.get(it.light).unwrap();
        let LightShape::Triangle(t) = light.shape else { panic!("{:?}", light.shape) };
        // The light's triangle contains the hit point (its barycentrics are in [0, 1]).
        let (e1, e2, d) = (t.e1, t.e2, it.surface.p - t.p0);
        let n = e1.cross(e2);
        let b1 = d.cross(e2).dot(n) / n.length_squared();
        let b2 = e1.cross(d).dot(n) / n.length_squared();
        assert!(b1 >= -1e-5 && b2 >= -1e-5 && b1 + b2 <= 1.0 + 1e-5, "({x}, {y}): ({b1}, {b2})");
        assert!((it.surface.uv - Vec2::new(x, y)).length() < 1e-5, "{:?}", it.surface.uv);
        assert!((it.surface.p - Vec3::new(x, y, 2.0)).length() < 1e-5);
    }
    // The other mesh does not emit.
    let ray = Ray::new(Vec3::new(5.5, 0.5, 1.0), -Vec3::Z);
    let hit = scene.intersect(&ray, f32::INFINITY).unwrap();
    assert_eq!(scene.interaction(&ray, &hit).light, Primitive::NO_LIGHT);
}

#[test]
fn vertex_normals_are_interpolated_and_placed() {
    let mut mesh = square();
    let tilted = Vec3::new(0.6, 0.0, 0.8);
    mesh.normals = Some(vec![Vec3::Z, tilted, tilted, Vec3::Z]);
    let mut b = SceneBuilder::new();
    b.allow_no_lights(true);
    let m = b.material(Material::Black);
    // A quarter turn about z: the x-tilt of the normals becomes a y-tilt.
    b.mesh(&mesh, m, &Transform::rotate_z(90.0)).unwrap();
    let scene = b.build().unwrap();
    // (x, y) = (-0.4, 0.5) after the turn is (0.5, 0.4) before, in the first triangle at
    // barycentrics (0.1, 0.4): half the first corner's normal, half the tilted one.
    let ray = Ray::new(Vec3::new(-0.4, 0.5, 1.0), -Vec3::Z);
    let hit = scene.intersect(&ray, f32::INFINITY).unwrap();
    let s = scene.interaction(&ray, &hit).surface;
    let want = Vec3::new(0.0, 0.3, 0.9).normalize();
    assert!((s.n_shading - want).length() < 1e-4, "{:?} vs {want:?}", s.n_shading);
    assert!((s.n_geometric - Vec3::Z).length() < 1e-6);
}

/// A UV sphere of `2 · stacks · slices` triangles (minus the degenerate ones at the poles) with
/// shared vertices.
fn uv_sphere(stacks: u32, slices: u32) -> TriangleMesh {
    let mut mesh = TriangleMesh::default();
    for i in 0..=stacks {
        let theta = std::f32::consts::PI * i as f32 / stacks as f32;
        for j in 0..slices {
            let phi = 2.0 * std::f32::consts::PI * j as f32 / slices as f32;
            mesh.positions.push(Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin()));
        }
    }
    let v = |i: u32, j: u32| i * slices + j % slices;
    for i in 0..stacks {
        for j in 0..slices {
            mesh.indices.push([v(i, j), v(i + 1, j), v(i + 1, j + 1)]);
            mesh.indices.push([v(i, j), v(i + 1, j + 1), v(i, j + 1)]);
        }
    }
    mesh
}

#[test]
fn a_mesh_and_its_bvh_take_under_80_bytes_per_triangle() {
    // Issue 5's memory target, counted from the vectors' capacities (deterministic).
    let mut b = SceneBuilder::new();
    b.allow_no_lights(true);
    let m = b.material(Material::Black);
    let skipped = b.mesh(&uv_sphere(100, 200), m, &Transform::IDENTITY).unwrap();
    let scene = b.build().unwrap();
    let triangles = scene.primitive_count();
    assert_eq!(triangles + skipped, 40_000);
    let per_triangle = scene.memory_bytes() as f64 / triangles as f64;
    eprintln!("sphere of {triangles} triangles: {per_triangle:.1} bytes per triangle (mesh + BVH)");
    assert!(per_triangle < 80.0, "{per_triangle:.1} bytes per triangle");
    // Not trivially small either: 12 bytes of indices and 40 of packet per triangle at least.
    assert!(per_triangle > 52.0, "{per_triangle:.1} bytes per triangle");
}
