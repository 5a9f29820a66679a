//! Brute-force intersection of a group of rays with every polygon and sphere of a small scene.
//!
//! Why no tree: for a few dozen primitives a BVH visit costs more than the tests it saves (the
//! Cornell box's 19 quads sit under one or two wide nodes anyway), and testing one
//! primitive against 8 or 16 rays at once keeps every SIMD lane busy on incoherent rays, which
//! packet traversal of a tree cannot. Scenes above [`MAX_FLAT_POLYGONS`] primitives use the BVH
//! one lane at a time instead.
//!
//! Each polygon is tested as a plane and two edge coordinates, as [`crate::shape::Quad`] does
//! ("Ray Tracing: The Next Week" §6): with n = e1 × e2, t = (n·q − n·o) / n·d, and for
//! h = o + t·d − q the coordinates a = h·ẽ1, b = h·ẽ2 with the dual vectors
//! ẽ1 = (e2 × n)/|n|², ẽ2 = (n × e1)/|n|². A quad holds a, b ∈ [0, 1]; a triangle a, b ≥ 0,
//! a + b ≤ 1 (a and b are then its barycentric coordinates). Spheres take the shape's own
//! test ([`Sphere::hits`], written for lanes), and their hits its re-projected point and normal.

use super::boxes::Parallelepiped;
use super::simd::{F32s, Ms, Vec3s};
use crate::math::Vec3;
use crate::primitive_store::{FlatPolygon, SmallSceneShapes};
use crate::scene::Primitive;
use crate::shape::{barycentric_mix, Sphere, EDGE_SLACK};

/// Largest scene tested by brute force; chosen by `pathtrace bench` on the Cornell box (19)
/// against meshes of a few hundred triangles, where the BVH wins.
pub const MAX_FLAT_POLYGONS: usize = 64;

/// One polygon's intersection data.
#[derive(Clone, Copy, Debug)]
struct Plane {
    n: Vec3,
    n_dot_q: f32,
    q: Vec3,
    e1_dual: Vec3,
    e2_dual: Vec3,
}

/// The polygons and spheres of a small scene, with what shading needs at a hit.
#[derive(Clone, Debug)]
pub struct FlatGeometry {
    boxes: Vec<Parallelepiped>,
    quads: Vec<Plane>,
    triangles: Vec<Plane>,
    spheres: Vec<Sphere>,
    /// Per polygon (the boxes' faces first, six per box, then quads, then triangles): unit
    /// normal along e1 × e2.
    normals: Vec<Vec3>,
    /// Per triangle (as `triangles`), the vertex normals its shading normal interpolates, if
    /// any; empty when no triangle has them.
    corner_normals: Vec<Option<[Vec3; 3]>>,
    /// Per primitive (the polygons in that order, then the spheres): material and light.
    materials: Vec<u32>,
    lights: Vec<u32>,
}

/// The rays' closest hits: distance and primitive (`u32::MAX` where nothing was hit).
#[derive(Clone, Copy, Debug)]
pub struct Hits<const N: usize> {
    pub t: F32s<N>,
    pub polygon: [u32; N],
}

