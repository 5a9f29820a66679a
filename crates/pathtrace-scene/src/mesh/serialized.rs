//! Mitsuba's `.serialized` meshes: a list of zlib-compressed shapes and, at the end of the file,
//! a table of their byte offsets and their count. Each shape: `u16` magic 0x041C, `u16` version
//! (3 or 4), then compressed: `u32` flags, (version 4: a NUL-terminated name), `u64` vertex and
//! triangle counts, positions, optional normals (flag 0x1), uvs (0x2) and colours (0x8), and
//! `u32` indices (`u64` beyond 2³² vertices). Values are `f32`, or `f64` with flag 0x2000.
//! All little-endian. One part per shape, named `shape{index}`.

use super::error::Failure;
use super::normals::normalised;
use flate2::read::ZlibDecoder;
use pathtrace::math::{Vec2, Vec3};
use pathtrace::shape::TriangleMesh;
use std::io::Read;

const MAGIC: u16 = 0x041C;
/// Largest decompressed shape accepted (guards against decompression bombs).
const MAX_SHAPE_BYTES: u64 = 1 << 30;

fn u16_at(b: &[u8], at: usize) -> Option<u16> {
    b.get(at..at + 2).map(|s| u16::from_le_bytes([s[0], s[1]]))
}

fn u32_at(b: &[u8], at: usize) -> Option<u32> {
    b.get(at..at + 4).map(|s| u32::from_le_bytes([s[0], s[1], s[2], s[3]]))
}

fn u64_at(b: &[u8], at: usize) -> Option<u64> {
    b.get(at..at + 8).and_then(|s| s.try_into().ok()).map(u64::from_le_bytes)
}

/// Parses every shape of the file.
pub(crate) fn parse(bytes: &[u8]) -> Result<Vec<(String, TriangleMesh)>, Failure> {
    if bytes.len() < 8 || u16_at(bytes, 0) != Some(MAGIC) {
        return Err(Failure::offset(0, "not a Mitsuba serialized mesh (bad magic number)"));
    }
    let version = u16_at(bytes, 2).unwrap_or(0);
    let end = bytes.len() - 4;
    let count = u32_at(bytes, end).unwrap_or(0) as usize;
    let entry = if version >= 4 { 8 } else { 4 };
    let table = count.checked_mul(entry).and_then(|t| end.checked_sub(t)).filter(|_| count > 0);
    let Some(table) = table else {
        return Err(Failure::offset(end, format!("bad shape count {count} in the end-of-file table")));
    };
    let mut parts = Vec::with_capacity(count);
    for i in 0..count {
        let at = table + i * entry;
        let offset = if entry == 8 { u64_at(bytes, at) } else { u32_at(bytes, at).map(u64::from) };
        let offset = offset.and_then(|o| usize::try_from(o).ok()).filter(|&o| o + 4 <= table);
        let Some(offset) = offset else {
            return Err(Failure::offset(at, format!("shape {i}: offset outside the file")));
        };
        parts.push((
            format!("shape{i}"),
            shape(bytes, offset, table).map_err(|m| Failure::offset(offset, format!("shape {i}: {m}")))?,
        ));
    }
    Ok(parts)
}

fn shape(bytes: &[u8], offset: usize, end: usize) -> Result<TriangleMesh, String> {
    if u16_at(bytes, offset) != Some(MAGIC) {
        return Err("bad magic number".into());
    }
    let version = u16_at(bytes, offset + 2).unwrap_or(0);
    if !(3..=4).contains(&version) {
        return Err(format!("unsupported version {version} (3 or 4 expected)"));
    }
    let mut data = Vec::new();
    ZlibDecoder::new(&bytes[offset + 4..end])
        .take(MAX_SHAPE_BYTES)
        .read_to_end(&mut data)
        .map_err(|e| format!("cannot decompress: {e}"))?;
    let mut r = Reader { b: &data, at: 0 };
    let flags = r.u32()?;
    if version == 4 {
        let n = data.get(r.at..).and_then(|s| s.iter().position(|&c| c == 0)).ok_or("unterminated shape name")?;
        r.at += n + 1;
    }
    let nv = usize::try_from(r.u64()?).map_err(|_| "vertex count too large")?;
    let nt = usize::try_from(r.u64()?).map_err(|_| "triangle count too large")?;
    let double = flags & 0x2000 != 0;
    let size = if double { 8 } else { 4 };
    // Check that the data holds what the counts promise before allocating for it.
    let per_vertex =
        3 + 3 * usize::from(flags & 1 != 0) + 2 * usize::from(flags & 2 != 0) + 3 * usize::from(flags & 8 != 0);
    let index_size = if nv > u32::MAX as usize { 8 } else { 4 };
    let need = nv
        .checked_mul(per_vertex * size)
        .and_then(|v| nt.checked_mul(3 * index_size).and_then(|t| v.checked_add(t)))
        .ok_or("counts overflow")?;
    if need > data.len().saturating_sub(r.at) {
        return Err(format!("{nv} vertices and {nt} triangles need {need} bytes; the shape has fewer"));
    }
    let vec3s = |r: &mut Reader| -> Result<Vec<Vec3>, String> {
        (0..nv).map(|_| Ok(Vec3::new(r.real(double)?, r.real(double)?, r.real(double)?))).collect()
    };
    let positions = vec3s(&mut r)?;
    let normals = if flags & 1 != 0 { normalised(vec3s(&mut r)?) } else { None };
    let uvs = if flags & 2 != 0 {
        Some((0..nv).map(|_| Ok(Vec2::new(r.real(double)?, r.real(double)?))).collect::<Result<Vec<_>, String>>()?)
    } else {
        None
    };
    if flags & 8 != 0 {
        r.at += nv * 3 * size; // vertex colours are not used
    }
    let mut indices = Vec::with_capacity(nt);
    for t in 0..nt {
        let mut tri = [0u32; 3];
        for slot in &mut tri {
            let i = if index_size == 8 { r.u64()? } else { u64::from(r.u32()?) };
            *slot = u32::try_from(i)
                .ok()
                .filter(|&i| (i as usize) < nv)
                .ok_or_else(|| format!("triangle {t}: vertex index {i} out of range ({nv} vertices)"))?;
        }
        indices.push(tri);
    }
    let mesh = TriangleMesh { positions, indices, normals, uvs, tangents: None };
    mesh.validate().map_err(|e| e.to_string())?;
    Ok(mesh)
}

struct Reader<'a> {
    b: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take<const N: usize>(&mut self) -> Result<[u8; N], String> {
        let s = self.b.get(self.at..self.at + N).ok_or("unexpected end of the shape data")?;
        self.at += N;
        s.try_into().map_err(|_| "unexpected end of the shape data".to_string())
    }
    fn u32(&mut self) -> Result<u32, String> {
        self.take::<4>().map(u32::from_le_bytes)
    }
    fn u64(&mut self) -> Result<u64, String> {
        self.take::<8>().map(u64::from_le_bytes)
    }
    fn real(&mut self, double: bool) -> Result<f32, String> {
        if double {
            self.take::<8>().map(|b| f64::from_le_bytes(b) as f32)
        } else {
            self.take::<4>().map(f32::from_le_bytes)
        }
    }
}
