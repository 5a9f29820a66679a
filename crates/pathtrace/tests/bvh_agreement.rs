//! The BVH (with its SIMD leaf packets) must find the same closest hit as testing every
//! primitive, and its any-hit query must agree with its closest-hit query, on random scenes
//! mixing quads, triangles, spheres and planes, for random rays including rays that start on
//! surfaces, graze edges and vertices, or miss everything.

use pathtrace::material::Material;
use pathtrace::math::{Ray, Transform, Vec3};
use pathtrace::sampling::Pcg32;
use pathtrace::scene::{Hit, PrimRef};
use pathtrace::shape::{Plane, Quad, Shape, Sphere, Triangle};
use pathtrace::{Scene, SceneBuilder};

fn uniform(rng: &mut Pcg32, lo: f32, hi: f32) -> f32 {
    lo + (hi - lo) * rng.next_f32()
}

fn point(rng: &mut Pcg32, extent: f32) -> Vec3 {
    Vec3::new(uniform(rng, -extent, extent), uniform(rng, -extent, extent), uniform(rng, -extent, extent))
}

fn direction(rng: &mut Pcg32) -> Vec3 {
    loop {
        let d = point(rng, 1.0);
        if d.length_squared() > 1e-4 && d.length_squared() <= 1.0 {
            return d.normalize();
        }
    }
}

/// A random shape near the origin and a function giving points on it (for rays that start on
/// surfaces or graze edges): `surface(a, b)` with `a, b ∈ [0, 1]`.
fn random_shape(rng: &mut Pcg32, kind: u32) -> Option<Shape> {
    let size = uniform(rng, 0.05, 3.0);
    let corner = point(rng, 5.0);
    match kind {
        0 => Quad::new(corner, direction(rng) * size, direction(rng) * size * uniform(rng, 0.2, 1.5)).map(Shape::Quad),
        1 => Triangle::new(corner, corner + direction(rng) * size, corner + direction(rng) * size, Triangle::FLAT)
            .map(Shape::Triangle),
        _ => Sphere::new(corner, 0.5 * size).map(Shape::Sphere),
    }
}

/// A point on a shape's surface or boundary, `edge` choosing a boundary point.
fn surface_point(rng: &mut Pcg32, shape: &Shape, edge: bool) -> Vec3 {
    let (mut a, mut b) = (rng.next_f32(), rng.next_f32());
    if edge {
        match rng.next_u32() % 3 {
            0 => a = (a > 0.5) as u32 as f32,
            1 => b = (b > 0.5) as u32 as f32,
            _ => (a, b) = ((a > 0.5) as u32 as f32, (b > 0.5) as u32 as f32),
        }
    }
    match shape {
        Shape::Quad(q) => q.point_at(a, b),
        Shape::Triangle(t) => {
            let [p0, p1, p2] = t.vertices();
            let (a, b) = if edge {
                (a, (1.0 - a) * b.round())
            } else if a + b > 1.0 {
                (1.0 - a, 1.0 - b)
            } else {
                (a, b)
            };
            p0 + a * (p1 - p0) + b * (p2 - p0)
        }
        Shape::Sphere(s) => s.center + s.radius * direction(rng),
        _ => Vec3::ZERO,
    }
}

fn random_scene(rng: &mut Pcg32, n: usize, with_plane: bool) -> (Scene, Vec<Shape>) {
    let mut b = SceneBuilder::new();
    b.allow_no_lights(true);
    let m = b.material(Material::Black);
    let mut shapes = Vec::new();
    while shapes.len() < n {
        let kind = rng.next_u32() % 5; // quads and triangles twice as often as spheres
        if let Some(s) = random_shape(rng, kind.min(2)) {
            b.shape(s.clone(), m, &Transform::IDENTITY).unwrap();
            shapes.push(s);
        }
    }
    // A box of quads whose faces share edges, as in the Cornell box.
    let lo = point(rng, 3.0);
    b.add_box(lo, lo + Vec3::new(1.0, 2.0, 1.5), m, &Transform::IDENTITY).unwrap();
    if with_plane {
        let p = Plane::new(Vec3::new(0.0, -6.0, 0.0), direction(rng)).unwrap();
        b.shape(Shape::Plane(p), m, &Transform::IDENTITY).unwrap();
    }
    (b.build().unwrap(), shapes)
}