impl FlatGeometry {
    /// `None` when some polygon is degenerate (the scene builder rejects those already).
    pub(crate) fn new(shapes: &SmallSceneShapes) -> Option<Self> {
        let (polygons, spheres) = (&join_parallelograms(&shapes.polygons), &shapes.spheres);
        let (quad_list, triangles): (Vec<&FlatPolygon>, Vec<&FlatPolygon>) = polygons.iter().partition(|p| !p.triangle);
        // Runs of six quads that bound a box (as `box` objects make them) become one box.
        let (mut boxes, mut box_faces, mut quads) = (Vec::new(), Vec::new(), Vec::new());
        let mut i = 0;
        while i < quad_list.len() {
            let run: Vec<FlatPolygon> = quad_list[i..(i + 6).min(quad_list.len())].iter().map(|p| **p).collect();
            if let Some(b) = Parallelepiped::recognise(&run) {
                boxes.push(b);
                box_faces.extend(&quad_list[i..i + 6]);
                i += 6;
            } else {
                quads.push(quad_list[i]);
                i += 1;
            }
        }
        let plane = |p: &&FlatPolygon| {
            let n = p.e1.cross(p.e2);
            let n2 = n.length_squared();
            (n2 > 0.0 && n2.is_finite()).then(|| Plane {
                n,
                n_dot_q: n.dot(p.origin),
                q: p.origin,
                e1_dual: p.e2.cross(n) / n2,
                e2_dual: n.cross(p.e1) / n2,
            })
        };
        let ordered = || box_faces.iter().chain(&quads).chain(&triangles);
        let corner_normals = if triangles.iter().any(|p| p.corner_normals.is_some()) {
            triangles.iter().map(|p| p.corner_normals).collect()
        } else {
            Vec::new()
        };
        Some(Self {
            boxes,
            quads: quads.iter().map(plane).collect::<Option<_>>()?,
            triangles: triangles.iter().map(plane).collect::<Option<_>>()?,
            normals: ordered().map(|p| p.e1.cross(p.e2).normalize()).collect(),
            corner_normals,
            materials: ordered().map(|p| p.material).chain(spheres.iter().map(|s| s.material)).collect(),
            lights: ordered().map(|p| p.light).chain(spheres.iter().map(|s| s.light)).collect(),
            spheres: spheres.iter().map(|s| s.sphere).collect(),
        })
    }

    /// Unit normal (front side), material and light of primitive `i`; a sphere's normal
    /// depends on the point: it is the caller's to complete with [`FlatGeometry::sphere_hit`].
    #[inline(always)]
    pub fn polygon(&self, i: u32) -> (Vec3, u32, u32) {
        let i = i as usize;
        (self.normals.get(i).copied().unwrap_or(Vec3::Z), self.materials[i], self.lights[i])
    }

    /// True if some triangle shades with interpolated vertex normals
    /// ([`FlatGeometry::interpolated_normal`]).
    #[inline(always)]
    pub fn has_corner_normals(&self) -> bool {
        !self.corner_normals.is_empty()
    }

    /// The shading normal, not yet normalised, of polygon `i` at its point `p` if `i` is a
    /// triangle with vertex normals: those interpolated at p's barycentric coordinates, which
    /// are its edge coordinates (a, b) of the hit test (as [`Triangle::surface_before_normalising`](crate::shape::Triangle::surface_before_normalising)
    /// interpolates them at a hit's).
    #[inline(always)]
    pub fn interpolated_normal(&self, i: u32, p: Vec3) -> Option<Vec3> {
        let k = (i as usize).checked_sub(6 * self.boxes.len() + self.quads.len())?;
        let corners = (*self.corner_normals.get(k)?)?;
        let plane = &self.triangles[k];
        let h = p - plane.q;
        Some(barycentric_mix(h.dot(plane.e1_dual).max(0.0), h.dot(plane.e2_dual).max(0.0), corners))
    }

    /// True if the scene has spheres (whose hits [`FlatGeometry::sphere_hit`] completes).
    #[inline(always)]
    pub fn has_spheres(&self) -> bool {
        !self.spheres.is_empty()
    }

    /// Where a ray met primitive `i` at `p`, if it is a sphere: the re-projected point and its
    /// unit normal (`Sphere::point_and_normal`: outward unless the sphere is inward).
    #[inline(always)]
    pub fn sphere_hit(&self, i: u32, p: Vec3) -> Option<(Vec3, Vec3)> {
        let k = (i as usize).checked_sub(self.normals.len())?;
        Some(self.spheres[k].point_and_normal(p))
    }

    /// Material of primitive `i`.
    #[cfg(test)]
    fn material(&self, i: u32) -> u32 {
        self.materials[i as usize]
    }

