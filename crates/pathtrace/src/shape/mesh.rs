//! Indexed triangle meshes: shared vertex positions (and optional normals and texture
//! coordinates) with index triples.
//! The scene builder keeps a mesh as a [`super::MeshGeometry`] (shared vertex buffer + indices).

use crate::math::{Vec2, Vec3, Vec4};

/// What can be wrong with a mesh.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeshError {
    #[error("triangle {triangle} refers to vertex {index}, but the mesh has {count} vertices")]
    IndexOutOfRange { triangle: usize, index: u32, count: usize },
    #[error("the mesh has {positions} positions but {normals} normals")]
    NormalCountMismatch { positions: usize, normals: usize },
    #[error("the mesh has {positions} positions but {uvs} texture coordinates")]
    UvCountMismatch { positions: usize, uvs: usize },
    #[error("vertex {0} has a non-finite coordinate")]
    NonFinite(usize),
    #[error("vertex {0} has a non-finite normal or texture coordinate")]
    NonFiniteAttribute(usize),
    #[error("the mesh has {positions} positions but {tangents} tangents")]
    TangentCountMismatch { positions: usize, tangents: usize },
    #[error("vertex {0}'s tangent is not finite, or its w (the bitangent's sign) is not 1 or -1")]
    InvalidTangent(usize),
}

/// An indexed triangle mesh.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleMesh {
    pub positions: Vec<Vec3>,
    pub indices: Vec<[u32; 3]>,
    /// Per-vertex shading normals, if the mesh has them.
    pub normals: Option<Vec<Vec3>>,
    /// Per-vertex texture coordinates, if the mesh has them.
    pub uvs: Option<Vec<Vec2>>,
    /// Per-vertex tangents, if the mesh has its own (glTF's `TANGENT`): xyz the tangent, w = ±1
    /// the bitangent's sign (bitangent = w · normal × tangent). Without them a normal map's
    /// tangent frame comes from the texture coordinates.
    pub tangents: Option<Vec<Vec4>>,
}

impl TriangleMesh {
    /// Turns the surface over (Mitsuba's `flip_normals`): every triangle's winding is reversed,
    /// so its face normal e1 × e2 points the other way, and stored vertex normals are negated.
    /// Positions and texture coordinates are untouched, so the surface and its texturing stay
    /// the same; a tangent's bitangent sign is negated too, keeping the bitangent w·(n × t) —
    /// the texture's v direction — where it was.
    pub fn flip_normals(&mut self) {
        for [_, b, c] in &mut self.indices {
            std::mem::swap(b, c);
        }
        for n in self.normals.iter_mut().flatten() {
            *n = -*n;
        }
        for t in self.tangents.iter_mut().flatten() {
            t.w = -t.w;
        }
    }

    /// Checks indices, normal and texture-coordinate counts and finiteness.
    pub fn validate(&self) -> Result<(), MeshError> {
        if let Some(i) = self.positions.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::NonFinite(i));
        }
        if let Some(n) = &self.normals {
            if n.len() != self.positions.len() {
                return Err(MeshError::NormalCountMismatch { positions: self.positions.len(), normals: n.len() });
            }
            if let Some(i) = n.iter().position(|v| !v.is_finite()) {
                return Err(MeshError::NonFiniteAttribute(i));
            }
        }
        if let Some(uv) = &self.uvs {
            if uv.len() != self.positions.len() {
                return Err(MeshError::UvCountMismatch { positions: self.positions.len(), uvs: uv.len() });
            }
            if let Some(i) = uv.iter().position(|v| !v.is_finite()) {
                return Err(MeshError::NonFiniteAttribute(i));
            }
        }
        if let Some(t) = &self.tangents {
            if t.len() != self.positions.len() {
                return Err(MeshError::TangentCountMismatch { positions: self.positions.len(), tangents: t.len() });
            }
            if let Some(i) = t.iter().position(|v| !v.is_finite() || v.w.abs() != 1.0) {
                return Err(MeshError::InvalidTangent(i));
            }
        }
        let count = self.positions.len();
        for (triangle, tri) in self.indices.iter().enumerate() {
            if let Some(&index) = tri.iter().find(|&&i| i as usize >= count) {
                return Err(MeshError::IndexOutOfRange { triangle, index, count });
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn out_of_range_indices_are_reported() {
        let m = TriangleMesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            indices: vec![[0, 1, 2], [0, 2, 3]],
            normals: None,
            uvs: None,
            tangents: None,
        };
        assert_eq!(m.validate(), Err(MeshError::IndexOutOfRange { triangle: 1, index: 3, count: 3 }));
    }

    #[test]
    fn uv_count_and_finiteness_are_checked() {
        let mut m = TriangleMesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            indices: vec![[0, 1, 2]],
            normals: None,
            uvs: Some(vec![Vec2::ZERO; 2]),
            tangents: None,
        };
        assert_eq!(m.validate(), Err(MeshError::UvCountMismatch { positions: 3, uvs: 2 }));
        m.uvs = Some(vec![Vec2::ZERO, Vec2::X, Vec2::new(f32::NAN, 0.0)]);
        assert_eq!(m.validate(), Err(MeshError::NonFiniteAttribute(2)));
        m.uvs = Some(vec![Vec2::ZERO, Vec2::X, Vec2::Y]);
        assert_eq!(m.validate(), Ok(()));
    }

    #[test]
    fn tangent_count_finiteness_and_sign_are_checked() {
        let mut m = TriangleMesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            indices: vec![[0, 1, 2]],
            tangents: Some(vec![Vec4::new(1.0, 0.0, 0.0, 1.0); 2]),
            ..Default::default()
        };
        assert_eq!(m.validate(), Err(MeshError::TangentCountMismatch { positions: 3, tangents: 2 }));
        m.tangents = Some(vec![Vec4::X + Vec4::W, Vec4::X - Vec4::W, Vec4::new(1.0, 0.0, 0.0, 0.5)]);
        assert_eq!(m.validate(), Err(MeshError::InvalidTangent(2)));
        m.tangents = Some(vec![Vec4::X + Vec4::W, Vec4::new(f32::NAN, 0.0, 0.0, 1.0), Vec4::X - Vec4::W]);
        assert_eq!(m.validate(), Err(MeshError::InvalidTangent(1)));
        m.tangents = Some(vec![Vec4::X + Vec4::W, Vec4::X - Vec4::W, Vec4::Y + Vec4::W]);
        assert_eq!(m.validate(), Ok(()));
    }
}
