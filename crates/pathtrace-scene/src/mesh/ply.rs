//! Stanford PLY: ASCII, binary little endian and binary big endian.
//!
//! - The `vertex` element must have scalar `x`, `y`, `z`; `nx`, `ny`, `nz` give shading normals
//!   and `u v`, `s t`, `texture_u texture_v` or `texture_s texture_t` texture coordinates (each set
//!   used only when complete). Other vertex properties, scalar or list, of any type are skipped.
//! - The `face` element must have a list `vertex_indices` (or `vertex_index`) with integer
//!   count and item types; polygons are fan triangulated from their first corner, and other face
//!   properties are skipped. Elements other than `vertex` and `face` are skipped.
//! - Normals are normalised; if any normal is zero the whole mesh drops its normals (flat
//!   shading). NaN or infinite positions, normals or texture coordinates are errors.
//! - Errors name the header line, the ASCII body line, or the byte offset of binary data.
//!   Element counts are checked against the bytes left before anything is allocated, so a
//!   header claiming 2^40 vertices is an error, not an allocation.

mod header;
mod source;

use super::error::Failure;
use super::normals::normalised;
use header::{Element, Format, Header, Kind, Scalar};
use pathtrace::math::{Vec2, Vec3};
use pathtrace::shape::TriangleMesh;
use source::{Ascii, Binary, MinSize, Source};

/// Parses a PLY file into one mesh.
pub(crate) fn parse(bytes: &[u8]) -> Result<TriangleMesh, Failure> {
    let header = header::parse(bytes)?;
    let layout = Layout::new(&header)?;
    let start = header.body_start;
    match header.format {
        Format::Ascii => decode(&mut Ascii::new(bytes, start, header.end_line + 1), &header, &layout),
        Format::BinaryLittleEndian => decode(&mut Binary::new(bytes, start, false), &header, &layout),
        Format::BinaryBigEndian => decode(&mut Binary::new(bytes, start, true), &header, &layout),
    }
}

/// What a property is used for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Role {
    Skip,
    /// Vertex attribute slot: x y z nx ny nz u v.
    Attr(usize),
    /// The face's vertex index list.
    Indices,
}

/// Which elements and properties carry the mesh.
struct Layout {
    vertex: usize,
    face: usize,
    vertex_roles: Vec<Role>,
    face_roles: Vec<Role>,
    has_normals: bool,
    has_uvs: bool,
}

impl Layout {
    fn new(header: &Header) -> Result<Layout, Failure> {
        let find = |name: &str| header.elements.iter().position(|e| e.name == name);
        let missing = |what: &str| Failure::line(header.end_line, format!("the file has no {what} element"));
        let vertex = find("vertex").ok_or_else(|| missing("vertex"))?;
        let face = find("face").ok_or_else(|| missing("face"))?;
        let velement = &header.elements[vertex];
        if velement.count > u64::from(u32::MAX) {
            return Err(Failure::line(velement.line, "too many vertices for 32-bit indices"));
        }
        let has = |name: &str| velement.properties.iter().any(|p| p.name == name);
        let has_normals = ["nx", "ny", "nz"].iter().all(|n| has(n));
        let uv_names = [["u", "v"], ["s", "t"], ["texture_u", "texture_v"], ["texture_s", "texture_t"]];
        let uv = uv_names.iter().find(|pair| pair.iter().all(|n| has(n)));
        let mut vertex_roles = Vec::new();
        for p in &velement.properties {
            let slot = match p.name.as_str() {
                "x" => Some(0),
                "y" => Some(1),
                "z" => Some(2),
                "nx" if has_normals => Some(3),
                "ny" if has_normals => Some(4),
                "nz" if has_normals => Some(5),
                n if uv.is_some_and(|pair| pair[0] == n) => Some(6),
                n if uv.is_some_and(|pair| pair[1] == n) => Some(7),
                _ => None,
            };
            if slot.is_some() && !matches!(p.kind, Kind::Scalar(_)) {
                return Err(Failure::line(p.line, format!("the vertex property {} must not be a list", p.name)));
            }
            vertex_roles.push(slot.map_or(Role::Skip, Role::Attr));
        }
        for axis in 0..3 {
            if !vertex_roles.contains(&Role::Attr(axis)) {
                return Err(Failure::line(velement.line, "the vertex element needs x, y and z properties"));
            }
        }
        let felement = &header.elements[face];
        let mut face_roles = vec![Role::Skip; felement.properties.len()];
        let list = felement.properties.iter().position(|p| p.name == "vertex_indices" || p.name == "vertex_index");
        let Some(list) = list else {
            return Err(Failure::line(felement.line, "the face element needs a vertex_indices list"));
        };
        let p = &felement.properties[list];
        if !matches!(p.kind, Kind::List { item, .. } if item.is_integer()) {
            return Err(Failure::line(p.line, format!("{} must be a list of an integer type", p.name)));
        }
        face_roles[list] = Role::Indices;
        Ok(Layout { vertex, face, vertex_roles, face_roles, has_normals, has_uvs: uv.is_some() })
    }
}