    /// Closest hits with t ∈ [0, t_max) of the lanes in `active`.
    #[inline(always)]
    pub fn intersect<const N: usize>(&self, o: &Vec3s<N>, d: &Vec3s<N>, active: Ms<N>, t_max: F32s<N>) -> Hits<N> {
        let mut best = F32s::<N>::select(active, t_max, F32s::<N>::ZERO);
        let mut polygon = [u32::MAX; N];
        for (k, b) in self.boxes.iter().enumerate() {
            let (hit, t, face) = b.test(o, d, best);
            best = F32s::select(hit, t, best);
            for i in 0..N {
                let id = 6 * k as u32 + face.0[i] as u32;
                polygon[i] = (id & hit.0[i]) | (polygon[i] & !hit.0[i]);
            }
        }
        let first_quad = 6 * self.boxes.len() as u32;
        for (k, plane) in self.quads.iter().enumerate() {
            let (hit, t) = plane.test::<N, false>(o, d, best);
            record(hit, t, first_quad + k as u32, &mut best, &mut polygon);
        }
        let first = first_quad + self.quads.len() as u32;
        for (k, plane) in self.triangles.iter().enumerate() {
            let (hit, t) = plane.test::<N, true>(o, d, best);
            record(hit, t, first + k as u32, &mut best, &mut polygon);
        }
        let first = self.normals.len() as u32;
        for (k, sphere) in self.spheres.iter().enumerate() {
            let (hit, t) = sphere.hits(o, d, F32s::ZERO, best);
            // The sphere's range is closed; a tie with a closer primitive keeps that one.
            let hit = hit & t.lt(best);
            record(hit, t, first + k as u32, &mut best, &mut polygon);
        }
        Hits { t: best, polygon }
    }

    /// Lanes of `active` whose ray meets a polygon with t ∈ [0, t_max).
    #[inline(always)]
    pub fn occluded<const N: usize>(&self, o: &Vec3s<N>, d: &Vec3s<N>, active: Ms<N>, t_max: F32s<N>) -> Ms<N> {
        let limit = F32s::<N>::select(active, t_max, F32s::<N>::ZERO);
        let mut blocked = Ms::<N>::NONE;
        for b in &self.boxes {
            blocked = blocked | b.test(o, d, limit).0;
            if !(active & !blocked).any() {
                return active;
            }
        }
        for plane in &self.quads {
            blocked = blocked | plane.test::<N, false>(o, d, limit).0;
            if !(active & !blocked).any() {
                return active;
            }
        }
        for plane in &self.triangles {
            blocked = blocked | plane.test::<N, true>(o, d, limit).0;
            if !(active & !blocked).any() {
                return active;
            }
        }
        for sphere in &self.spheres {
            let (hit, t) = sphere.hits(o, d, F32s::ZERO, limit);
            blocked = blocked | (hit & t.lt(limit));
            if !(active & !blocked).any() {
                return active;
            }
        }
        blocked & active
    }
}

/// Consecutive triangles (a, b, c), (a, c, d) that split a parallelogram along its diagonal,
/// as meshes store a quad face, joined into that quad: one test instead of two (the walls and
/// boxes of an OBJ Cornell box). Only where nothing tells the halves apart: the same material,
/// face normals, and no light (a light's triangles are sampled one by one).
fn join_parallelograms(polygons: &[FlatPolygon]) -> Vec<FlatPolygon> {
    let mut out = Vec::with_capacity(polygons.len());
    let mut i = 0;
    while i < polygons.len() {
        if let Some(quad) = polygons.get(i + 1).and_then(|next| parallelogram(&polygons[i], next)) {
            out.push(quad);
            i += 2;
        } else {
            out.push(polygons[i]);
            i += 1;
        }
    }
    out
}

