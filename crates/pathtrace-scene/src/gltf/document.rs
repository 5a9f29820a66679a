//! A glTF 2.0 file (`.gltf` JSON or `.glb` binary) opened with the `gltf` crate, with its buffers
//! resolved: the `.glb` binary chunk, files next to the `.gltf`, or `data:` URIs (base64).
//! Every failure is a message naming what in the file is wrong (`buffers[1]`, …).

use std::path::Path;

/// A parsed glTF document and the bytes of each of its buffers.
pub struct Opened {
    pub doc: gltf::Document,
    pub buffers: Vec<Vec<u8>>,
}

/// Parses `bytes` (JSON or GLB) and loads every buffer. JSON syntax errors carry the line and
/// column the JSON parser reports.
pub fn open(bytes: &[u8], path: &Path) -> Result<Opened, String> {
    let gltf = gltf::Gltf::from_slice(bytes).map_err(|e| format!("not a valid glTF 2.0 file: {e}"))?;
    let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
    let mut blob = gltf.blob;
    let mut buffers = Vec::new();
    for b in gltf.document.buffers() {
        let at = format!("buffers[{}]", b.index());
        let data = match b.source() {
            gltf::buffer::Source::Bin => {
                blob.take().ok_or_else(|| format!("{at}: refers to the GLB binary chunk, which is missing"))?
            }
            gltf::buffer::Source::Uri(uri) => read_uri(uri, &dir).map_err(|e| format!("{at}: {e}"))?,
        };
        if data.len() < b.length() {
            return Err(format!("{at}: declares {} bytes but holds only {} (truncated?)", b.length(), data.len()));
        }
        buffers.push(data);
    }
    Ok(Opened { doc: gltf.document, buffers })
}

/// The bytes a URI names: a `data:` URI in base64, or a file relative to `dir`.
pub fn read_uri(uri: &str, dir: &Path) -> Result<Vec<u8>, String> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_, data) = rest.split_once(";base64,").ok_or("only base64 data: URIs are supported")?;
        return base64(data).ok_or_else(|| "the data: URI is not valid base64".to_string());
    }
    let file = dir.join(percent_decode(uri));
    std::fs::read(&file).map_err(|e| format!("cannot read `{}`: {e}", file.display()))
}

/// `%20`-style escapes in a relative URI (RFC 3986), as glTF requires for file names.
pub fn percent_decode(s: &str) -> String {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = |c: u8| (c as char).to_digit(16);
        if b[i] == b'%' && i + 2 < b.len() {
            if let (Some(h), Some(l)) = (hex(b[i + 1]), hex(b[i + 2])) {
                out.push((h * 16 + l) as u8);
                i += 3;
                continue;
            }
        }
        out.push(b[i]);
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Standard base64 (RFC 4648, padding optional); `None` on any other character.
fn base64(s: &str) -> Option<Vec<u8>> {
    let value = |c: u8| -> Option<u32> {
        Some(match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' => 62,
            b'/' => 63,
            _ => return None,
        } as u32)
    };
    let digits: Vec<u8> = s.bytes().filter(|c| !c.is_ascii_whitespace()).collect();
    let digits = digits.strip_suffix(b"==").or_else(|| digits.strip_suffix(b"=")).unwrap_or(&digits);
    let mut out = Vec::with_capacity(digits.len() * 3 / 4);
    for chunk in digits.chunks(4) {
        let mut acc = 0u32;
        for (k, &c) in chunk.iter().enumerate() {
            acc |= value(c)? << (18 - 6 * k);
        }
        let bytes = acc.to_be_bytes();
        match chunk.len() {
            4 => out.extend_from_slice(&bytes[1..4]),
            3 => out.extend_from_slice(&bytes[1..3]),
            2 => out.push(bytes[1]),
            _ => return None,
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_and_percent_decoding() {
        assert_eq!(base64("aGVsbG8=").unwrap(), b"hello");
        assert_eq!(base64("aGVsbG8h").unwrap(), b"hello!");
        assert_eq!(base64("aGk").unwrap(), b"hi");
        assert!(base64("a$==").is_none());
        assert!(base64("a").is_none());
        assert_eq!(percent_decode("my%20mesh.bin"), "my mesh.bin");
        assert_eq!(percent_decode("a%2"), "a%2");
    }
}
