//! The BVH (with its SIMD leaf packets) must find the same closest hit as testing every
//! primitive, and its any-hit query must agree with its closest-hit query, on random scenes
//! mixing quads, triangles, spheres and planes, for random rays including rays that start on
//! surfaces, graze edges and vertices, or miss everything.

use pathtrace::accel::{BruteForce, BuildOptions, Bvh, Packable, SplitMethod};
use pathtrace::material::Material;
use pathtrace::math::Vec2;
use pathtrace::math::{Aabb, Ray, Transform, Vec3};
use pathtrace::sampling::Pcg32;
use pathtrace::scene::{Hit, PrimRef, Primitive};
use pathtrace::shape::{Plane, PrimHit, Quad, Shape, Sphere, Triangle, TriangleMesh};
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
    // A mesh kept in compact form (shared vertices, with normals and texture coordinates);
    // its triangles are also ray targets.
    let mesh = height_field_mesh(rng, 3);
    b.mesh(&mesh, m, &Transform::IDENTITY).unwrap();
    shapes.extend(mesh.indices.iter().filter_map(|t| {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        Triangle::new(a, b, c, Triangle::FLAT).map(Shape::Triangle)
    }));
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

// ---------------------------------------------------------------------------------------------
// Every build variant and the brute-force intersector, driven directly (not through a Scene).
// ---------------------------------------------------------------------------------------------

/// A small indexed height-field mesh (`cells × cells` squares, two triangles each) with
/// vertex normals and texture coordinates.
fn height_field_mesh(rng: &mut Pcg32, cells: usize) -> TriangleMesh {
    let origin = point(rng, 4.0);
    let step = uniform(rng, 0.1, 0.6);
    let side = cells + 1;
    let mut mesh = TriangleMesh::default();
    let (mut normals, mut uvs) = (Vec::new(), Vec::new());
    for i in 0..side {
        for j in 0..side {
            mesh.positions.push(origin + Vec3::new(i as f32 * step, uniform(rng, -0.3, 0.3), j as f32 * step));
            normals.push(Vec3::new(uniform(rng, -0.3, 0.3), 1.0, uniform(rng, -0.3, 0.3)).normalize());
            uvs.push(Vec2::new(i as f32, j as f32) / cells as f32);
        }
    }
    for i in 0..cells as u32 {
        for j in 0..cells as u32 {
            let v = |a: u32, b: u32| a * side as u32 + b;
            mesh.indices.push([v(i, j), v(i + 1, j), v(i + 1, j + 1)]);
            mesh.indices.push([v(i, j), v(i + 1, j + 1), v(i, j + 1)]);
        }
    }
    mesh.normals = Some(normals);
    mesh.uvs = Some(uvs);
    mesh
}

/// A small height field of triangles sharing edges and vertices (rays aimed at its edges
/// graze two triangles at once).
fn height_field(rng: &mut Pcg32, cells: usize) -> Vec<Shape> {
    let origin = point(rng, 4.0);
    let step = uniform(rng, 0.1, 0.6);
    let heights: Vec<f32> = (0..(cells + 1) * (cells + 1)).map(|_| uniform(rng, -0.3, 0.3)).collect();
    let vertex =
        |i: usize, j: usize| origin + Vec3::new(i as f32 * step, heights[i * (cells + 1) + j], j as f32 * step);
    let mut out = Vec::new();
    for i in 0..cells {
        for j in 0..cells {
            let [a, b, c, d] = [vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1)];
            out.extend(Triangle::new(a, b, c, Triangle::FLAT).map(Shape::Triangle));
            out.extend(Triangle::new(a, c, d, Triangle::FLAT).map(Shape::Triangle));
        }
    }
    out
}

fn random_bounded_shapes(rng: &mut Pcg32, n: usize) -> Vec<Shape> {
    let mut shapes = height_field(rng, 4);
    while shapes.len() < n {
        let kind = rng.next_u32() % 5;
        shapes.extend(random_shape(rng, kind.min(2)));
    }
    shapes
}