/// The smallest record of an element.
fn min_size(element: &Element) -> MinSize {
    let bytes = element.properties.iter().map(|p| p.kind.min_size()).sum();
    (bytes, element.properties.len())
}

/// Reads the body up to the end of the vertex and face elements.
fn decode<S: Source>(src: &mut S, header: &Header, layout: &Layout) -> Result<TriangleMesh, Failure> {
    let mut mesh = TriangleMesh::default();
    let mut normals = Vec::new();
    let mut uvs = Vec::new();
    let vertex_count = header.elements[layout.vertex].count;
    for (i, element) in header.elements.iter().enumerate() {
        if i == layout.vertex {
            let out = (&mut mesh.positions, &mut normals, &mut uvs);
            read_vertices(src, element, layout, out)?;
        } else if i == layout.face {
            read_faces(src, element, &layout.face_roles, vertex_count, &mut mesh.indices)?;
        } else {
            skip_element(src, element)?;
        }
        if i >= layout.vertex && i >= layout.face {
            break;
        }
    }
    if mesh.indices.is_empty() {
        return Err(Failure::line(header.end_line, "the file holds no faces"));
    }
    mesh.normals = if layout.has_normals { normalised(normals) } else { None };
    mesh.uvs = layout.has_uvs.then_some(uvs);
    Ok(mesh)
}

/// Prefixes a record's failure with which record it was.
fn in_record(mut failure: Failure, what: &str, index: u64, count: u64) -> Failure {
    failure.message = format!("{what} {index} of {count}: {}", failure.message);
    failure
}

/// Reads every vertex record.
fn read_vertices<S: Source>(
    src: &mut S,
    element: &Element,
    layout: &Layout,
    (positions, normals, uvs): (&mut Vec<Vec3>, &mut Vec<Vec3>, &mut Vec<Vec2>),
) -> Result<(), Failure> {
    src.check_fits(element.count, min_size(element), "vertices")?;
    let count = element.count as usize;
    positions.reserve_exact(count);
    if layout.has_normals {
        normals.reserve_exact(count);
    }
    if layout.has_uvs {
        uvs.reserve_exact(count);
    }
    let mut slots = [0.0f32; 8];
    for v in 0..element.count {
        read_vertex(src, element, &layout.vertex_roles, &mut slots)
            .map_err(|f| in_record(f, "vertex", v, element.count))?;
        if !slots.iter().all(|s| s.is_finite()) {
            let message = format!("vertex {v} has a NaN or infinite coordinate, normal or texture coordinate");
            return Err(src.fail(message));
        }
        positions.push(Vec3::new(slots[0], slots[1], slots[2]));
        if layout.has_normals {
            normals.push(Vec3::new(slots[3], slots[4], slots[5]));
        }
        if layout.has_uvs {
            uvs.push(Vec2::new(slots[6], slots[7]));
        }
    }
    Ok(())
}

