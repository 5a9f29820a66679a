//! Helpers shared by the mesh tests: temporary folders and a PLY writer for every encoding.

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// A temporary folder removed on drop.
pub struct TempDir(PathBuf);

impl TempDir {
    /// A fresh, empty folder.
    pub fn new() -> TempDir {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let dir = std::env::temp_dir().join(format!("pathtrace-mesh-test-{}-{n}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        TempDir(dir)
    }

    /// Writes a file into the folder and returns its path.
    pub fn write(&self, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
        let path = self.0.join(name);
        std::fs::write(&path, bytes).unwrap();
        path
    }

    /// The folder.
    pub fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A PLY body encoding.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Enc {
    Ascii,
    Le,
    Be,
}

/// One property value: a scalar or a list.
#[derive(Clone, Debug)]
pub enum Val {
    S(f64),
    L(Vec<f64>),
}

/// An element: name, property declarations ("float x", "list uchar int vertex_indices") and
/// records.
#[derive(Clone)]
pub struct El<'a> {
    pub name: &'a str,
    pub props: &'a [&'a str],
    pub records: Vec<Vec<Val>>,
}

/// Writes a PLY file in the given encoding.
pub fn write_ply(enc: Enc, elements: &[El]) -> Vec<u8> {
    let format = match enc {
        Enc::Ascii => "ascii",
        Enc::Le => "binary_little_endian",
        Enc::Be => "binary_big_endian",
    };
    let mut out = format!("ply\nformat {format} 1.0\ncomment written by the tests\n");
    for el in elements {
        out += &format!("element {} {}\n", el.name, el.records.len());
        for p in el.props {
            out += &format!("property {p}\n");
        }
    }
    out += "end_header\n";
    let mut bytes = out.into_bytes();
    for el in elements {
        for record in &el.records {
            for (decl, val) in el.props.iter().zip(record) {
                let words: Vec<&str> = decl.split_whitespace().collect();
                match (words[0], val) {
                    ("list", Val::L(items)) => {
                        put(enc, words[1], items.len() as f64, &mut bytes);
                        for &v in items {
                            put(enc, words[2], v, &mut bytes);
                        }
                    }
                    (ty, Val::S(v)) => put(enc, ty, *v, &mut bytes),
                    _ => panic!("value does not match {decl}"),
                }
            }
            if enc == Enc::Ascii {
                bytes.push(b'\n');
            }
        }
    }
    bytes
}

/// Encodes one value.
fn put(enc: Enc, ty: &str, v: f64, out: &mut Vec<u8>) {
    macro_rules! bin {
        ($t:ty) => {{
            let x = v as $t;
            out.extend_from_slice(&if enc == Enc::Le { x.to_le_bytes() } else { x.to_be_bytes() })
        }};
    }
    if enc == Enc::Ascii {
        let text = if ty.contains("float") || ty == "double" { format!("{v} ") } else { format!("{} ", v as i64) };
        out.extend_from_slice(text.as_bytes());
        return;
    }
    match ty {
        "char" | "int8" => bin!(i8),
        "uchar" | "uint8" => bin!(u8),
        "short" | "int16" => bin!(i16),
        "ushort" | "uint16" => bin!(u16),
        "int" | "int32" => bin!(i32),
        "uint" | "uint32" => bin!(u32),
        "float" | "float32" => bin!(f32),
        "double" | "float64" => bin!(f64),
        _ => panic!("unknown type {ty}"),
    }
}

/// Scalars as values.
pub fn s(values: &[f64]) -> Vec<Val> {
    values.iter().map(|&v| Val::S(v)).collect()
}