fn accel_inputs(shapes: &[Shape]) -> (Vec<Aabb>, Vec<Packable>) {
    let bounds = shapes.iter().map(|s| s.bounds().expect("bounded")).collect();
    let kinds = shapes
        .iter()
        .map(|s| match s {
            Shape::Quad(q) => Packable::Quad(*q),
            Shape::Triangle(t) => Packable::Triangle(*t),
            _ => Packable::No,
        })
        .collect();
    (bounds, kinds)
}

fn primitives(shapes: &[Shape]) -> Vec<Primitive> {
    shapes.iter().map(|s| Primitive { shape: s.clone(), material: 0, light: Primitive::NO_LIGHT }).collect()
}

/// Closest hit by testing every shape with its scalar test: (hit, shape index).
fn reference_hit(shapes: &[Shape], ray: &Ray, t_max: f32) -> Option<(PrimHit, u32)> {
    let mut best = None;
    let mut limit = t_max;
    for (i, s) in shapes.iter().enumerate() {
        if let Some(h) = s.intersect(ray, 0.0, limit) {
            limit = h.t;
            best = Some((h, i as u32));
        }
    }
    best
}

/// A closest-hit query: (hit, original shape index).
type ClosestFn = Box<dyn Fn(&Ray, f32) -> Option<(PrimHit, u32)>>;
type OccludedFn = Box<dyn Fn(&Ray, f32) -> bool>;

/// One accelerator under test: closest hit and occlusion in terms of original shape indices.
struct Variant {
    name: &'static str,
    closest: ClosestFn,
    occluded: OccludedFn,
}

fn bvh_variant(name: &'static str, shapes: &[Shape], opts: BuildOptions) -> Variant {
    let (bounds, kinds) = accel_inputs(shapes);
    let bvh = std::rc::Rc::new(Bvh::build_with(&bounds, &kinds, &opts));
    let prims = std::rc::Rc::new(primitives(shapes));
    let (b2, p2) = (bvh.clone(), prims.clone());
    Variant {
        name,
        closest: Box::new(move |ray, t_max| bvh.intersect(&prims[..], ray, 0.0, t_max)),
        occluded: Box::new(move |ray, t_max| b2.occluded(&p2[..], ray, 0.0, t_max)),
    }
}

fn brute_variant(shapes: &[Shape]) -> Variant {
    let (_, kinds) = accel_inputs(shapes);
    let brute = std::rc::Rc::new(BruteForce::new(&kinds));
    let prims = std::rc::Rc::new(primitives(shapes));
    let (b2, p2) = (brute.clone(), prims.clone());
    Variant {
        name: "brute force",
        closest: Box::new(move |ray, t_max| brute.intersect(&prims[..], ray, 0.0, t_max)),
        occluded: Box::new(move |ray, t_max| b2.occluded(&p2[..], ray, 0.0, t_max)),
    }
}

/// Same closest hit as the reference: the same shape with bit-identical `(t, u, v)` and
/// normal, or (on ties between shapes meeting at the hit point) the same `t` within rounding.
fn check_same(name: &str, shapes: &[Shape], ray: &Ray, got: Option<(PrimHit, u32)>, want: Option<(PrimHit, u32)>) {
    match (got, want) {
        (None, None) => {}
        (Some((g, gi)), Some((w, wi))) if gi == wi => {
            assert_eq!(g, w, "{name} {ray:?}: shape {gi}");
            let normal = |h: &PrimHit| shapes[gi as usize].surface(ray, h, &[]).n_geometric;
            assert_eq!(normal(&g), normal(&w), "{name} {ray:?}: shape {gi}");
        }
        (Some((g, gi)), Some((w, wi))) => {
            assert!(
                (g.t - w.t).abs() <= 1e-4 * g.t.abs().max(w.t.abs()),
                "{name} {ray:?}: shape {gi} {g:?} vs {wi} {w:?}"
            )
        }
        _ => panic!("{name} {ray:?}: {got:?} vs reference {want:?}"),
    }
}

