//! Smooth vertex normals computed from a mesh's faces, by Mitsuba 3's rule.
//!
//! Mitsuba 3 gives a PLY, OBJ or serialized mesh without stored normals smooth vertex normals
//! (unless its `face_normals` is true): each non-degenerate face adds its unit normal, weighted
//! by the face's interior angle at the corner, to each of its three vertices; the sums are then
//! normalised, and a vertex no valid face reaches gets the placeholder (1, 0, 0). Source: the
//! weighting of Thürmer and Wüthrich, "Computing Vertex Normals from Polygonal Facets" (JGT 3(1),
//! 1998), as Mitsuba 3.9's `Mesh::recompute_vertex_normals` (src/render/mesh.cpp) applies it —
//! in world space, after the shape's `to_world`, and per mesh vertex (an OBJ vertex is one
//! distinct position/uv/normal triple, so uv seams keep separate normals).
//!
//! In a scene file (the native format's mesh `normals` field; `"smooth"` is the default):
//! ```toml
//! [[objects]]
//! type = "mesh"
//! file = "bunny.ply"
//! normals = "smooth"   # or "face", "file", "computed"
//! material = "white"
//! ```

use super::TriangleMesh;
use crate::math::{Transform, Vec3};

/// The angle between unit vectors `a` and `b`, accurate near 0 and π (Mitsuba's `unit_angle`:
/// 2·asin(|a − b|/2), or π − 2·asin(|a + b|/2) for obtuse angles).
fn unit_angle(a: Vec3, b: Vec3) -> f32 {
    let half_asin = |x: f32| 2.0 * (0.5 * x).clamp(-1.0, 1.0).asin();
    if a.dot(b) < 0.0 {
        std::f32::consts::PI - half_asin((a + b).length())
    } else {
        half_asin((b - a).length())
    }
}

/// Angle-weighted vertex normals of the triangles `indices` over `positions` (already in the
/// space where the normals are wanted). Faces naming a vertex out of range are skipped (mesh
/// validation reports them); vertices no valid face touches get (1, 0, 0), as in Mitsuba.
pub fn angle_weighted_normals(positions: &[Vec3], indices: &[[u32; 3]]) -> Vec<Vec3> {
    let mut sums = vec![Vec3::ZERO; positions.len()];
    for tri in indices {
        let Some(p) = tri.iter().map(|&i| positions.get(i as usize).copied()).collect::<Option<Vec<_>>>() else {
            continue;
        };
        let n = (p[1] - p[0]).cross(p[2] - p[0]);
        let length_sqr = n.length_squared();
        if !(length_sqr > 0.0 && length_sqr.is_finite()) {
            continue;
        }
        let n = n / length_sqr.sqrt();
        for k in 0..3 {
            let a = (p[(k + 1) % 3] - p[k]).normalize();
            let b = (p[(k + 2) % 3] - p[k]).normalize();
            sums[tri[k] as usize] += n * unit_angle(a, b);
        }
    }
    sums.into_iter()
        .map(|n| {
            let length = n.length();
            if length != 0.0 && length.is_finite() {
                n / length
            } else {
                Vec3::X
            }
        })
        .collect()
}

impl TriangleMesh {
    /// Object-space normals which, once `transform` places the mesh, are the angle-weighted
    /// normals of the placed mesh (Mitsuba computes them after `to_world`, which matters under a
    /// non-uniform scale or shear).
    pub fn smooth_normals(&self, transform: &Transform) -> Vec<Vec3> {
        let placed: Vec<Vec3> = self.positions.iter().map(|&p| transform.point(p)).collect();
        let world = angle_weighted_normals(&placed, &self.indices);
        if transform.is_identity() {
            return world;
        }
        // A normal maps by the inverse transpose; its preimage is the transpose (of the matrix).
        let back = Transform { matrix: transform.inverse, inverse: transform.matrix };
        world.into_iter().map(|n| back.normal(n)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Transform;

    #[test]
    fn unit_angle_matches_acos() {
        for (a, b) in [(Vec3::X, Vec3::Y), (Vec3::X, Vec3::new(-1.0, 1e-3, 0.0).normalize()), (Vec3::X, Vec3::X)] {
            assert!((unit_angle(a, b) - a.dot(b).clamp(-1.0, 1.0).acos()).abs() < 1e-3);
        }
    }

    /// A vertex shared by a right-angled and a 45° corner of perpendicular faces leans towards
    /// the face with the larger angle by the ratio of the angles.
    #[test]
    fn normals_are_weighted_by_corner_angle() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(0.0, 0.0, 1.0), Vec3::new(0.0, 1.0, 1.0)];
        // Face 0 in the z = 0 plane (normal +z, right angle at vertex 0); face 1 in the x = 0
        // plane (normal +x, 45° at vertex 0).
        let idx = [[0, 1, 2], [0, 4, 3]];
        let n = angle_weighted_normals(&p, &idx);
        let expected = (Vec3::Z * std::f32::consts::FRAC_PI_2 + Vec3::X * std::f32::consts::FRAC_PI_4).normalize();
        assert!((n[0] - expected).length() < 1e-6, "{:?}", n[0]);
        assert!((n[1] - Vec3::Z).length() < 1e-6);
        assert!((n[4] - Vec3::X).length() < 1e-6);
    }

    #[test]
    fn unused_degenerate_and_out_of_range_give_the_placeholder() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::new(2.0, 0.0, 0.0), Vec3::Y];
        let n = angle_weighted_normals(&p, &[[0, 1, 2], [0, 1, 9]]);
        assert_eq!(n, vec![Vec3::X; 4]);
    }

    /// Under a non-uniform scale the normals are those of the scaled mesh, not the scaled normals.
    #[test]
    fn normals_are_computed_after_the_transform() {
        let mesh = TriangleMesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(0.0, 0.0, 1.0)],
            indices: vec![[0, 1, 2], [0, 3, 1]],
            ..Default::default()
        };
        let t = Transform::scale(Vec3::new(1.0, 5.0, 1.0)).unwrap();
        let object = mesh.smooth_normals(&t);
        let placed: Vec<Vec3> = mesh.positions.iter().map(|&p| t.point(p)).collect();
        let world = angle_weighted_normals(&placed, &mesh.indices);
        for (o, w) in object.iter().zip(&world) {
            assert!((t.normal(*o) - *w).length() < 1e-5, "{o:?} {w:?}");
        }
    }
}
