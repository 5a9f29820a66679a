//! glTF mesh primitives as triangle meshes: one part per primitive, numbered through all meshes
//! in order (`meshes[0].primitives[0]` is part 0). Positions, normals, the first texture
//! coordinates and tangents (`TANGENT`: xyz and the bitangent's sign w, glTF 2.0 §3.7.2.1)
//! are read in the mesh's own space; the node transforms are the scene's business.
//! Every accessor is checked against its buffer view and buffer before it is read, so a
//! truncated buffer or an out-of-range accessor is an error naming the accessor, never a panic.

use super::document::Opened;
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;
use pathtrace::math::{Vec2, Vec3, Vec4};
use pathtrace::shape::TriangleMesh;

/// The part number of every primitive: `first[m] + p` for `meshes[m].primitives[p]`.
pub fn first_parts(doc: &gltf::Document) -> Vec<usize> {
    let mut next = 0;
    doc.meshes()
        .map(|m| {
            let first = next;
            next += m.primitives().len();
            first
        })
        .collect()
}

/// Every primitive as a named part (`mesh name` or `mesh M`, then `.P`). A primitive that is not
/// made of triangles gives an empty mesh (the scene importer warns about it).
pub fn parts(o: &Opened) -> Result<Vec<(String, TriangleMesh)>, String> {
    let mut out = Vec::new();
    for mesh in o.doc.meshes() {
        let name = mesh.name().map_or_else(|| format!("mesh {}", mesh.index()), str::to_string);
        for prim in mesh.primitives() {
            let at = format!("meshes[{}].primitives[{}]", mesh.index(), prim.index());
            let part = if prim.mode() == Mode::Triangles {
                primitive(o, &prim).map_err(|e| format!("{at}: {e}"))?
            } else {
                TriangleMesh::default()
            };
            out.push((format!("{name}.{}", prim.index()), part));
        }
    }
    Ok(out)
}

/// Checks that `accessor` lies inside its view and buffer, with the expected types.
fn check(o: &Opened, a: &gltf::Accessor, what: &str, types: &[DataType], dims: Dimensions) -> Result<(), String> {
    let at = format!("{what} (accessors[{}])", a.index());
    if a.sparse().is_some() {
        return Err(format!("{at}: sparse accessors are not supported"));
    }
    if !types.contains(&a.data_type()) || a.dimensions() != dims {
        return Err(format!("{at}: expected {dims:?} of {types:?}, found {:?} of {:?}", a.dimensions(), a.data_type()));
    }
    let view = a.view().ok_or_else(|| format!("{at}: has no buffer view"))?;
    let buffer = &o.buffers[view.buffer().index()];
    let view_end = view.offset().checked_add(view.length());
    if view_end.is_none_or(|end| end > buffer.len()) {
        return Err(format!(
            "{at}: buffer view {} (bytes {}..+{}) runs past the end of buffer {} ({} bytes)",
            view.index(),
            view.offset(),
            view.length(),
            view.buffer().index(),
            buffer.len()
        ));
    }
    let size = a.size();
    let stride = view.stride().unwrap_or(size);
    if a.count() == 0 {
        return Err(format!("{at}: count is 0"));
    }
    let end =
        (a.count() - 1).checked_mul(stride).and_then(|x| x.checked_add(size)).and_then(|x| x.checked_add(a.offset()));
    if end.is_none_or(|end| end > view.length()) {
        return Err(format!(
            "{at}: {} elements of {size} bytes (stride {stride}) from offset {} do not fit in buffer view {} ({} bytes)",
            a.count(),
            a.offset(),
            view.index(),
            view.length()
        ));
    }
    Ok(())
}

fn primitive(o: &Opened, prim: &gltf::Primitive) -> Result<TriangleMesh, String> {
    let positions_acc = prim.get(&gltf::Semantic::Positions).ok_or("has no POSITION attribute")?;
    check(o, &positions_acc, "POSITION", &[DataType::F32], Dimensions::Vec3)?;
    let normals_acc = prim.get(&gltf::Semantic::Normals);
    if let Some(a) = &normals_acc {
        check(o, a, "NORMAL", &[DataType::F32], Dimensions::Vec3)?;
    }
    let uv_acc = prim.get(&gltf::Semantic::TexCoords(0));
    if let Some(a) = &uv_acc {
        check(o, a, "TEXCOORD_0", &[DataType::F32, DataType::U8, DataType::U16], Dimensions::Vec2)?;
    }
    let tangent_acc = prim.get(&gltf::Semantic::Tangents);
    if let Some(a) = &tangent_acc {
        check(o, a, "TANGENT", &[DataType::F32], Dimensions::Vec4)?;
    }
    if let Some(a) = prim.indices() {
        check(o, &a, "indices", &[DataType::U8, DataType::U16, DataType::U32], Dimensions::Scalar)?;
    }
    let reader = prim.reader(|b| o.buffers.get(b.index()).map(Vec::as_slice));
    let unreadable = |what: &str| format!("{what} cannot be read");
    let positions: Vec<Vec3> = reader.read_positions().ok_or_else(|| unreadable("POSITION"))?.map(Vec3::from).collect();
    let n = positions.len();
    let normals = match &normals_acc {
        Some(_) => {
            let ns: Vec<Vec3> = reader.read_normals().ok_or_else(|| unreadable("NORMAL"))?.map(Vec3::from).collect();
            same_count(ns, n, "NORMAL")?
        }
        None => None,
    };
    let uvs = match uv_acc {
        Some(_) => {
            let uv = reader.read_tex_coords(0).ok_or_else(|| unreadable("TEXCOORD_0"))?.into_f32();
            // glTF's v runs down the image from its top row, as ours (Mitsuba's) does.
            same_count(uv.map(|[u, v]| Vec2::new(u, v)).collect(), n, "TEXCOORD_0")?
        }
        None => None,
    };
    // glTF 2.0 §3.7.2.1: without NORMAL (flat normals), TANGENT must be ignored.
    let tangents = match tangent_acc {
        Some(_) if normals_acc.is_some() => {
            let ts: Vec<Vec4> = reader.read_tangents().ok_or_else(|| unreadable("TANGENT"))?.map(Vec4::from).collect();
            if let Some(i) = ts.iter().position(|t| !t.is_finite() || t.w.abs() != 1.0) {
                return Err(format!(
                    "TANGENT element {i} is {:?}: its w (the bitangent's sign) must be 1 or -1 and every \
                     component finite",
                    ts[i].to_array()
                ));
            }
            same_count(ts, n, "TANGENT")?
        }
        _ => None,
    };
    let flat: Vec<u32> = match reader.read_indices() {
        Some(i) => i.into_u32().collect(),
        None => (0..n as u32).collect(),
    };
    if !flat.len().is_multiple_of(3) {
        return Err(format!("{} indices do not make whole triangles", flat.len()));
    }
    if let Some(bad) = flat.iter().find(|&&i| i as usize >= n) {
        return Err(format!("index {bad} is out of range ({n} vertices)"));
    }
    let indices = flat.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
    // Zero normals cannot be normalised: drop them (the mesh is then flat shaded).
    let normals = normals.and_then(crate::mesh::normalised_normals);
    let mesh = TriangleMesh { positions, indices, normals, uvs, tangents };
    mesh.validate().map_err(|e| e.to_string())?;
    Ok(mesh)
}

fn same_count<T>(v: Vec<T>, n: usize, what: &str) -> Result<Option<Vec<T>>, String> {
    if v.len() != n {
        return Err(format!("{what} has {} elements but POSITION has {n}", v.len()));
    }
    Ok(Some(v))
}
