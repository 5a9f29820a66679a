//! One OBJ part (a material's faces): corners as read, then re-indexed into a compact mesh.

use crate::mesh::normals::normalised;
use pathtrace::math::{Vec2, Vec3};
use pathtrace::shape::TriangleMesh;
use std::collections::HashMap;

/// "No texture coordinate / normal" in a [`Corner`].
pub(crate) const NONE: u32 = u32::MAX;

/// A face corner: 0-based indices into the file's positions, texture coordinates and normals.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Corner {
    pub v: u32,
    pub vt: u32,
    pub vn: u32,
}

/// The triangles of one material, as file-wide corner indices.
pub(crate) struct Part {
    name: String,
    triangles: Vec<[Corner; 3]>,
    all_uvs: bool,
    all_normals: bool,
}

impl Part {
    /// An empty part.
    pub fn new(name: String) -> Part {
        Part { name, triangles: Vec::new(), all_uvs: true, all_normals: true }
    }

    /// Fan-triangulates a polygon of at least three corners.
    pub fn add_polygon(&mut self, corners: &[Corner]) {
        self.all_uvs &= corners.iter().all(|c| c.vt != NONE);
        self.all_normals &= corners.iter().all(|c| c.vn != NONE);
        let first = corners[0];
        for pair in corners[1..].windows(2) {
            self.triangles.push([first, pair[0], pair[1]]);
        }
    }

    /// The compact mesh: only the vertices this part uses, one per distinct (v, vt, vn) triple
    /// (ignoring vt / vn when the part drops them). `None` for a part without faces.
    pub fn build(
        self,
        positions: &[Vec3],
        uvs: &[Vec2],
        normals: &[Vec3],
    ) -> Option<Result<(String, TriangleMesh), String>> {
        if self.triangles.is_empty() {
            return None;
        }
        let mut map: HashMap<(u32, u32, u32), u32> = HashMap::new();
        let mut mesh = TriangleMesh::default();
        let mut out_uvs = Vec::new();
        let mut out_normals = Vec::new();
        let mut indices = Vec::with_capacity(self.triangles.len());
        for tri in &self.triangles {
            let mut out = [0u32; 3];
            for (slot, c) in out.iter_mut().zip(tri) {
                let vt = if self.all_uvs { c.vt } else { NONE };
                let vn = if self.all_normals { c.vn } else { NONE };
                let next = mesh.positions.len();
                let index = *map.entry((c.v, vt, vn)).or_insert(next as u32);
                if index as usize == next {
                    if next >= NONE as usize {
                        return Some(Err("too many vertices for 32-bit indices".to_string()));
                    }
                    mesh.positions.push(positions.get(c.v as usize).copied().unwrap_or_default());
                    if self.all_uvs {
                        out_uvs.push(uvs.get(vt as usize).copied().unwrap_or_default());
                    }
                    if self.all_normals {
                        out_normals.push(normals.get(vn as usize).copied().unwrap_or_default());
                    }
                }
                *slot = index;
            }
            indices.push(out);
        }
        mesh.indices = indices;
        mesh.uvs = self.all_uvs.then_some(out_uvs);
        mesh.normals = if self.all_normals { normalised(out_normals) } else { None };
        Some(Ok((self.name, mesh)))
    }
}
