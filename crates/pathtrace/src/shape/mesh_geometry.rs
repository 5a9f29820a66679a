//! The compact form in which a scene keeps a mesh: one shared vertex buffer (positions and the
//! optional normals and texture coordinates, already placed in the world) and one index triple
//! per triangle — 12 bytes of indices plus the triangle's share of the vertices, instead of a
//! full shape per triangle. Triangles are rebuilt from their corners when they are needed (for
//! the BVH's packets, for shading a hit, for the brute-force reference).

use super::triangle::{barycentric_mix, with_unit_normals};
use super::{MeshError, PrimHit, SurfacePoint, Triangle, TriangleMesh};
use crate::math::{Aabb, Ray, Transform, Vec2, Vec3, Vec4};

/// A placed mesh without degenerate triangles.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshGeometry {
    positions: Vec<Vec3>,
    normals: Option<Vec<Vec3>>,
    uvs: Option<Vec<Vec2>>,
    /// The mesh's own tangents (xyz placed as vectors, w the bitangent's sign in the world).
    tangents: Option<Vec<Vec4>>,
    indices: Vec<[u32; 3]>,
}

impl MeshGeometry {
    /// Validates `mesh`, places it by `transform` (normals by its inverse transpose) and drops
    /// its degenerate triangles (meshes often contain a few); returns the geometry and how many
    /// were dropped.
    pub fn new(mesh: &TriangleMesh, transform: &Transform) -> Result<(MeshGeometry, usize), MeshError> {
        mesh.validate()?;
        let positions: Vec<Vec3> = mesh.positions.iter().map(|&p| transform.point(p)).collect();
        let normals: Option<Vec<Vec3>> =
            mesh.normals.as_ref().map(|ns| ns.iter().map(|&n| transform.normal(n)).collect());
        // A tangent moves with the surface (a vector); a mirroring transform reverses the
        // handedness of (normal, tangent, bitangent), so the bitangent's sign turns over.
        let mirror = transform.matrix.determinant() < 0.0;
        let tangents: Option<Vec<Vec4>> = mesh.tangents.as_ref().map(|ts| {
            ts.iter().map(|&t| transform.vector(t.truncate()).extend(if mirror { -t.w } else { t.w })).collect()
        });
        let corners = |tri: &[u32; 3]| tri.map(|i| positions[i as usize]);
        // The same test (and arithmetic) as `Triangle::new`, so the kept triangles are exactly
        // those the per-triangle storage kept.
        let indices: Vec<[u32; 3]> = mesh
            .indices
            .iter()
            .filter(|tri| {
                let [a, b, c] = corners(tri);
                Triangle::new(a, b, c, Triangle::FLAT).is_some()
            })
            .copied()
            .collect();
        let skipped = mesh.indices.len() - indices.len();
        let mut geometry = MeshGeometry { positions, normals, uvs: mesh.uvs.clone(), tangents, indices };
        geometry.shrink_to_fit();
        Ok((geometry, skipped))
    }

    /// Number of (non-degenerate) triangles.
    pub fn len(&self) -> usize {
        self.indices.len()
    }

    pub fn is_empty(&self) -> bool {
        self.indices.is_empty()
    }

    /// True if the mesh has vertex normals (its shading normals are interpolated).
    pub fn has_normals(&self) -> bool {
        self.normals.is_some()
    }

    /// True if every triangle's shading normal is its face normal: no vertex normals, or vertex
    /// normals all parallel to the faces they touch (a planar mesh given smooth normals, as
    /// Mitsuba gives meshes without normals). The shading normal is kept on the face's side
    /// ([`Triangle::surface_with`]), so either orientation counts. "Parallel" allows a cosine
    /// two float steps below 1 (an angle under 5·10⁻⁴ rad), the rounding of normals computed
    /// from the faces.
    pub fn is_planar_shaded(&self) -> bool {
        // Floats below 1 are ε/2 apart: two steps.
        const PARALLEL: f32 = 1.0 - f32::EPSILON;
        let Some(normals) = &self.normals else { return true };
        (0..self.len() as u32).all(|i| {
            let t = self.triangle(i);
            let face = t.e1.cross(t.e2).normalize();
            self.indices[i as usize]
                .iter()
                .all(|&v| normals[v as usize].normalize_or_zero().dot(face).abs() >= PARALLEL)
        })
    }

