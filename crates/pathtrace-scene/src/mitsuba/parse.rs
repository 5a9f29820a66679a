//! Mitsuba 3 XML text → an owned element tree that keeps byte offsets (for `FILE:LINE:COL`
//! errors), with `<default>` parameters and caller overrides substituted into `$name` references.

use crate::native::SceneError;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The XML text of a scene file, kept to turn offsets into lines and columns.
#[derive(Clone, Debug)]
pub struct XmlSource {
    /// The file as named in messages.
    pub path: PathBuf,
    /// Its contents.
    pub text: String,
    /// Files read through `<include>`: their elements' offsets start at `base`, past the end of
    /// the main text and of the previous includes.
    pub includes: Vec<Included>,
}

/// One file read through `<include>`.
#[derive(Clone, Debug)]
pub struct Included {
    pub base: usize,
    pub path: PathBuf,
    pub text: String,
}

impl XmlSource {
    /// A source with no includes.
    pub fn new(path: PathBuf, text: String) -> Self {
        Self { path, text, includes: Vec::new() }
    }

    /// The file, its text and the local offset for a global offset.
    fn segment(&self, offset: usize) -> (&Path, &str, usize) {
        match self.includes.iter().rev().find(|s| offset >= s.base) {
            Some(s) => (&s.path, &s.text, offset - s.base),
            None => (&self.path, &self.text, offset),
        }
    }

    /// The first offset past everything read so far.
    fn end(&self) -> usize {
        self.includes.last().map_or(self.text.len(), |s| s.base + s.text.len()) + 1
    }

    /// An error at a byte offset (of the main file or an included one).
    pub fn error(&self, offset: usize, message: impl Into<String>) -> SceneError {
        let (path, text, local) = self.segment(offset);
        SceneError::at_offset(path, text, local, message)
    }

    /// `FILE:LINE:COL` of an offset.
    pub fn location(&self, offset: usize) -> String {
        let (path, text, local) = self.segment(offset);
        let (line, col) = crate::native::line_column(text, local);
        format!("{}:{line}:{col}", path.display())
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

fn convert(node: roxmltree::Node, depth: usize, base: usize) -> Result<Element, usize> {
    if depth > MAX_DEPTH {
        return Err(base + node.range().start);
    }
    let attrs = node
        .attributes()
        .map(|a| Attr {
            name: a.name().to_string(),
            value: a.value().to_string(),
            offset: base + a.range_value().start,
        })
        .collect();
    let children =
        node.children().filter(|c| c.is_element()).map(|c| convert(c, depth + 1, base)).collect::<Result<_, _>>()?;
    Ok(Element { tag: node.tag_name().name().to_string(), attrs, children, offset: base + node.range().start })
}

type R<T> = Result<T, SceneError>;

/// Parses one file's text (its offsets shifted by `base`) into its `<scene>` element.
fn parse_text(src: &XmlSource, text: &str, base: usize, path: Option<&Path>) -> R<Element> {
    let err_path = path.unwrap_or(&src.path);
    // The XML parser recurses per nesting level: refuse absurd nesting before it runs.
    if let Some(at) = too_deep(text) {
        return Err(SceneError::at_offset(
            err_path,
            text,
            at,
            format!("elements are nested more than {MAX_DEPTH} deep"),
        ));
    }
    let doc = roxmltree::Document::parse(text).map_err(|e| {
        let pos = e.pos();
        SceneError::at_line(err_path, text, pos.row as usize, pos.col as usize, format!("malformed XML: {e}"))
    })?;
    let root = convert(doc.root_element(), 0, base)
        .map_err(|at| src.error(at, format!("elements are nested more than {MAX_DEPTH} deep")))?;
    if root.tag != "scene" {
        return Err(src.error(root.offset, format!("the root element must be <scene>, not <{}>", root.tag)));
    }
    Ok(root)
}

/// Replaces each `<include filename>` child by the children of the file's `<scene>` (relative to
/// the main file's folder, as Mitsuba resolves it), recursively up to 8 levels.
fn expand_includes(src: &mut XmlSource, scene: &mut Element, level: usize) -> R<()> {
    let mut out = Vec::with_capacity(scene.children.len());
    for child in std::mem::take(&mut scene.children) {
        if child.tag != "include" {
            out.push(child);
            continue;
        }
        if level >= 8 {
            return Err(src.error(child.offset, "<include> is nested more than 8 deep (an include cycle?)"));
        }
        let Some(name) = child.attr("filename") else {
            return Err(src.error(child.offset, "<include> needs a `filename` attribute"));
        };
        let dir = src.path.parent().map(Path::to_path_buf).unwrap_or_default();
        let path = dir.join(name);
        let text = std::fs::read_to_string(&path).map_err(|e| {
            src.error(child.offset_of("filename"), format!("cannot read included file `{}`: {e}", path.display()))
        })?;
        let base = src.end();
        src.includes.push(Included { base, path: path.clone(), text: text.clone() });
        let mut inner = parse_text(src, &text, base, Some(&path))?;
        expand_includes(src, &mut inner, level + 1)?;
        out.extend(inner.children);
    }
    scene.children = out;
    Ok(())
}

/// Parses the text into the root `<scene>` element, substituting parameters: `<default>` values,
/// overridden by `defines` (a define without a matching `<default>` gives a warning). When two
/// `<default>`s name one parameter (a scene file and a file it includes, as mitsuba-data's
/// `medium_homogeneous_sss.xml` sets `max_depth` 64 and its included `shape_scene.xml` −1),
/// the first in document order wins, as in Mitsuba 3's parser (`src/core/parser.cpp`, the
/// `Default` tag: a parameter already known is kept).
pub fn parse(src: &mut XmlSource, defines: &[(&str, &str)], warnings: &mut Vec<String>) -> R<Element> {
    let text = src.text.clone();
    let mut root = parse_text(src, &text, 0, None)?;
    if root.attr("version").is_none() {
        warnings.push(format!(
            "{}: <scene> has no `version` attribute; reading it as Mitsuba 3",
            src.location(root.offset)
        ));
    }
    expand_includes(src, &mut root, 0)?;
    let mut params: BTreeMap<String, String> = BTreeMap::new();
    for d in root.children.iter().filter(|c| c.tag == "default") {
        let (Some(name), Some(value)) = (d.attr("name"), d.attr("value")) else {
            return Err(src.error(d.offset, "<default> needs `name` and `value`"));
        };
        params.entry(name.to_string()).or_insert_with(|| value.to_string());
    }
    for (name, value) in defines {
        if !params.contains_key(*name) {
            warnings.push(format!("parameter `{name}` is defined but the scene has no <default name=\"{name}\">"));
        }
        params.insert(name.to_string(), value.to_string());
    }
    substitute(&mut root, &params);
    // After substitution, as Mitsuba upgrades the parsed properties (`$name` may be a colour).
    if super::upgrade::is_v1(&root) {
        super::upgrade::upgrade(&mut root, src, warnings)?;
    }
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
