//! [`SceneError`]: one message that names the file, line and column of what is wrong.

use std::fmt;
use std::path::{Path, PathBuf};

/// Why a scene file cannot be loaded, and where. Displays as `FILE:LINE:COL: message`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneError {
    /// The scene file (as given).
    pub path: PathBuf,
    /// 1-based line.
    pub line: usize,
    /// 1-based column, counted in characters.
    pub column: usize,
    /// What is wrong, with the offending text where there is some.
    pub message: String,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}: {}", self.path.display(), self.line, self.column, self.message)
    }
}

impl std::error::Error for SceneError {}

impl SceneError {
    /// An error about the whole file (reading it, an empty scene): reported at 1:1.
    pub fn whole_file(path: &Path, message: impl Into<String>) -> Self {
        Self { path: path.to_path_buf(), line: 1, column: 1, message: crate::elide::elide_long_runs(&message.into()) }
    }

    /// An error at a byte offset of `text`, quoting the offending line.
    pub fn at_offset(path: &Path, text: &str, offset: usize, message: impl Into<String>) -> Self {
        let (line, column) = line_column(text, offset);
        Self::at_line(path, text, line, column, message)
    }

    /// An error at a 1-based line and column of `text` (values below 1 are raised to 1),
    /// quoting the offending line.
    pub fn at_line(path: &Path, text: &str, line: usize, column: usize, message: impl Into<String>) -> Self {
        let (line, column) = (line.max(1), column.max(1));
        let mut message = message.into();
        // Keep the message on one line: parsers sometimes wrap theirs.
        message = message.split_whitespace().collect::<Vec<_>>().join(" ");
        // A value echoed in the message may be megabytes long.
        message = crate::elide::elide_long_runs(&message);
        if let Some(quote) = snippet(text, line) {
            message = format!("{message} — in `{quote}`");
        }
        Self { path: path.to_path_buf(), line, column, message }
    }
}

/// 1-based line and character column of a byte offset (clamped to the text).
pub fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, text[line_start..offset].chars().count() + 1)
}

/// The given line, trimmed and shortened for a message; `None` if it is blank or absent.
fn snippet(text: &str, line: usize) -> Option<String> {
    const MAX: usize = 60;
    let l = text.lines().nth(line - 1)?.trim();
    if l.is_empty() {
        return None;
    }
    let mut s: String = l.chars().take(MAX).collect();
    if l.chars().count() > MAX {
        s.push('…');
    }
    Some(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offsets_become_lines_and_character_columns() {
        let t = "ab\nçd = 1\n";
        assert_eq!(line_column(t, 0), (1, 1));
        assert_eq!(line_column(t, 3), (2, 1));
        assert_eq!(line_column(t, 5), (2, 2)); // after the two-byte ç
        assert_eq!(line_column(t, 999), (3, 1));
    }

    #[test]
    fn messages_quote_the_line_and_stay_on_one_line() {
        let e = SceneError::at_offset(Path::new("s.toml"), "x = 1\nradius = nan\n", 15, "bad\nnumber");
        assert_eq!(e.to_string(), "s.toml:2:10: bad number — in `radius = nan`");
        let e = SceneError::at_line(Path::new("s.json"), "", 0, 0, "empty");
        assert_eq!(e.to_string(), "s.json:1:1: empty");
    }
}
