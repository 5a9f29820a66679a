//! The PLY header: format, elements and their properties, up to `end_header`.

use crate::mesh::error::{quote, Failure};

/// How the body is encoded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Format {
    Ascii,
    BinaryLittleEndian,
    BinaryBigEndian,
}

/// A PLY scalar type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    /// Parses a type name, both the classic (`uchar`) and the sized (`uint8`) spelling.
    fn parse(name: &[u8]) -> Option<Scalar> {
        Some(match name {
            b"char" | b"int8" => Scalar::I8,
            b"uchar" | b"uint8" => Scalar::U8,
            b"short" | b"int16" => Scalar::I16,
            b"ushort" | b"uint16" => Scalar::U16,
            b"int" | b"int32" => Scalar::I32,
            b"uint" | b"uint32" => Scalar::U32,
            b"float" | b"float32" => Scalar::F32,
            b"double" | b"float64" => Scalar::F64,
            _ => return None,
        })
    }

    /// Size in bytes in binary encodings.
    pub fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    /// Whether this is an integer type.
    pub fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }
}

/// A property's type: one scalar, or a list with its count and item types.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

impl Kind {
    /// The fewest bytes a value of this kind takes in a binary body.
    pub fn min_size(self) -> usize {
        match self {
            Kind::Scalar(s) => s.size(),
            Kind::List { count, .. } => count.size(),
        }
    }
}

/// A named property of an element.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Property {
    pub name: String,
    pub kind: Kind,
    /// Its header line.
    pub line: usize,
}

/// An element declaration: name, record count and properties.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Element {
    pub name: String,
    pub count: u64,
    pub properties: Vec<Property>,
    /// Its header line.
    pub line: usize,
}

/// A parsed header.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Header {
    pub format: Format,
    pub elements: Vec<Element>,
    /// Byte offset of the first body byte.
    pub body_start: usize,
    /// Line number of `end_header`.
    pub end_line: usize,
}

/// Parses the header at the start of `bytes`.
pub(crate) fn parse(bytes: &[u8]) -> Result<Header, Failure> {
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    let mut pos = 0;
    let mut line_no = 0;
    while pos < bytes.len() {
        line_no += 1;
        let end = bytes[pos..].iter().position(|&b| b == b'\n').map_or(bytes.len(), |e| pos + e);
        let raw = &bytes[pos..end];
        pos = (end + 1).min(bytes.len());
        let mut tokens = raw.split(|b| b.is_ascii_whitespace()).filter(|t| !t.is_empty());
        let keyword = tokens.next().unwrap_or_default();
        let err = |message: String| Err(Failure::line(line_no, message));
        if line_no == 1 {
            if keyword != b"ply" {
                return err("not a PLY file: the first line must be \"ply\"".to_string());
            }
            continue;
        }
        match keyword {
            b"format" => {
                format = Some(match tokens.next().unwrap_or_default() {
                    b"ascii" => Format::Ascii,
                    b"binary_little_endian" => Format::BinaryLittleEndian,
                    b"binary_big_endian" => Format::BinaryBigEndian,
                    other => return err(format!("unknown PLY format {}", quote(other))),
                })
            }
            b"comment" | b"obj_info" | b"" => {}
            b"element" => {
                let (Some(name), Some(count)) = (tokens.next(), tokens.next()) else {
                    return err("expected \"element NAME COUNT\"".to_string());
                };
                let Some(count) = std::str::from_utf8(count).ok().and_then(|c| c.parse::<u64>().ok()) else {
                    return err(format!("malformed element count {}", quote(count)));
                };
                let name = String::from_utf8_lossy(name).into_owned();
                elements.push(Element { name, count, properties: Vec::new(), line: line_no });
            }
            b"property" => {
                let Some(element) = elements.last_mut() else {
                    return err("a property before any element".to_string());
                };
                let property = property(tokens, line_no)?;
                element.properties.push(property);
            }
            b"end_header" => {
                let Some(format) = format else {
                    return err("the header has no \"format\" line".to_string());
                };
                return Ok(Header { format, elements, body_start: pos, end_line: line_no });
            }
            other => return err(format!("unknown header keyword {}", quote(other))),
        }
    }
    Err(Failure::line(line_no.max(1), "the header has no \"end_header\" line"))
}

/// The rest of a `property` line: `TYPE NAME` or `list COUNT_TYPE ITEM_TYPE NAME`.
fn property<'a>(mut tokens: impl Iterator<Item = &'a [u8]>, line_no: usize) -> Result<Property, Failure> {
    let scalar = |t: Option<&[u8]>| {
        let t = t.unwrap_or_default();
        Scalar::parse(t).ok_or_else(|| Failure::line(line_no, format!("unknown property type {}", quote(t))))
    };
    let first = tokens.next();
    let kind = if first == Some(b"list".as_slice()) {
        let count = scalar(tokens.next())?;
        let item = scalar(tokens.next())?;
        if !count.is_integer() {
            return Err(Failure::line(line_no, "a list count must have an integer type"));
        }
        Kind::List { count, item }
    } else {
        Kind::Scalar(scalar(first)?)
    };
    let Some(name) = tokens.next() else {
        return Err(Failure::line(line_no, "the property has no name"));
    };
    Ok(Property { name: String::from_utf8_lossy(name).into_owned(), kind, line: line_no })
}