/// One vertex record into the attribute slots.
#[inline]
fn read_vertex<S: Source>(src: &mut S, element: &Element, roles: &[Role], slots: &mut [f32; 8]) -> Result<(), Failure> {
    for (p, role) in element.properties.iter().zip(roles) {
        match (role, p.kind) {
            (Role::Attr(k), Kind::Scalar(ty)) => slots[*k] = src.float(ty)?,
            (_, kind) => skip_value(src, kind)?,
        }
    }
    Ok(())
}

/// Reads every face record, fan-triangulating into `indices`.
fn read_faces<S: Source>(
    src: &mut S,
    element: &Element,
    roles: &[Role],
    vertex_count: u64,
    indices: &mut Vec<[u32; 3]>,
) -> Result<(), Failure> {
    let size = min_size(element);
    src.check_fits(element.count, size, "faces")?;
    // Capacity for triangles: exact for triangle meshes, and bounded by the file size whatever
    // the header says.
    let tri_bytes = element.properties.iter().map(|p| match p.kind {
        Kind::List { count, item } => count.size() + 3 * item.size(),
        kind => kind.min_size(),
    });
    let tri_size = (tri_bytes.sum(), size.1 + 3);
    indices.reserve(src.fits(tri_size).min(element.count) as usize);
    for f in 0..element.count {
        for (p, role) in element.properties.iter().zip(roles) {
            match (role, p.kind) {
                (Role::Indices, Kind::List { count, item }) => read_polygon(src, count, item, vertex_count, indices),
                (_, kind) => skip_value(src, kind),
            }
            .map_err(|e| in_record(e, "face", f, element.count))?;
        }
    }
    Ok(())
}

/// One polygon: its corner count, then its indices, fan-triangulated.
#[inline]
fn read_polygon<S: Source>(
    src: &mut S,
    count: Scalar,
    item: Scalar,
    vertex_count: u64,
    indices: &mut Vec<[u32; 3]>,
) -> Result<(), Failure> {
    let n = src.int(count)?;
    if n < 3 {
        return Err(src.fail(format!("a face needs at least 3 vertices, this one has {n}")));
    }
    if n > 255 {
        src.check_fits(n as u64, (item.size(), 1), "face corners")?;
    }
    let index = |src: &mut S| -> Result<u32, Failure> {
        let i = src.int(item)?;
        if i < 0 || i as u64 >= vertex_count {
            return Err(src.fail(format!("vertex index {i} is out of range: the file has {vertex_count} vertices")));
        }
        Ok(i as u32)
    };
    let first = index(src)?;
    let mut previous = index(src)?;
    for _ in 2..n {
        let next = index(src)?;
        indices.push([first, previous, next]);
        previous = next;
    }
    Ok(())
}

/// Skips one property value of any kind.
#[inline]
fn skip_value<S: Source>(src: &mut S, kind: Kind) -> Result<(), Failure> {
    match kind {
        Kind::Scalar(ty) => src.skip(ty, 1),
        Kind::List { count, item } => {
            let n = src.int(count)?;
            if n < 0 {
                return Err(src.fail(format!("negative list length {n}")));
            }
            src.skip(item, n as u64)
        }
    }
}

/// Skips an element the mesh does not use.
fn skip_element<S: Source>(src: &mut S, element: &Element) -> Result<(), Failure> {
    if element.properties.is_empty() {
        return Ok(());
    }
    src.check_fits(element.count, min_size(element), &format!("{} records", element.name))?;
    for r in 0..element.count {
        for p in &element.properties {
            skip_value(src, p.kind).map_err(|e| in_record(e, &element.name, r, element.count))?;
        }
    }
    Ok(())
}