/// The quad of triangles (a, b, c) and (a, c, d) if d − a + b − a is c − a (to 10⁻⁵ of the
/// longer edge: the corners' rounding). The second may list its corners from any of the three
/// (as (c, d, a) or (d, a, c): the same triangle, facing the same way), as exporters that
/// triangulate quads themselves do (Veach's scene: (a, b, c), (c, d, a)); its corners are then
/// matched to a and c to the same 10⁻⁵.
fn parallelogram(first: &FlatPolygon, second: &FlatPolygon) -> Option<FlatPolygon> {
    let plain = |p: &FlatPolygon| p.triangle && p.corner_normals.is_none() && p.light == Primitive::NO_LIGHT;
    if !(plain(first) && plain(second) && first.material == second.material) {
        return None;
    }
    let size = first.e1.length().max(first.e2.length()).max(second.e1.length()).max(second.e2.length());
    let near = |p: Vec3, q: Vec3| (p - q).length() <= 1e-5 * size;
    let (a, c) = (first.origin, first.origin + first.e2);
    let corners = [second.origin, second.origin + second.e1, second.origin + second.e2];
    // d − a by the second's own edges, one rounding from its corners: as stored when it starts
    // at a (the loader's fan, bit for bit as before), else the difference of two edges.
    let to_d = if first.origin == second.origin && first.e2 == second.e1 {
        second.e2
    } else if near(corners[1], a) && near(corners[2], c) {
        -second.e1
    } else if near(corners[2], a) && near(corners[0], c) {
        second.e1 - second.e2
    } else {
        return None;
    };
    let (u, v) = (first.e1, to_d);
    ((u + v - first.e2).length() <= 1e-5 * u.length().max(v.length())).then_some(FlatPolygon {
        e1: u,
        e2: v,
        triangle: false,
        ..*first
    })
}

#[inline(always)]
fn record<const N: usize>(hit: Ms<N>, t: F32s<N>, k: u32, best: &mut F32s<N>, polygon: &mut [u32; N]) {
    *best = F32s::<N>::select(hit, t, *best);
    for i in 0..N {
        polygon[i] = (k & hit.0[i]) | (polygon[i] & !hit.0[i]);
    }
}

