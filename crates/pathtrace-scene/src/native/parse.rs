//! Reading and writing [`SceneFile`]s as TOML or JSON, chosen by the file extension; every
//! syntax or schema error becomes a [`SceneError`] at its line and column.

use super::error::SceneError;
use super::locate::{locate_json, locate_toml, ItemPath, Locate};
use super::model::SceneFile;
use std::path::{Path, PathBuf};

/// The two spellings of the native format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Toml,
    Json,
}

impl Format {
    /// The format named by a path's extension (`.toml` or `.json`, any case).
    pub fn from_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "toml" => Some(Format::Toml),
            "json" => Some(Format::Json),
            _ => None,
        }
    }
}

/// A scene file's text, kept to turn item paths into line and column after parsing.
#[derive(Clone, Debug)]
pub struct Source {
    /// The file as named in messages.
    pub path: PathBuf,
    /// Its contents.
    pub text: String,
    /// How it is written.
    pub format: Format,
}

impl Source {
    /// An error about the item at `item` (or its deepest part present in the file).
    pub fn error_at(&self, item: &ItemPath, message: impl Into<String>) -> SceneError {
        let offset = match self.format {
            Format::Toml => locate_toml(&self.text, item),
            Format::Json => locate_json(&self.text, item),
        };
        SceneError::at_offset(&self.path, &self.text, offset, message)
    }

    /// Parses the text into the model.
    pub fn parse(&self) -> Result<SceneFile, SceneError> {
        parse_str(&self.text, self.format, &self.path)
    }
}

impl Locate for Source {
    fn path(&self) -> &Path {
        &self.path
    }

    fn error_at(&self, item: &ItemPath, message: impl Into<String>) -> SceneError {
        Source::error_at(self, item, message)
    }
}

/// Parses scene text; `path` only names the file in errors.
pub fn parse_str(text: &str, format: Format, path: &Path) -> Result<SceneFile, SceneError> {
    match format {
        Format::Toml => toml::from_str(text).map_err(|e| {
            let offset = e.span().map_or(0, |s| s.start);
            SceneError::at_offset(path, text, offset, e.message())
        }),
        Format::Json => serde_json::from_str(text).map_err(|e| {
            let full = e.to_string();
            let suffix = format!(" at line {} column {}", e.line(), e.column());
            let message = full.strip_suffix(&suffix).unwrap_or(&full);
            SceneError::at_line(path, text, e.line(), e.column(), message)
        }),
    }
}

/// Writes a scene in the given format.
pub fn to_string(scene: &SceneFile, format: Format) -> Result<String, String> {
    match format {
        Format::Toml => toml::to_string(scene).map_err(|e| e.to_string()),
        Format::Json => serde_json::to_string_pretty(scene).map(|s| s + "\n").map_err(|e| e.to_string()),
    }
}