    /// Triangle `i` (flat: its vertex normals stay in the mesh). Built without
    /// [`Triangle::new`]'s degeneracy test, which hit records need not repeat: the mesh's
    /// triangles were checked when it was built.
    #[inline(always)]
    pub fn triangle(&self, i: u32) -> Triangle {
        let [a, b, c] = self.indices[i as usize].map(|v| self.positions[v as usize]);
        Triangle { p0: a, e1: b - a, e2: c - a, shading: Triangle::FLAT }
    }

    /// The vertex normals at triangle `i`'s corners, if the mesh has them.
    #[inline(always)]
    pub fn corner_normals(&self, i: u32) -> Option<[Vec3; 3]> {
        let tri = self.indices[i as usize];
        self.normals.as_ref().map(|ns| tri.map(|v| ns[v as usize]))
    }

    /// Bounding box of triangle `i`.
    pub fn bounds(&self, i: u32) -> Aabb {
        Aabb::from_points(&self.indices[i as usize].map(|v| self.positions[v as usize]))
    }

    /// Ray test of triangle `i` (the scalar Möller–Trumbore test the packets agree with).
    #[inline(always)]
    pub fn intersect(&self, i: u32, ray: &Ray, t_min: f32, t_max: f32) -> Option<PrimHit> {
        self.triangle(i).intersect(ray, t_min, t_max)
    }

    /// The surface of triangle `i` at a hit: interpolated vertex normals and texture
    /// coordinates when the mesh has them.
    #[inline(always)]
    pub fn surface(&self, i: u32, hit: &PrimHit) -> SurfacePoint {
        with_unit_normals(self.surface_before_normalising(i, hit))
    }

    /// [`MeshGeometry::surface`] with its normals as [`Triangle::surface_before_normalising`]
    /// leaves them, for [`unit_normals`](super::triangle::unit_normals) to finish.
    #[inline(always)]
    pub fn surface_before_normalising(&self, i: u32, hit: &PrimHit) -> SurfacePoint {
        self.corners(i).surface_before_normalising(hit)
    }

    /// What a hit record reads of triangle `i`: its edges and its corners' vertex data.
    #[inline(always)]
    pub fn corners(&self, i: u32) -> TriangleCorners {
        let tri = self.indices[i as usize];
        TriangleCorners {
            triangle: self.triangle(i),
            normals: self.corner_normals(i),
            uvs: self.uvs.as_ref().map(|uv| tri.map(|v| uv[v as usize])),
            tangents: self.tangents.as_ref().map(|ts| tri.map(|v| ts[v as usize])),
        }
    }

    /// The texture coordinates at triangle `i`'s corners; without them on the mesh, those that
    /// make a hit's uv its barycentrics ((0, 0), (1, 0), (0, 1)), as [`MeshGeometry::surface`]
    /// reports them.
    pub fn corner_uvs(&self, i: u32) -> [Vec2; 3] {
        match &self.uvs {
            Some(uv) => self.indices[i as usize].map(|v| uv[v as usize]),
            None => [Vec2::ZERO, Vec2::X, Vec2::Y],
        }
    }

    /// Releases spare capacity (the memory accounting counts capacities).
    pub fn shrink_to_fit(&mut self) {
        self.positions.shrink_to_fit();
        self.indices.shrink_to_fit();
        if let Some(n) = &mut self.normals {
            n.shrink_to_fit();
        }
        if let Some(uv) = &mut self.uvs {
            uv.shrink_to_fit();
        }
        if let Some(t) = &mut self.tangents {
            t.shrink_to_fit();
        }
    }

    /// Heap bytes, from the vectors' capacities.
    pub fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        self.positions.capacity() * size_of::<Vec3>()
            + self.normals.as_ref().map_or(0, |n| n.capacity() * size_of::<Vec3>())
            + self.uvs.as_ref().map_or(0, |n| n.capacity() * size_of::<Vec2>())
            + self.tangents.as_ref().map_or(0, |n| n.capacity() * size_of::<Vec4>())
            + self.indices.capacity() * size_of::<[u32; 3]>()
    }
}

/// A mesh triangle as a hit record reads it ([`MeshGeometry::corners`]): gathered once, it serves
/// every hit on the triangle (a group's camera rays often hit one triangle together).
#[derive(Clone, Copy, Debug)]
pub struct TriangleCorners {
    triangle: Triangle,
    normals: Option<[Vec3; 3]>,
    uvs: Option<[Vec2; 3]>,
    tangents: Option<[Vec4; 3]>,
}