fn random_ray(rng: &mut Pcg32, shapes: &[Shape]) -> Ray {
    let shape = &shapes[rng.next_u32() as usize % shapes.len()];
    match rng.next_u32() % 4 {
        // Anywhere, in any direction (many rays miss).
        0 => Ray::new(point(rng, 8.0), direction(rng)),
        // Starting on a surface.
        1 => Ray::new(surface_point(rng, shape, false), direction(rng)),
        // Aimed at an edge or vertex (grazing the primitives that share it).
        2 => {
            let target = surface_point(rng, shape, true);
            let origin = point(rng, 8.0);
            Ray::new(origin, (target - origin).normalize())
        }
        // From far outside, pointing away from everything.
        _ => {
            let d = direction(rng);
            Ray::new(d * 100.0, d)
        }
    }
}

fn same_hit(a: &Hit, b: &Hit) -> bool {
    a.prim == b.prim || (a.hit.t - b.hit.t).abs() <= 1e-4 * a.hit.t.abs().max(b.hit.t.abs())
}

/// The hit names the primitive that was really hit: its surface, rebuilt from `(u, v)`, lies
/// where the ray is at `t`.
fn consistent(scene: &Scene, ray: &Ray, h: &Hit) -> bool {
    let p = scene.interaction(ray, h).surface.p;
    let q = ray.at(h.hit.t);
    (p - q).length() <= 1e-3 * (1.0 + q.abs().max_element())
}

fn check_scenes(seed: u64, scenes: usize, prims: usize, rays: usize) {
    let mut rng = Pcg32::new(seed, 1);
    let (mut hits, mut total) = (0, 0);
    for s in 0..scenes {
        let (scene, shapes) = random_scene(&mut rng, prims, s % 2 == 1);
        for _ in 0..rays {
            let ray = random_ray(&mut rng, &shapes);
            let t_max = if rng.next_f32() < 0.5 { f32::INFINITY } else { uniform(&mut rng, 0.0, 12.0) };
            let bvh = scene.intersect(&ray, t_max);
            let brute = scene.intersect_brute_force(&ray, t_max);
            match (&bvh, &brute) {
                (Some(a), Some(b)) => {
                    assert!(same_hit(a, b), "scene {s} {ray:?}: bvh {a:?} vs brute force {b:?}");
                    assert!(consistent(&scene, &ray, a), "scene {s} {ray:?}: bvh {a:?} is elsewhere");
                }
                (None, None) => {}
                _ => {
                    panic!("scene {s} {ray:?} t_max {t_max}: bvh {bvh:?} vs brute force {brute:?}")
                }
            }
            assert_eq!(scene.occluded(&ray, t_max), bvh.is_some(), "scene {s} {ray:?} t_max {t_max}");
            if let Some(h) = bvh {
                // Just before the closest hit nothing blocks, unless another surface is there too.
                let before = 0.999 * h.hit.t;
                if before > 0.0 {
                    assert_eq!(scene.occluded(&ray, before), scene.intersect(&ray, before).is_some());
                }
                assert!(matches!(h.prim, PrimRef::Bounded(_) | PrimRef::Unbounded(_)));
                hits += 1;
            }
            total += 1;
        }
    }
    // The ray mix must exercise both outcomes.
    assert!(hits > total / 10 && hits < total * 9 / 10, "{hits} hits of {total}");
}

#[test]
fn small_scenes_agree_with_brute_force() {
    check_scenes(1, 200, 7, 200);
}

#[test]
fn larger_scenes_agree_with_brute_force() {
    check_scenes(2, 20, 300, 2_000);
}

#[test]
fn cornell_like_leaves_agree_with_brute_force() {
    // Single-primitive and two-primitive scenes exercise partial packets.
    check_scenes(3, 300, 1, 50);
    check_scenes(4, 300, 2, 50);
}
