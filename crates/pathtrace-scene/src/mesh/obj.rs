//! Wavefront OBJ: `v`, `vt`, `vn` and `f` statements, with `usemtl` splitting the faces into
//! parts.
//!
//! - Face corners are `v`, `v/vt`, `v//vn` or `v/vt/vn`; indices count from 1, negative ones
//!   count back from the last vertex defined so far, and must refer to an already defined vertex.
//! - Polygons are fan triangulated from their first corner.
//! - Each `usemtl` material gives one part named after it; faces before any `usemtl` go to the
//!   part "default". Faces of the same material anywhere in the file share one part.
//! - A part keeps normals only if every corner of every face in it has one (and every normal
//!   has a direction), and texture coordinates only if every corner has one: otherwise they are
//!   dropped for that part, which is then flat shaded or untextured.
//! - `o`, `g`, `s`, `mtllib`, `l`, `p` and unknown statements are ignored; `#` starts a comment;
//!   a line ending in `\` continues on the next.
//! - Malformed, NaN or infinite numbers, index 0 and out-of-range indices are errors naming the
//!   line.

mod part;

use super::error::{quote, Failure};
use part::{Corner, Part, NONE};
use pathtrace::math::{Vec2, Vec3};
use pathtrace::shape::TriangleMesh;
use std::collections::HashMap;

/// The lines of `bytes`, ended by `\n`, `\r\n` or a lone `\r` (classic Mac OS exporters), so line
/// numbers in errors count as an editor does.
fn text_lines(bytes: &[u8]) -> impl Iterator<Item = &[u8]> {
    let mut rest = Some(bytes);
    std::iter::from_fn(move || {
        let text = rest?;
        match text.iter().position(|&b| b == b'\n' || b == b'\r') {
            Some(end) => {
                let skip = if text[end] == b'\r' && text.get(end + 1) == Some(&b'\n') { 2 } else { 1 };
                rest = Some(&text[end + skip..]);
                Some(&text[..end])
            }
            None => {
                rest = None;
                Some(text)
            }
        }
    })
}

/// Parses OBJ text into named parts.
pub(crate) fn parse(bytes: &[u8]) -> Result<Vec<(String, TriangleMesh)>, Failure> {
    let mut state = State::default();
    let mut pending: Vec<u8> = Vec::new();
    let mut pending_line = 0;
    let mut last_line = 0;
    // A UTF-8 byte-order mark (some Windows exporters write one) is not part of the first line.
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    for (i, line) in text_lines(bytes).enumerate() {
        let line_no = i + 1;
        last_line = line_no;
        if let Some(head) = line.strip_suffix(b"\\") {
            if pending.is_empty() {
                pending_line = line_no;
            }
            pending.extend_from_slice(head);
            pending.push(b' ');
            continue;
        }
        if pending.is_empty() {
            state.statement(line, line_no)?;
        } else {
            pending.extend_from_slice(line);
            let joined = std::mem::take(&mut pending);
            state.statement(&joined, pending_line)?;
        }
    }
    if !pending.is_empty() {
        state.statement(&pending, pending_line)?;
    }
    state.finish(last_line.max(1))
}

/// Everything read so far.
#[derive(Default)]
struct State {
    positions: Vec<Vec3>,
    uvs: Vec<Vec2>,
    normals: Vec<Vec3>,
    parts: Vec<Part>,
    by_name: HashMap<String, usize>,
    current: Option<usize>,
    corners: Vec<Corner>,
}

impl State {
    /// Handles one logical line.
    fn statement(&mut self, line: &[u8], line_no: usize) -> Result<(), Failure> {
        let line = match line.iter().position(|&b| b == b'#') {
            Some(p) => &line[..p],
            None => line,
        };
        let mut tokens = line.split(|b| b.is_ascii_whitespace()).filter(|t| !t.is_empty());
        let Some(keyword) = tokens.next() else { return Ok(()) };
        match keyword {
            b"v" => {
                let [x, y, z] = floats::<3>(&mut tokens, 3, line_no, "a vertex position")?;
                push_limited(&mut self.positions, Vec3::new(x, y, z), line_no)
            }
            b"vn" => {
                let [x, y, z] = floats::<3>(&mut tokens, 3, line_no, "a vertex normal")?;
                push_limited(&mut self.normals, Vec3::new(x, y, z), line_no)
            }
            b"vt" => {
                let [u, v] = floats::<2>(&mut tokens, 1, line_no, "a texture coordinate")?;
                push_limited(&mut self.uvs, Vec2::new(u, v), line_no)
            }
            b"f" => self.face(tokens, line_no),
            b"usemtl" => {
                let name: Vec<String> = tokens.map(|t| String::from_utf8_lossy(t).into_owned()).collect();
                let name = if name.is_empty() { "default".to_string() } else { name.join(" ") };
                self.current = Some(self.part_index(name));
                Ok(())
            }
            _ => Ok(()),
        }
    }

