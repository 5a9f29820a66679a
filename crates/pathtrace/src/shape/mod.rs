//! Geometric shapes: one file per shape, gathered in the closed [`Shape`] enum that the
//! renderer dispatches on with `match` (no virtual calls, no allocation).

mod disk;
mod mesh;
mod mesh_geometry;
mod plane;
mod quad;
mod sphere;
mod triangle;
mod vertex_normals;

pub use disk::Disk;
pub use mesh::{MeshError, TriangleMesh};
pub use mesh_geometry::{MeshGeometry, TriangleCorners};
pub use plane::Plane;
pub use quad::Quad;
pub(crate) use sphere::sphere_hits;
pub use sphere::{Ellipsoid, Sphere};
pub use triangle::Triangle;
pub(crate) use triangle::{barycentric_mix, EDGE_SLACK};
pub use triangle::{unit_normals, with_unit_normals};
pub use vertex_normals::angle_weighted_normals;

use crate::math::{Aabb, Ray, Transform, Vec2, Vec3, Vec4};

/// Where a ray met a primitive: the distance and two shape-specific parameters (barycentrics
/// for triangles, edge coordinates for quads) from which the surface is rebuilt on demand.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimHit {
    pub t: f32,
    pub u: f32,
    pub v: f32,
}

/// Local surface geometry at a hit point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    pub p: Vec3,
    /// Unit geometric normal, oriented as the shape defines its front (outward for closed
    /// shapes, `u × v` for quads, counter-clockwise winding for triangles).
    pub n_geometric: Vec3,
    /// Unit shading normal (interpolated vertex normals on meshes), on the same side as
    /// `n_geometric`.
    pub n_shading: Vec3,
    pub uv: Vec2,
    /// ∂p/∂u: the direction of increasing `u` (not normalised), from which the shading frame's
    /// first tangent is taken for anisotropic materials, as in Mitsuba 3. Zero where `uv` has no
    /// derivative (a triangle without texture coordinates, a sphere's pole): the frame then
    /// takes Mitsuba's fallback, the `coordinate_system` tangent of the geometric normal
    /// ([`SurfacePoint::tangent`]).
    pub dpdu: Vec3,
    /// ∂p/∂v, the direction of increasing `v` (not normalised): with `dpdu` it spans the
    /// tangent plane that bump maps tilt (Mitsuba 3's `dp_dv`); zero where `dpdu` is.
    pub dpdv: Vec3,
    /// The mesh's own tangent at the hit (glTF's `TANGENT` attribute, interpolated): xyz the
    /// tangent, w the bitangent's sign (±1, bitangent = w · n × tangent, glTF 2.0 §3.7.2.1);
    /// all zero where the mesh has none (every other shape), and the tangent then comes from
    /// the texture coordinates ([`SurfacePoint::tangent`]).
    pub vertex_tangent: Vec4,
}

impl SurfacePoint {
    /// The tangent that normal maps and anisotropic materials align their frame's first axis
    /// with: the mesh's own tangent where it has one, else `dpdu`, or when that is zero the
    /// first axis of the geometric normal's Duff et al. basis (Mitsuba 3's
    /// `coordinate_system(n)` for meshes without texture coordinates).
    #[inline(always)]
    pub fn tangent(&self) -> Vec3 {
        if self.vertex_tangent.w != 0.0 {
            self.vertex_tangent.truncate()
        } else if self.dpdu == Vec3::ZERO {
            crate::math::Frame::from_normal(self.n_geometric).s
        } else {
            self.dpdu
        }
    }

    /// The sign of the bitangent relative to n × tangent: −1 where the mesh's own tangents say
    /// its texture space is mirrored (a tangent's w < 0), else +1.
    #[inline(always)]
    pub fn bitangent_sign(&self) -> f32 {
        if self.vertex_tangent.w < 0.0 {
            -1.0
        } else {
            1.0
        }
    }
}

/// Every shape the engine intersects.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    Sphere(Sphere),
    Ellipsoid(Ellipsoid),
    Plane(Plane),
    Quad(Quad),
    Triangle(Triangle),
    Disk(Disk),
}

impl Shape {
    /// Closest intersection with `t` in `[t_min, t_max]`.
    #[inline(always)]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<PrimHit> {
        match self {
            Shape::Sphere(s) => s.intersect(ray, t_min, t_max),
            Shape::Ellipsoid(s) => s.intersect(ray, t_min, t_max),
            Shape::Plane(s) => s.intersect(ray, t_min, t_max),
            Shape::Quad(s) => s.intersect(ray, t_min, t_max),
            Shape::Triangle(s) => s.intersect(ray, t_min, t_max),
            Shape::Disk(s) => s.intersect(ray, t_min, t_max),
        }
    }

    /// Rebuilds the surface at a hit found by [`Shape::intersect`] with the same ray.
    #[inline(always)]
    pub fn surface(&self, ray: &Ray, hit: &PrimHit, vertex_normals: &[[Vec3; 3]]) -> SurfacePoint {
        match self {
            Shape::Sphere(s) => s.surface(ray, hit),
            Shape::Ellipsoid(s) => s.surface(ray, hit),
            Shape::Plane(s) => s.surface(ray, hit),
            Shape::Quad(s) => s.surface(ray, hit),
            Shape::Triangle(s) => s.surface(hit, vertex_normals),
            Shape::Disk(s) => s.surface(ray, hit),
        }
    }

    /// Bounding box, or `None` for unbounded shapes (planes), which the BVH keeps aside.
    pub fn bounds(&self) -> Option<Aabb> {
        match self {
            Shape::Sphere(s) => Some(s.bounds()),
            Shape::Ellipsoid(s) => Some(s.bounds()),
            Shape::Plane(_) => None,
            Shape::Quad(s) => Some(s.bounds()),
            Shape::Triangle(s) => Some(s.bounds()),
            Shape::Disk(s) => Some(s.bounds()),
        }
    }

    /// Surface area, when finite and known in closed form.
    pub fn area(&self) -> Option<f32> {
        match self {
            Shape::Sphere(s) => Some(s.area()),
            Shape::Ellipsoid(_) | Shape::Plane(_) => None,
            Shape::Quad(s) => Some(s.area()),
            Shape::Triangle(s) => Some(s.area()),
            Shape::Disk(s) => Some(s.area()),
        }
    }

    /// Applies a transform (baked into the geometry; spheres under non-uniform scale become
    /// ellipsoids). `None` if the result is degenerate.
    pub fn transformed(&self, t: &Transform) -> Option<Shape> {
        if t.is_identity() {
            return Some(self.clone());
        }
        match self {
            Shape::Sphere(s) => Some(s.transformed(t)),
            Shape::Ellipsoid(s) => Some(Shape::Ellipsoid(s.transformed(t))),
            Shape::Plane(s) => Some(Shape::Plane(s.transformed(t))),
            Shape::Quad(s) => Quad::new(t.point(s.q), t.vector(s.u), t.vector(s.v)).map(Shape::Quad),
            Shape::Triangle(s) => {
                let [a, b, c] = s.vertices();
                Triangle::new(t.point(a), t.point(b), t.point(c), s.shading).map(Shape::Triangle)
            }
            Shape::Disk(s) => s.transformed(t).map(Shape::Disk),
        }
    }
}