fn check_variants(seed: u64, scenes: usize, prims: usize, rays: usize) -> usize {
    let mut rng = Pcg32::new(seed, 7);
    let mut checked = 0;
    for _ in 0..scenes {
        let shapes = random_bounded_shapes(&mut rng, prims);
        let sah = BuildOptions::default();
        let variants = [
            bvh_variant("sah serial", &shapes, sah.serial()),
            bvh_variant("sah parallel", &shapes, BuildOptions { parallel_above: 16, ..sah }),
            bvh_variant("median", &shapes, BuildOptions { method: SplitMethod::Median, ..sah }),
            bvh_variant("sah leaf 1, 4 bins", &shapes, BuildOptions { bins: 4, max_leaf: 1, ..sah }),
            brute_variant(&shapes),
        ];
        for _ in 0..rays {
            let ray = random_ray(&mut rng, &shapes);
            let t_max = if rng.next_f32() < 0.5 { f32::INFINITY } else { uniform(&mut rng, 0.0, 12.0) };
            let want = reference_hit(&shapes, &ray, t_max);
            for v in &variants {
                check_same(v.name, &shapes, &ray, (v.closest)(&ray, t_max), want);
                assert_eq!((v.occluded)(&ray, t_max), want.is_some(), "{} any-hit {ray:?} t_max {t_max}", v.name);
            }
            checked += 1;
        }
    }
    checked
}

#[test]
fn every_build_and_brute_force_agree_with_scalar_tests() {
    // 40 scenes × 5,000 rays + 400 scenes × 250 rays = 300,000 rays, each through five
    // accelerators, closest hit and any-hit.
    let rays = check_variants(11, 40, 400, 5_000) + check_variants(12, 400, 20, 250);
    assert_eq!(rays, 300_000);
}

#[test]
fn parallel_build_gives_the_serial_tree() {
    let mut rng = Pcg32::new(21, 3);
    let shapes = random_bounded_shapes(&mut rng, 60_000);
    let (bounds, kinds) = accel_inputs(&shapes);
    for method in [SplitMethod::Sah, SplitMethod::Median] {
        let opts = BuildOptions { method, ..Default::default() };
        let serial = Bvh::build_with(&bounds, &kinds, &opts.serial());
        for parallel_above in [1, 100, BuildOptions::PARALLEL_ABOVE] {
            let par = Bvh::build_with(&bounds, &kinds, &BuildOptions { parallel_above, ..opts });
            // Same nodes, and the same primitives in the same leaf packets.
            assert!(par.same_structure(&serial), "{method:?} parallel above {parallel_above}");
            assert_eq!(par.stats(), serial.stats());
        }
    }
    // The comparison itself can fail: a different build is a different tree.
    let a = Bvh::build_with(&bounds, &kinds, &BuildOptions::default());
    let b = Bvh::build_with(&bounds, &kinds, &BuildOptions { bins: 8, ..Default::default() });
    assert!(!a.same_structure(&b));
}

/// Bit-identical hits: same primitive kind and index, same `t`, `u`, `v` bits.
fn identical(a: &Option<Hit>, b: &Option<Hit>) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => {
            a.prim == b.prim
                && [a.hit.t, a.hit.u, a.hit.v].map(f32::to_bits) == [b.hit.t, b.hit.u, b.hit.v].map(f32::to_bits)
        }
        _ => false,
    }
}

