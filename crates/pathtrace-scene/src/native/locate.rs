//! Finding where an item of a parsed scene is written, so errors found while building (an
//! unknown material, a degenerate quad) still point at their line. An item is named by its
//! [`ItemPath`] (`objects[3].material`); the located offset is that of the deepest part of the
//! path present in the file (a missing field is reported at its object).

use std::fmt;

/// One step of a path into the document.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Key {
    /// A field of a table/object.
    Field(String),
    /// An element of an array.
    Index(usize),
}

/// Where an item sits in the document, e.g. `groups[0].objects[2].transform[1]`.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ItemPath(pub Vec<Key>);

impl ItemPath {
    /// The empty path: the whole document.
    pub fn root() -> Self {
        Self::default()
    }

    /// This path extended by a field.
    pub fn field(&self, name: &str) -> Self {
        let mut p = self.clone();
        p.0.push(Key::Field(name.to_string()));
        p
    }

    /// This path extended by an array index.
    pub fn index(&self, i: usize) -> Self {
        let mut p = self.clone();
        p.0.push(Key::Index(i));
        p
    }
}

impl fmt::Display for ItemPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, k) in self.0.iter().enumerate() {
            match k {
                Key::Field(name) if i == 0 => write!(f, "{name}")?,
                Key::Field(name) => write!(f, ".{name}")?,
                Key::Index(n) => write!(f, "[{n}]")?,
            }
        }
        Ok(())
    }
}

/// Byte offset of `path` in a TOML document (0 if the document does not parse).
pub fn locate_toml(text: &str, path: &ItemPath) -> usize {
    let Ok(root) = toml::de::DeTable::parse(text) else { return 0 };
    let root_value = toml::de::DeValue::Table(root.get_ref().clone());
    let mut here = &root_value;
    let mut offset = 0;
    for key in &path.0 {
        let next = match key {
            Key::Field(name) => here.get(name.as_str()),
            Key::Index(i) => here.get(*i),
        };
        match next {
            Some(v) => {
                offset = v.span().start;
                here = v.get_ref();
            }
            None => break,
        }
    }
    offset
}

/// Byte offset of `path` in a JSON document that `serde_json` accepted (0 if not found).
pub fn locate_json(text: &str, path: &ItemPath) -> usize {
    let mut s = JsonScan { b: text.as_bytes(), text, pos: 0 };
    s.ws();
    s.find(&path.0).unwrap_or(0)
}

/// A minimal scanner over valid JSON: enough to skip values and walk to a path.
struct JsonScan<'a> {
    b: &'a [u8],
    text: &'a str,
    pos: usize,
}

impl JsonScan<'_> {
    fn ws(&mut self) {
        while self.b.get(self.pos).is_some_and(|c| c.is_ascii_whitespace()) {
            self.pos += 1;
        }
    }

    fn eat(&mut self, c: u8) -> Option<()> {
        self.ws();
        (self.b.get(self.pos) == Some(&c)).then(|| self.pos += 1)
    }

    /// Skips a string starting at `pos` (which holds `"`); returns its decoded value.
    fn string(&mut self) -> Option<String> {
        let start = self.pos;
        self.pos += 1;
        loop {
            match self.b.get(self.pos)? {
                b'\\' => self.pos += 2,
                b'"' => break,
                _ => self.pos += 1,
            }
        }
        self.pos += 1;
        serde_json::from_str(self.text.get(start..self.pos)?).ok()
    }

    fn skip_value(&mut self) -> Option<()> {
        self.ws();
        match *self.b.get(self.pos)? {
            b'"' => self.string().map(|_| ()),
            open @ (b'{' | b'[') => {
                let close = if open == b'{' { b'}' } else { b']' };
                self.pos += 1;
                if self.eat(close).is_some() {
                    return Some(());
                }
                loop {
                    if open == b'{' {
                        self.ws();
                        self.string()?;
                        self.eat(b':')?;
                    }
                    self.skip_value()?;
                    if self.eat(b',').is_none() {
                        return self.eat(close);
                    }
                }
            }
            _ => {
                while self.b.get(self.pos).is_some_and(|c| !b",}] \t\r\n".contains(c)) {
                    self.pos += 1;
                }
                Some(())
            }
        }
    }

    /// With `pos` at a value, the offset of `path` inside it (or of its deepest present prefix).
    fn find(&mut self, path: &[Key]) -> Option<usize> {
        self.ws();
        let here = self.pos;
        let Some((key, rest)) = path.split_first() else { return Some(here) };
        match (key, self.b.get(self.pos)) {
            (Key::Field(name), Some(b'{')) => {
                self.pos += 1;
                if self.eat(b'}').is_some() {
                    return Some(here);
                }
                loop {
                    self.ws();
                    let k = self.string()?;
                    self.eat(b':')?;
                    if &k == name {
                        return self.find(rest);
                    }
                    self.skip_value()?;
                    if self.eat(b',').is_none() {
                        return Some(here);
                    }
                }
            }
            (Key::Index(i), Some(b'[')) => {
                self.pos += 1;
                if self.eat(b']').is_some() {
                    return Some(here);
                }
                for _ in 0..*i {
                    self.skip_value()?;
                    if self.eat(b',').is_none() {
                        return Some(here);
                    }
                }
                self.find(rest)
            }
            _ => Some(here),
        }
    }
}

/// Turns an item of a parsed scene into an error at its place in the file the scene was read
/// from: a native TOML/JSON [`super::Source`], or Mitsuba XML through the element each item was
/// converted from.
pub trait Locate {
    /// The scene file (relative mesh paths resolve against its folder).
    fn path(&self) -> &std::path::Path;
    /// An error about `item` (or the deepest part of it the file shows), quoting the file.
    fn error_at(&self, item: &ItemPath, message: impl Into<String>) -> super::SceneError;
}

impl ItemPath {
    /// True if `self` starts with every key of `prefix`.
    pub fn starts_with(&self, prefix: &ItemPath) -> bool {
        self.0.len() >= prefix.0.len() && self.0.iter().zip(&prefix.0).all(|(a, b)| a == b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn path() -> ItemPath {
        ItemPath::root().field("objects").index(1).field("material")
    }

    #[test]
    fn json_paths_are_found() {
        let t = r#"{"a": {"x": [1, "]"]}, "objects": [{"material": "a"}, {"type": "quad", "material": "b\"c"}]}"#;
        let at = locate_json(t, &path());
        assert!(t[at..].starts_with(r#""b\"c""#), "{}", &t[at..]);
        let missing = ItemPath::root().field("objects").index(7);
        assert!(t[locate_json(t, &missing)..].starts_with("[{"));
    }

    #[test]
    fn toml_paths_are_found() {
        let t = "[a]\nx = 1\n\n[[objects]]\nmaterial = \"a\"\n\n[[objects]]\ntype = \"quad\"\nmaterial = \"b\"\n";
        let at = locate_toml(t, &path());
        assert!(t[at..].starts_with("\"b\""), "{}", &t[at..]);
        assert_eq!(path().to_string(), "objects[1].material");
    }
}