impl Plane {
    /// Lanes hitting this polygon at 0 ≤ t < limit, and their t.
    #[inline(always)]
    fn test<const N: usize, const TRIANGLE: bool>(
        &self,
        o: &Vec3s<N>,
        d: &Vec3s<N>,
        limit: F32s<N>,
    ) -> (Ms<N>, F32s<N>) {
        let n = Vec3s::<N>::splat(self.n);
        let denom = n.dot(d);
        let t = (F32s::<N>::splat(self.n_dot_q) - n.dot(o)) / denom;
        // Ordered comparisons are false for NaN (rays parallel to the plane).
        let in_range = t.ge(F32s::<N>::ZERO) & t.lt(limit);
        let q = Vec3s::<N>::splat(self.q);
        let h = Vec3s { x: o.x + t * d.x - q.x, y: o.y + t * d.y - q.y, z: o.z + t * d.z - q.z };
        let a = h.dot(&Vec3s::<N>::splat(self.e1_dual));
        let b = h.dot(&Vec3s::<N>::splat(self.e2_dual));
        let lo = F32s::<N>::splat(-EDGE_SLACK);
        let hi = F32s::<N>::splat(1.0 + EDGE_SLACK);
        let inside =
            if TRIANGLE { a.ge(lo) & b.ge(lo) & (a + b).le(hi) } else { a.ge(lo) & a.le(hi) & b.ge(lo) & b.le(hi) };
        (in_range & inside, t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Ray;
    use crate::math::Transform;
    use crate::primitive_store::SceneSphere;
    use crate::sampling::Pcg32;
    use crate::shape::{Quad, Triangle};
    use crate::wide::simd::LANES_256 as N;

    fn random_vec(rng: &mut Pcg32, scale: f32) -> Vec3 {
        Vec3::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5, rng.next_f32() - 0.5) * scale
    }

    /// Casts 4000 groups of random rays at `shapes` and compares the brute-force hits with
    /// the scalar quad, triangle and sphere tests; returns how many rays hit.
    fn assert_agrees_with_scalar(shapes: &SmallSceneShapes, rng: &mut Pcg32) -> u32 {
        let geometry = FlatGeometry::new(shapes).unwrap();
        let scalar_hit = |ray: &Ray, t_max: f32| -> Option<(f32, u32)> {
            let mut best: Option<(f32, u32)> = None;
            for p in &shapes.polygons {
                let limit = best.map_or(t_max, |b| b.0);
                let hit = if p.triangle {
                    Triangle::new(p.origin, p.origin + p.e1, p.origin + p.e2, Triangle::FLAT)?
                        .intersect(ray, 0.0, limit)
                } else {
                    Quad::new(p.origin, p.e1, p.e2)?.intersect(ray, 0.0, limit)
                };
                if let Some(h) = hit {
                    best = Some((h.t, p.material));
                }
            }
            for s in &shapes.spheres {
                let limit = best.map_or(t_max, |b| b.0);
                if let Some(h) = s.sphere.intersect(ray, 0.0, limit).filter(|h| h.t < limit) {
                    best = Some((h.t, s.material));
                }
            }
            best
        };
        let (mut hits, mut disagreements) = (0, 0);
        for _ in 0..4000 {
            let rays: Vec<Ray> =
                (0..N).map(|_| Ray::new(random_vec(rng, 6.0), random_vec(rng, 2.0).normalize())).collect();
            let o = Vec3s::<N>::from_fn(|i| rays[i].origin);
            let d = Vec3s::<N>::from_fn(|i| rays[i].dir);
            let t_max = F32s::from_fn(|i| if i == 5 { 1.5 } else { f32::INFINITY });
            let active = Ms::from_fn(|i| i != 2);
            let wide = geometry.intersect(&o, &d, active, t_max);
            let blocked = geometry.occluded(&o, &d, active, t_max);
            for (i, ray) in rays.iter().enumerate() {
                if !active.lane(i) {
                    assert_eq!(wide.polygon[i], u32::MAX);
                    assert!(!blocked.lane(i));
                    continue;
                }
                let expect = scalar_hit(ray, t_max.0[i]);
                let got = (wide.polygon[i] != u32::MAX).then(|| (wide.t.0[i], geometry.material(wide.polygon[i])));
                hits += expect.is_some() as u32;
                match (expect, got) {
                    (Some((te, me)), Some((tg, mg))) => {
                        assert!((te - tg).abs() <= 1e-4 * te.max(1.0), "t {te} vs {tg}");
                        disagreements += (me != mg) as u32;
                    }
                    (None, None) => {}
                    // Grazing hits on an edge may fall either way by rounding.
                    _ => disagreements += 1,
                }
                assert_eq!(blocked.lane(i), got.is_some(), "any-hit agrees with closest-hit");
            }
        }
        assert!(disagreements <= 2, "{disagreements} rays of {hits} hits disagree");
        hits
    }

    fn random_polygon(rng: &mut Pcg32, k: u32) -> FlatPolygon {
        FlatPolygon {
            origin: random_vec(rng, 4.0),
            e1: random_vec(rng, 2.0),
            e2: random_vec(rng, 2.0),
            triangle: k.is_multiple_of(3),
            corner_normals: None,
            material: k,
            light: u32::MAX,
        }
    }

    /// Random quads, triangles and spheres against the scalar shape tests.
    #[test]
    fn brute_force_hits_agree_with_the_scalar_shape_tests() {
        let mut rng = Pcg32::new(7, 3);
        let polygons: Vec<FlatPolygon> = (0..40).map(|k| random_polygon(&mut rng, k)).collect();
        let spheres = (40..48)
            .map(|k| SceneSphere {
                sphere: Sphere::new(random_vec(&mut rng, 5.0), 0.2 + rng.next_f32()).unwrap(),
                material: k,
                light: u32::MAX,
            })
            .collect();
        let shapes = SmallSceneShapes { polygons, spheres };
        let hits = assert_agrees_with_scalar(&shapes, &mut rng);
        assert!(hits > 2000, "the test rays must hit often: {hits}");
    }

    /// Triangles with vertex normals (among quads and triangles without): at a brute-force
    /// hit the interpolated normal is the one the scalar triangle interpolates at its own hit
    /// of the same ray (its Möller–Trumbore barycentrics); polygons without vertex normals
    /// have none.
    #[test]
    fn interpolated_normals_agree_with_the_scalar_triangles() {
        let mut rng = Pcg32::new(5, 8);
        let polygons: Vec<FlatPolygon> = (0..40)
            .map(|k| {
                let mut p = random_polygon(&mut rng, k);
                if p.triangle && k % 2 == 1 {
                    let face = p.e1.cross(p.e2).normalize();
                    p.corner_normals = Some([0; 3].map(|_| 2.0 * face + random_vec(&mut rng, 2.0)));
                }
                p
            })
            .collect();
        let geometry =
            FlatGeometry::new(&SmallSceneShapes { polygons: polygons.clone(), spheres: Vec::new() }).unwrap();
        assert!(geometry.has_corner_normals());
        let (mut compared, mut without) = (0, 0);
        for _ in 0..8000 {
            let rays: Vec<Ray> =
                (0..N).map(|_| Ray::new(random_vec(&mut rng, 6.0), random_vec(&mut rng, 2.0).normalize())).collect();
            let o = Vec3s::<N>::from_fn(|i| rays[i].origin);
            let d = Vec3s::<N>::from_fn(|i| rays[i].dir);
            let hits = geometry.intersect(&o, &d, Ms::from_fn(|_| true), F32s::splat(f32::INFINITY));
            let p = o.add(&d.scale(hits.t));
            for (i, ray) in rays.iter().enumerate().filter(|(i, _)| hits.polygon[*i] != u32::MAX) {
                let polygon = &polygons[geometry.material(hits.polygon[i]) as usize];
                let got = geometry.interpolated_normal(hits.polygon[i], p.lane(i));
                let Some(corners) = polygon.corner_normals else {
                    assert!(got.is_none());
                    without += 1;
                    continue;
                };
                let (a, e1, e2) = (polygon.origin, polygon.e1, polygon.e2);
                let triangle = Triangle::new(a, a + e1, a + e2, Triangle::FLAT).unwrap();
                // Grazing hits on an edge may fall either way by rounding.
                let Some(hit) = triangle.intersect(ray, 0.0, f32::INFINITY) else { continue };
                if (hit.t - hits.t.0[i]).abs() > 1e-4 * hit.t.max(1.0) {
                    continue;
                }
                let want = triangle.surface_before_normalising(&hit, Some(corners), None).n_shading.normalize();
                let got = got.expect("a triangle with vertex normals interpolates them").normalize();
                assert!((got - want).length() < 1e-3, "{got} vs {want}");
                compared += 1;
            }
        }
        // About 200 and 1700 per 2000 groups of rays.
        assert!(compared > 400 && without > 4000, "{compared} smooth hits, {without} others");
        let flat = FlatGeometry::new(&SmallSceneShapes {
            polygons: polygons.iter().map(|p| FlatPolygon { corner_normals: None, ..*p }).collect(),
            spheres: Vec::new(),
        });
        assert!(!flat.unwrap().has_corner_normals());
    }

    /// Parallelograms stored as two triangles (a, b, c), (a, c, d) (the second also listed from
    /// c or d) are tested as one quad where
    /// nothing tells the halves apart, and hit where the triangles are; a trapezoid, halves of
    /// different materials, a light's triangles and smooth-shaded ones stay triangles.
    #[test]
    fn parallelograms_split_into_triangles_are_joined() {
        let mut rng = Pcg32::new(3, 11);
        let mut polygons = Vec::new();
        // Corners on a grid of 2⁻⁶, so that the sums and differences below, and the join's, are
        // exact: which pairs join does not hang on rounding.
        let snap = |v: Vec3| (v * 64.0).round() / 64.0;
        for k in 0..24u32 {
            let p = random_polygon(&mut rng, 1);
            let p = FlatPolygon { origin: snap(p.origin), e1: snap(p.e1), e2: snap(p.e2), ..p };
            // Every fourth a trapezoid (its fourth corner d pulled in along e2).
            let d = if k % 4 == 3 { p.e2 * 0.7 } else { p.e2 };
            let half = |e1: Vec3, e2: Vec3| FlatPolygon { e1, e2, triangle: true, material: k, ..p };
            let (mut first, mut second) = (half(p.e1, p.e1 + p.e2), half(p.e1 + p.e2, d));
            // The second listed from a, from c (c, d, a) or from d (d, a, c).
            let (c, d) = (p.origin + p.e1 + p.e2, p.origin + d);
            match k % 3 {
                1 => (second.origin, second.e1, second.e2) = (c, d - c, p.origin - c),
                2 => (second.origin, second.e1, second.e2) = (d, p.origin - d, c - d),
                _ => {}
            }
            match k % 8 {
                1 => second.material = 100 + k,
                5 => (first.light, second.light) = (2 * k, 2 * k + 1),
                6 => first.corner_normals = Some([p.e1.cross(p.e2); 3]),
                _ => {}
            }
            polygons.extend([first, second]);
        }
        let shapes = SmallSceneShapes { polygons, spheres: Vec::new() };
        let geometry = FlatGeometry::new(&shapes).unwrap();
        // Of 24 pairs, 6 trapezoids and 3 for each other reason stay split.
        assert_eq!((geometry.quads.len(), geometry.triangles.len()), (9, 30));
        let hits = assert_agrees_with_scalar(&shapes, &mut rng);
        assert!(hits > 1000, "the test rays must hit often: {hits}");
    }

    /// Rotated, sheared boxes made by `Quad::box_faces` are recognised and hit where their six
    /// quads are, by rays from outside and inside them.
    #[test]
    fn boxes_are_recognised_and_agree_with_their_quads() {
        let mut rng = Pcg32::new(9, 4);
        let mut polygons = Vec::new();
        let mut k = 0;
        for b in 0..5 {
            let place = Transform::rotate_y(37.0 * b as f32)
                .then(&Transform::rotate_x(11.0 * b as f32))
                .then(&Transform::scale(Vec3::new(1.0, 0.5 + 0.3 * b as f32, 1.2)).unwrap())
                .then(&Transform::translate(random_vec(&mut rng, 5.0)));
            let size = Vec3::new(1.0 + rng.next_f32(), 1.0 + rng.next_f32(), 0.5 + rng.next_f32());
            for face in Quad::box_faces(-0.5 * size, 0.5 * size, &place).unwrap() {
                polygons.push(FlatPolygon {
                    origin: face.q,
                    e1: face.u,
                    e2: face.v,
                    triangle: false,
                    corner_normals: None,
                    material: k,
                    light: u32::MAX,
                });
                k += 1;
            }
            polygons.push(random_polygon(&mut rng, k));
            k += 1;
        }
        let shapes = SmallSceneShapes { polygons, spheres: Vec::new() };
        assert_eq!(FlatGeometry::new(&shapes).unwrap().boxes.len(), 5);
        let hits = assert_agrees_with_scalar(&shapes, &mut rng);
        assert!(hits > 2000, "the test rays must hit often: {hits}");
    }
}
