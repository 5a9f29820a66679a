//! Where a scene keeps its bounded primitives: single shapes (quads, spheres, disks, lone
//! triangles) as [`Primitive`]s, and meshes in compact form ([`MeshGeometry`]: shared vertices
//! plus an index triple per triangle, with one material and light range per mesh). The BVH
//! names every bounded primitive by one index: shapes first, then each mesh's triangles in turn.

use crate::accel::{Packable, PrimitiveSet};
use crate::math::{Aabb, Ray, Vec3};
use crate::scene::Primitive;
use crate::shape::{with_unit_normals, MeshGeometry, PrimHit, Shape, Sphere, SurfacePoint, Triangle, TriangleCorners};

/// A mesh in a scene.
#[derive(Clone, Debug)]
pub(crate) struct SceneMesh {
    pub geometry: MeshGeometry,
    pub material: u32,
    /// Light of triangle 0 (triangle `i` has light `first_light + i`), or
    /// [`Primitive::NO_LIGHT`] for a mesh that does not emit.
    pub first_light: u32,
}

/// A flat quad (`origin + a·e1 + b·e2`, a, b ∈ [0, 1]) or triangle (a, b ≥ 0, a + b ≤ 1)
/// with its material and light; its front is along `e1 × e2`, as for [`Quad`](crate::shape::Quad) and
/// [`Triangle`](crate::shape::Triangle).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FlatPolygon {
    pub origin: Vec3,
    pub e1: Vec3,
    pub e2: Vec3,
    pub triangle: bool,
    /// A mesh triangle's vertex normals at its corners (`origin`, `origin + e1`,
    /// `origin + e2`), when they depart from its face: its shading normal interpolates them.
    pub corner_normals: Option<[Vec3; 3]>,
    pub material: u32,
    pub light: u32,
}

/// A sphere with its material and light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SceneSphere {
    pub sphere: Sphere,
    pub material: u32,
    pub light: u32,
}

/// The primitives of a scene made only of flat polygons and spheres.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct SmallSceneShapes {
    pub polygons: Vec<FlatPolygon>,
    pub spheres: Vec<SceneSphere>,
}

impl SmallSceneShapes {
    /// Polygons and spheres together.
    pub fn len(&self) -> usize {
        self.polygons.len() + self.spheres.len()
    }
}

/// The mesh triangle a hit record last gathered ([`PrimitiveStore::surface_unless_mesh_normals_reusing`]).
#[derive(Clone, Copy, Debug)]
pub struct LastTriangle {
    index: u32,
    corners: TriangleCorners,
    material: u32,
    light: u32,
}

/// Which stored item a primitive index names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Item {
    Shape(u32),
    MeshTriangle { mesh: u32, triangle: u32 },
}

/// The bounded primitives, indexed as the BVH was built over them.
#[derive(Clone, Debug, Default)]
pub(crate) struct PrimitiveStore {
    shapes: Vec<Primitive>,
    meshes: Vec<SceneMesh>,
    /// Index of each mesh's first triangle (after all shapes).
    mesh_starts: Vec<u32>,
    len: u32,
}

impl PrimitiveStore {
    pub fn new(shapes: Vec<Primitive>, meshes: Vec<SceneMesh>) -> Self {
        let mut next = shapes.len() as u32;
        let mesh_starts = meshes
            .iter()
            .map(|m| {
                let start = next;
                next += m.geometry.len() as u32;
                start
            })
            .collect();
        Self { shapes, meshes, mesh_starts, len: next }
    }