    /// The index of the part for a material, creating it on first use.
    fn part_index(&mut self, name: String) -> usize {
        if let Some(&i) = self.by_name.get(&name) {
            return i;
        }
        self.parts.push(Part::new(name.clone()));
        self.by_name.insert(name, self.parts.len() - 1);
        self.parts.len() - 1
    }

    /// An `f` statement: resolves the corners, then fan-triangulates into the current part.
    fn face<'a>(&mut self, tokens: impl Iterator<Item = &'a [u8]>, line_no: usize) -> Result<(), Failure> {
        self.corners.clear();
        for token in tokens {
            let corner = self.corner(token, line_no)?;
            self.corners.push(corner);
        }
        if self.corners.len() < 3 {
            let n = self.corners.len();
            return Err(Failure::line(line_no, format!("a face needs at least 3 vertices, this one has {n}")));
        }
        let index = match self.current {
            Some(i) => i,
            None => {
                let i = self.part_index("default".to_string());
                self.current = Some(i);
                i
            }
        };
        self.parts[index].add_polygon(&self.corners);
        Ok(())
    }

    /// One face corner: `v`, `v/vt`, `v//vn` or `v/vt/vn`.
    fn corner(&self, token: &[u8], line_no: usize) -> Result<Corner, Failure> {
        let mut fields = token.split(|&b| b == b'/');
        let v = fields.next().unwrap_or_default();
        let vt = fields.next();
        let vn = fields.next();
        let malformed = || Failure::line(line_no, format!("malformed face corner {}", quote(token)));
        if fields.next().is_some() || v.is_empty() || vt.is_some_and(<[u8]>::is_empty) && vn.is_none() {
            return Err(malformed());
        }
        let v = resolve(v, self.positions.len(), "vertex", line_no)?;
        let vt = match vt {
            Some(t) if !t.is_empty() => resolve(t, self.uvs.len(), "texture coordinate", line_no)?,
            _ => NONE,
        };
        let vn = match vn {
            Some([]) => return Err(malformed()),
            Some(t) => resolve(t, self.normals.len(), "normal", line_no)?,
            None => NONE,
        };
        Ok(Corner { v, vt, vn })
    }

    /// Builds one mesh per non-empty part.
    fn finish(self, last_line: usize) -> Result<Vec<(String, TriangleMesh)>, Failure> {
        let mut out = Vec::new();
        for part in self.parts {
            if let Some(named) = part.build(&self.positions, &self.uvs, &self.normals) {
                out.push(named.map_err(|m| Failure::line(last_line, m))?);
            }
        }
        if out.is_empty() {
            return Err(Failure::line(last_line, "the file holds no faces"));
        }
        Ok(out)
    }
}

/// Appends a vertex attribute, refusing more than u32 indices can address.
fn push_limited<T>(list: &mut Vec<T>, value: T, line_no: usize) -> Result<(), Failure> {
    if list.len() >= NONE as usize {
        return Err(Failure::line(line_no, "too many vertices for 32-bit indices"));
    }
    list.push(value);
    Ok(())
}

/// Reads between `required` and `N` numbers (missing optional ones are 0); extra numbers
/// (a `w`, vertex colours) are ignored.
fn floats<'a, const N: usize>(
    tokens: &mut impl Iterator<Item = &'a [u8]>,
    required: usize,
    line_no: usize,
    what: &str,
) -> Result<[f32; N], Failure> {
    let mut out = [0.0; N];
    for (i, slot) in out.iter_mut().enumerate() {
        match tokens.next() {
            Some(t) => *slot = number(t, line_no)?,
            None if i < required => {
                return Err(Failure::line(line_no, format!("{what} needs {required} numbers, found {i}")));
            }
            None => break,
        }
    }
    Ok(out)
}

/// A finite decimal number.
pub(crate) fn number(token: &[u8], line_no: usize) -> Result<f32, Failure> {
    let value: f32 = std::str::from_utf8(token)
        .ok()
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| Failure::line(line_no, format!("malformed number {}", quote(token))))?;
    if !value.is_finite() {
        return Err(Failure::line(line_no, format!("the number {} is not finite", quote(token))));
    }
    Ok(value)
}

/// Turns a 1-based or negative (relative) OBJ index into a 0-based one, checked against the
/// `count` items defined so far.
fn resolve(token: &[u8], count: usize, what: &str, line_no: usize) -> Result<u32, Failure> {
    let index: i64 = std::str::from_utf8(token)
        .ok()
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| Failure::line(line_no, format!("malformed {what} index {}", quote(token))))?;
    let resolved = match index {
        0 => return Err(Failure::line(line_no, format!("{what} index 0 is invalid: OBJ indices count from 1"))),
        i if i > 0 => i - 1,
        i => count as i64 + i,
    };
    if resolved < 0 || resolved >= count as i64 {
        let message = format!("{what} index {index} is out of range: {count} defined so far");
        return Err(Failure::line(line_no, message));
    }
    Ok(resolved as u32)
}