/// The rays of a group in lanes: origins, directions and the active mask. With `some_off`,
/// about a third of the lanes are switched off at random (one draw per lane, in lane order).
fn group_lanes<const N: usize>(
    rays: &[Ray; N],
    rng: &mut Pcg32,
    some_off: bool,
) -> (pathtrace::wide::simd::Vec3s<N>, pathtrace::wide::simd::Vec3s<N>, pathtrace::wide::simd::Ms<N>) {
    let mut origin = pathtrace::wide::simd::Vec3s::<N>::default();
    let mut dir = pathtrace::wide::simd::Vec3s::<N>::default();
    let mut active = pathtrace::wide::simd::Ms::<N>::NONE;
    for (i, r) in rays.iter().enumerate() {
        origin.set(i, r.origin);
        dir.set(i, r.dir);
        if !some_off || !rng.next_u32().is_multiple_of(3) {
            active.0[i] = u32::MAX;
        }
    }
    (origin, dir, active)
}

/// Groups of 16 rays traversed together (`Scene::intersect_lanes`, `Scene::occluded_lanes`)
/// give each ray exactly what it gets alone — the primitive, and `t`, `u`, `v` bit for bit — whether the group is coherent
/// (one origin, directions within a few degrees: the tree is walked as a packet), incoherent
/// (rays split off to single-ray traversal) or partly inactive, on the random scenes above and
/// with rays aimed at shared edges and vertices, where two primitives are hit at one distance.
#[test]
fn ray_groups_find_what_single_rays_find() {
    const N: usize = 16;
    let mut rng = Pcg32::new(7, 3);
    let (mut hits, mut ties_possible, mut blocked_count) = (0, 0, 0);
    for s in 0..60 {
        let (scene, shapes) = random_scene(&mut rng, 40, s % 2 == 1);
        for g in 0..40 {
            let mut rays = [Ray::new(Vec3::ZERO, Vec3::X); N];
            match g % 3 {
                // Coherent: one origin, directions jittered around one aimed at a shape's edge.
                0 => {
                    let base = random_ray(&mut rng, &shapes);
                    for r in rays.iter_mut() {
                        let d = (base.dir + point(&mut rng, 0.03)).normalize();
                        *r = Ray::new(base.origin, d);
                    }
                    // A few rays aimed exactly at edges and vertices, from the same origin.
                    for r in rays.iter_mut().take(4) {
                        let shape = &shapes[rng.next_u32() as usize % shapes.len()];
                        let target = surface_point(&mut rng, shape, true);
                        *r = Ray::new(base.origin, (target - base.origin).normalize());
                        ties_possible += 1;
                    }
                }
                // Incoherent.
                1 => rays.iter_mut().for_each(|r| *r = random_ray(&mut rng, &shapes)),
                // Coherent but from points spread over a small area (shadow-ray-like).
                _ => {
                    let target = point(&mut rng, 4.0);
                    let centre = point(&mut rng, 8.0);
                    for r in rays.iter_mut() {
                        let o = centre + point(&mut rng, 0.5);
                        *r = Ray::new(o, (target - o).normalize());
                    }
                }
            }
            // Every fifth group has some lanes switched off.
            let (origin, dir, active) = group_lanes(&rays, &mut rng, g % 5 == 4);
            let t_max = if g % 2 == 0 { f32::INFINITY } else { uniform(&mut rng, 1.0, 12.0) };
            let mut together = [None; N];
            let mut order = Vec::new();
            scene.intersect_lanes(&origin, &dir, active, t_max, |i, hit| {
                together[i] = Some(hit);
                order.push(i);
            });
            assert!(order.is_sorted(), "lanes visited lowest first: {order:?}");
            // Shadow-ray lengths: some end before the closest hit, some after.
            let lengths = pathtrace::wide::simd::F32s::<N>::from_fn(|_| uniform(&mut rng, 0.5, 14.0));
            let blocked = scene.occluded_lanes(&origin, &dir, active, lengths);
            for (i, r) in rays.iter().enumerate() {
                let alone = if active.lane(i) { scene.intersect(r, t_max) } else { None };
                assert!(
                    identical(&together[i], &alone),
                    "scene {s} group {g} lane {i} {r:?}: {:?} vs {alone:?}",
                    together[i]
                );
                hits += alone.is_some() as usize;
                let shadowed = active.lane(i) && scene.occluded(r, lengths.0[i]);
                assert_eq!(blocked.lane(i), shadowed, "scene {s} group {g} lane {i} {r:?} to {}", lengths.0[i]);
                blocked_count += shadowed as usize;
            }
        }
    }
    assert!(hits > 2000 && ties_possible > 300, "{hits} hits, {ties_possible} edge rays");
    assert!(blocked_count > 1000 && blocked_count < 60 * 40 * N - 1000, "{blocked_count} blocked");
}