impl TriangleCorners {
    /// [`MeshGeometry::surface_before_normalising`] of this triangle.
    #[inline(always)]
    pub fn surface_before_normalising(&self, hit: &PrimHit) -> SurfacePoint {
        let mut surface = self.triangle.surface_before_normalising(hit, self.normals, self.uvs);
        if let Some(ts) = self.tangents {
            surface.vertex_tangent = interpolated_tangent(ts, hit);
        }
        surface
    }
}

/// The corners' tangents interpolated at a hit (barycentrics as [`Triangle::surface_with`]
/// takes them), with the first corner's bitangent sign (glTF gives one per vertex, the same
/// over a face unless the texture space folds there); zero, so that the texture coordinates'
/// tangent is used, where they cancel.
#[inline(always)]
fn interpolated_tangent([t0, t1, t2]: [Vec4; 3], hit: &PrimHit) -> Vec4 {
    let (b1, b2) = (hit.u.max(0.0), hit.v.max(0.0));
    let t = barycentric_mix(b1, b2, [t0, t1, t2].map(Vec4::truncate));
    if t.length_squared() > 0.0 && t.is_finite() {
        t.extend(t0.w)
    } else {
        Vec4::ZERO
    }
}

/// The BVH asks a mesh for the triangles it does not keep in packets (none, when built with
/// `Packable::Triangle` kinds), by triangle index.
impl crate::accel::PrimitiveSet for MeshGeometry {
    #[inline(always)]
    fn intersect_one(&self, index: u32, ray: &Ray, t_min: f32, t_max: f32) -> Option<PrimHit> {
        self.intersect(index, ray, t_min, t_max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad_mesh() -> TriangleMesh {
        TriangleMesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y, 2.0 * Vec3::X],
            // The last triangle is degenerate (three collinear corners).
            indices: vec![[0, 1, 2], [0, 2, 3], [0, 1, 4]],
            normals: Some(vec![Vec3::Z, Vec3::Z, Vec3::new(0.0, 0.6, 0.8), Vec3::Z, Vec3::Z]),
            uvs: Some(vec![Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y, Vec2::X]),
            tangents: None,
        }
    }

    #[test]
    fn degenerate_triangles_are_dropped_and_counted() {
        let (m, skipped) = MeshGeometry::new(&quad_mesh(), &Transform::IDENTITY).unwrap();
        assert_eq!((m.len(), skipped), (2, 1));
    }

    #[test]
    fn hits_report_interpolated_uv_and_normal() {
        let (m, _) = MeshGeometry::new(&quad_mesh(), &Transform::IDENTITY).unwrap();
        let ray = Ray::new(Vec3::new(0.75, 0.25, 1.0), -Vec3::Z);
        let hit = m.intersect(0, &ray, 0.0, 10.0).unwrap();
        let s = m.surface(0, &hit);
        // Barycentrics (b1, b2) = (0.5, 0.25) on corners 0, 1, 2: uv = 0.5·(1,0) + 0.25·(1,1).
        assert!((s.uv - Vec2::new(0.75, 0.25)).length() < 1e-6, "{:?}", s.uv);
        assert!((s.p - Vec3::new(0.75, 0.25, 0.0)).length() < 1e-6);
        assert!(s.n_shading.y > 0.0 && (s.n_shading.length() - 1.0).abs() < 1e-5);
        assert_eq!(s.n_geometric, Vec3::Z);
    }

    #[test]
    fn without_uvs_the_barycentrics_are_the_uv() {
        let mut mesh = quad_mesh();
        mesh.uvs = None;
        let (m, _) = MeshGeometry::new(&mesh, &Transform::IDENTITY).unwrap();
        let hit = PrimHit { t: 1.0, u: 0.5, v: 0.25 };
        assert_eq!(m.surface(0, &hit).uv, Vec2::new(0.5, 0.25));
    }

    #[test]
    fn invalid_meshes_are_rejected() {
        let mut mesh = quad_mesh();
        mesh.indices.push([0, 1, 9]);
        assert!(matches!(MeshGeometry::new(&mesh, &Transform::IDENTITY), Err(MeshError::IndexOutOfRange { .. })));
    }
}
