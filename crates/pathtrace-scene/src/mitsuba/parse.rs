//! Mitsuba 3 XML text → an owned element tree that keeps byte offsets (for `FILE:LINE:COL`
//! errors), with `<default>` parameters and caller overrides substituted into `$name` references.

use crate::native::SceneError;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// The XML text of a scene file, kept to turn offsets into lines and columns.
#[derive(Clone, Debug)]
pub struct XmlSource {
    /// The file as named in messages.
    pub path: PathBuf,
    /// Its contents.
    pub text: String,
}

impl XmlSource {
    /// An error at a byte offset of the text.
    pub fn error(&self, offset: usize, message: impl Into<String>) -> SceneError {
        SceneError::at_offset(&self.path, &self.text, offset, message)
    }
}

/// One attribute with the byte offset of its value.
#[derive(Clone, Debug, PartialEq)]
pub struct Attr {
    pub name: String,
    pub value: String,
    pub offset: usize,
}

/// One XML element: tag, attributes (after substitution), child elements and its byte offset.
#[derive(Clone, Debug, PartialEq)]
pub struct Element {
    pub tag: String,
    pub attrs: Vec<Attr>,
    pub children: Vec<Element>,
    pub offset: usize,
}

impl Element {
    /// The value of an attribute.
    pub fn attr(&self, name: &str) -> Option<&str> {
        self.attrs.iter().find(|a| a.name == name).map(|a| a.value.as_str())
    }

    /// An attribute with its offset.
    pub fn attr_full(&self, name: &str) -> Option<&Attr> {
        self.attrs.iter().find(|a| a.name == name)
    }

    /// The offset of an attribute's value, or of the element.
    pub fn offset_of(&self, name: &str) -> usize {
        self.attr_full(name).map_or(self.offset, |a| a.offset)
    }
}

/// Deepest element nesting accepted (real scenes use fewer than 10 levels).
const MAX_DEPTH: usize = 64;

fn convert(node: roxmltree::Node, depth: usize) -> Result<Element, usize> {
    if depth > MAX_DEPTH {
        return Err(node.range().start);
    }
    let attrs = node
        .attributes()
        .map(|a| Attr { name: a.name().to_string(), value: a.value().to_string(), offset: a.range_value().start })
        .collect();
    let children =
        node.children().filter(|c| c.is_element()).map(|c| convert(c, depth + 1)).collect::<Result<_, _>>()?;
    Ok(Element { tag: node.tag_name().name().to_string(), attrs, children, offset: node.range().start })
}

/// Parses the text into the root `<scene>` element, substituting parameters: `<default>` values,
/// overridden by `defines` (a define without a matching `<default>` gives a warning).
pub fn parse(src: &XmlSource, defines: &[(&str, &str)], warnings: &mut Vec<String>) -> Result<Element, SceneError> {
    // The XML parser recurses per nesting level: refuse absurd nesting before it runs.
    if let Some(at) = too_deep(&src.text) {
        return Err(src.error(at, format!("elements are nested more than {MAX_DEPTH} deep")));
    }
    let doc = roxmltree::Document::parse(&src.text).map_err(|e| {
        let pos = e.pos();
        SceneError::at_line(&src.path, &src.text, pos.row as usize, pos.col as usize, format!("malformed XML: {e}"))
    })?;
    let mut root = convert(doc.root_element(), 0)
        .map_err(|at| src.error(at, format!("elements are nested more than {MAX_DEPTH} deep")))?;
    if root.tag != "scene" {
        return Err(src.error(root.offset, format!("the root element must be <scene>, not <{}>", root.tag)));
    }
    if root.attr("version").is_none() {
        warnings.push("<scene> has no `version` attribute; reading it as Mitsuba 3".to_string());
    }
    let mut params: BTreeMap<String, String> = BTreeMap::new();
    for d in root.children.iter().filter(|c| c.tag == "default") {
        let (Some(name), Some(value)) = (d.attr("name"), d.attr("value")) else {
            return Err(src.error(d.offset, "<default> needs `name` and `value`"));
        };
        params.insert(name.to_string(), value.to_string());
    }
    for (name, value) in defines {
        if !params.contains_key(*name) {
            warnings.push(format!("parameter `{name}` is defined but the scene has no <default name=\"{name}\">"));
        }
        params.insert(name.to_string(), value.to_string());
    }
    substitute(&mut root, &params);
    Ok(root)
}

/// The offset of the first start tag nested deeper than [`MAX_DEPTH`], by a quick scan that
/// skips comments, CDATA, declarations and quoted attribute values.
fn too_deep(text: &str) -> Option<usize> {
    let b = text.as_bytes();
    let find = |from: usize, pat: &str| text.get(from..).and_then(|t| t.find(pat)).map(|i| from + i + pat.len());
    let (mut i, mut depth) = (0usize, 0usize);
    while i < b.len() {
        if b[i] != b'<' {
            i += 1;
            continue;
        }
        let rest = &text[i..];
        let skip = if rest.starts_with("<!--") {
            find(i, "-->")
        } else if rest.starts_with("<![CDATA[") {
            find(i, "]]>")
        } else if rest.starts_with("<?") {
            find(i, "?>")
        } else if rest.starts_with("<!") || rest.starts_with("</") {
            depth = depth.saturating_sub(usize::from(rest.starts_with("</")));
            find(i, ">")
        } else {
            // A start tag: find its end outside quotes.
            let (mut j, mut quote) = (i + 1, None);
            while j < b.len() {
                match (quote, b[j]) {
                    (None, q @ (b'"' | b'\'')) => quote = Some(q),
                    (Some(q), c) if c == q => quote = None,
                    (None, b'>') => break,
                    _ => {}
                }
                j += 1;
            }
            if j < b.len() && b[j - 1] != b'/' {
                depth += 1;
                if depth > MAX_DEPTH {
                    return Some(i);
                }
            }
            Some(j + 1)
        };
        i = skip.unwrap_or(b.len());
    }
    None
}

fn substitute(e: &mut Element, params: &BTreeMap<String, String>) {
    if e.tag != "default" {
        for a in &mut e.attrs {
            if a.value.contains('$') {
                a.value = substitute_str(&a.value, params);
            }
        }
    }
    for c in &mut e.children {
        substitute(c, params);
    }
}

/// Replaces each `$name` (letters, digits, `_`) that names a parameter; others stay as written.
pub fn substitute_str(s: &str, params: &BTreeMap<String, String>) -> String {
    let mut out = String::with_capacity(s.len());
    let mut rest = s;
    while let Some(i) = rest.find('$') {
        out.push_str(&rest[..i]);
        let after = &rest[i + 1..];
        let len = after.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).unwrap_or(after.len());
        match params.get(&after[..len]) {
            Some(v) if len > 0 => out.push_str(v),
            _ => {
                out.push('$');
                out.push_str(&after[..len]);
            }
        }
        rest = &after[len..];
    }
    out.push_str(rest);
    out
}