/// A group's rays that miss the box around the whole tree are dropped before the root is
/// visited (`Bvh::intersect_lanes`); the others go on. Groups that mix rays passing beside the
/// box, rays with a direction component of exactly zero (some along the planes of its faces,
/// where slab distances meet 0 · ∞) and rays into it give each ray what it gets alone: the
/// same primitive, and `t`, `u`, `v` bit for bit. (Rays along a face's plane find nothing
/// either way: the boxes are padded, so no primitive reaches the plane.)
#[test]
fn ray_groups_beside_and_along_the_tree_box_find_what_single_rays_find() {
    const N: usize = 8;
    let mut rng = Pcg32::new(19, 5);
    let (mut along, mut along_hits, mut hits) = (0, 0, 0);
    for s in 0..40 {
        let shapes = random_bounded_shapes(&mut rng, 30);
        let (bounds, kinds) = accel_inputs(&shapes);
        let bvh = Bvh::build(&bounds, &kinds);
        let prims = primitives(&shapes);
        let b = bvh.bounds();
        for g in 0..30 {
            let mut is_along = [false; N];
            let rays: [Ray; N] = std::array::from_fn(|i| match rng.next_u32() % 3 {
                // With a zero direction component (sometimes two), from a point inside the box
                // or on the plane of one of its faces.
                0 => {
                    is_along[i] = true;
                    let axis = rng.next_u32() as usize % 3;
                    let mut o = b.min + (b.max - b.min) * Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
                    match rng.next_u32() % 3 {
                        0 => o[axis] = b.min[axis],
                        1 => o[axis] = b.max[axis],
                        _ => {}
                    }
                    let mut d = direction(&mut rng);
                    d[axis] = 0.0;
                    if rng.next_u32().is_multiple_of(2) {
                        d[(axis + 1 + rng.next_u32() as usize % 2) % 3] = 0.0;
                    }
                    let mut fallback = Vec3::ONE;
                    fallback[axis] = 0.0;
                    Ray::new(o, d.normalize_or(fallback.normalize()))
                }
                // From outside the box, beside it or into it.
                1 => {
                    let o = b.min + (b.max - b.min) * 0.5 + direction(&mut rng) * (b.max - b.min).length();
                    let aim = b.min + (b.max - b.min) * Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
                    Ray::new(o, (aim - o + point(&mut rng, 3.0)).normalize())
                }
                _ => random_ray(&mut rng, &shapes),
            });
            let (origin, dir, active) = group_lanes(&rays, &mut rng, g % 4 == 3);
            let t_max = if g % 2 == 0 { f32::INFINITY } else { uniform(&mut rng, 1.0, 12.0) };
            let together = bvh.intersect_lanes(&prims[..], &origin, &dir, active, 0.0, t_max);
            for (i, r) in rays.iter().enumerate() {
                let alone = if active.lane(i) { bvh.intersect(&prims[..], r, 0.0, t_max) } else { None };
                let bits = |h: Option<(PrimHit, u32)>| h.map(|(h, p)| (p, [h.t, h.u, h.v].map(f32::to_bits)));
                assert_eq!(bits(together[i]), bits(alone), "set {s} group {g} lane {i} {r:?}");
                hits += alone.is_some() as usize;
                if is_along[i] && active.lane(i) {
                    along += 1;
                    along_hits += alone.is_some() as usize;
                }
            }
        }
    }
    assert!(
        along > 2000 && along_hits > 100 && hits > 1000,
        "{along} rays with zero components ({along_hits} hit), {hits} hits"
    );
}