    /// Number of bounded primitives (shapes and mesh triangles).
    pub fn len(&self) -> usize {
        self.len as usize
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    #[inline(always)]
    fn item(&self, index: u32) -> Item {
        if (index as usize) < self.shapes.len() {
            return Item::Shape(index);
        }
        // Meshes are few; a binary search over their starts.
        let mesh = self.mesh_starts.partition_point(|&s| s <= index) - 1;
        Item::MeshTriangle { mesh: mesh as u32, triangle: index - self.mesh_starts[mesh] }
    }

    /// Bounding boxes of all primitives, in index order (`None` never occurs: unbounded shapes
    /// are kept elsewhere; a missing box becomes the empty box).
    pub fn bounds(&self) -> Vec<Aabb> {
        let shapes = self.shapes.iter().map(|p| p.shape.bounds().unwrap_or_default());
        let tris = self.meshes.iter().flat_map(|m| (0..m.geometry.len() as u32).map(|i| m.geometry.bounds(i)));
        shapes.chain(tris).collect()
    }

    /// How the BVH stores each primitive, in index order: quads and triangles in SIMD
    /// packets, other shapes tested one by one.
    pub fn packables(&self) -> Vec<Packable> {
        let shape_kinds = self.shapes.iter().map(|p| match p.shape {
            Shape::Quad(q) => Packable::Quad(q),
            Shape::Triangle(t) => Packable::Triangle(t),
            _ => Packable::No,
        });
        let mesh_kinds = self
            .meshes
            .iter()
            .flat_map(|m| (0..m.geometry.len() as u32).map(|i| Packable::Triangle(m.geometry.triangle(i))));
        shape_kinds.chain(mesh_kinds).collect()
    }

    /// True if primitive `index`'s front is defined by its winding or edge order (triangles,
    /// quads, disks), so a mirroring transform turns it over; false for spheres and
    /// ellipsoids, whose front is their outside.
    pub fn front_follows_winding(&self, index: u32) -> bool {
        match self.item(index) {
            Item::Shape(i) => !matches!(self.shapes[i as usize].shape, Shape::Sphere(_) | Shape::Ellipsoid(_)),
            Item::MeshTriangle { .. } => true,
        }
    }

    /// Surface, material and light of primitive `index` at a hit.
    #[inline(always)]
    pub fn surface(&self, index: u32, ray: &Ray, hit: &PrimHit) -> (SurfacePoint, u32, u32) {
        let (surface, material, light, normalised) = self.surface_unless_mesh_normals(index, ray, hit);
        (if normalised { surface } else { with_unit_normals(surface) }, material, light)
    }

    /// [`PrimitiveStore::surface`], except that a mesh triangle's normals are left as
    /// [`Triangle::surface_before_normalising`] leaves them, for [`unit_normals`](crate::shape::unit_normals) to finish:
    /// the last value is false then.
    #[inline(always)]
    pub fn surface_unless_mesh_normals(&self, index: u32, ray: &Ray, hit: &PrimHit) -> (SurfacePoint, u32, u32, bool) {
        self.surface_unless_mesh_normals_reusing(index, ray, hit, &mut None)
    }

    /// [`PrimitiveStore::surface_unless_mesh_normals`], reusing the mesh triangle `last` of the
    /// previous hit when it is this one, and keeping this one's there otherwise: the gather of
    /// a triangle's corners through the index buffer was most of a mesh hit's record, and a
    /// group's camera rays hit the same few triangles.
    #[inline(always)]
    pub fn surface_unless_mesh_normals_reusing(
        &self,
        index: u32,
        ray: &Ray,
        hit: &PrimHit,
        last: &mut Option<LastTriangle>,
    ) -> (SurfacePoint, u32, u32, bool) {
        if let Some(l) = last {
            if l.index == index {
                return (l.corners.surface_before_normalising(hit), l.material, l.light, false);
            }
        }
        match self.item(index) {
            Item::Shape(i) => {
                let p = &self.shapes[i as usize];
                (p.shape.surface(ray, hit, &[]), p.material, p.light, true)
            }
            Item::MeshTriangle { mesh, triangle } => {
                let m = &self.meshes[mesh as usize];
                let light = if m.first_light == Primitive::NO_LIGHT { m.first_light } else { m.first_light + triangle };
                let corners = m.geometry.corners(triangle);
                *last = Some(LastTriangle { index, corners, material: m.material, light });
                (corners.surface_before_normalising(hit), m.material, light, false)
            }
        }
    }

    /// Every primitive as a flat polygon (a mesh triangle with the vertex normals its shading
    /// normal interpolates, unless they are its face's) or a sphere, or `None` if some
    /// primitive is another shape: what the estimator's brute-force lane intersector
    /// (`wide/geometry.rs`) can hold.
    pub fn small_scene_shapes(&self) -> Option<SmallSceneShapes> {
        let mut out = SmallSceneShapes { polygons: Vec::with_capacity(self.len()), spheres: Vec::new() };
        for p in &self.shapes {
            let (origin, e1, e2, triangle) = match p.shape {
                Shape::Quad(q) => (q.q, q.u, q.v, false),
                Shape::Triangle(t) if t.shading == Triangle::FLAT => (t.p0, t.e1, t.e2, true),
                Shape::Sphere(sphere) => {
                    out.spheres.push(SceneSphere { sphere, material: p.material, light: p.light });
                    continue;
                }
                _ => return None,
            };
            let corner_normals = None;
            out.polygons.push(FlatPolygon {
                origin,
                e1,
                e2,
                triangle,
                corner_normals,
                material: p.material,
                light: p.light,
            });
        }
        for m in &self.meshes {
            // A planar-shaded mesh's triangles shade with their face normals, as quads do.
            let smooth = !m.geometry.is_planar_shaded();
            for i in 0..m.geometry.len() as u32 {
                let t = m.geometry.triangle(i);
                let light = if m.first_light == Primitive::NO_LIGHT { m.first_light } else { m.first_light + i };
                let corner_normals = if smooth { m.geometry.corner_normals(i) } else { None };
                let polygon = FlatPolygon {
                    origin: t.p0,
                    e1: t.e1,
                    e2: t.e2,
                    triangle: true,
                    corner_normals,
                    material: m.material,
                    light,
                };
                out.polygons.push(polygon);
            }
        }
        Some(out)
    }

    /// Heap bytes, from the vectors' capacities.
    pub fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        self.shapes.capacity() * size_of::<Primitive>()
            + self.meshes.capacity() * size_of::<SceneMesh>()
            + self.meshes.iter().map(|m| m.geometry.memory_bytes()).sum::<usize>()
            + self.mesh_starts.capacity() * size_of::<u32>()
    }
}

impl PrimitiveSet for PrimitiveStore {
    #[inline(always)]
    fn intersect_one(&self, index: u32, ray: &Ray, t_min: f32, t_max: f32) -> Option<PrimHit> {
        match self.item(index) {
            Item::Shape(i) => self.shapes[i as usize].shape.intersect(ray, t_min, t_max),
            Item::MeshTriangle { mesh, triangle } => {
                self.meshes[mesh as usize].geometry.intersect(triangle, ray, t_min, t_max)
            }
        }
    }
}
