//! Mesh loading errors: every one names the file and, for bad content, the line (text) or the
//! byte offset (binary data) where the problem was found.

use std::path::{Path, PathBuf};

/// Why a mesh file could not be loaded. `Display` is always one line.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum MeshLoadError {
    /// The file could not be read, or its extension names no supported mesh format.
    #[error("{}: {message}", file.display())]
    File {
        /// The file named by the caller.
        file: PathBuf,
        /// What went wrong.
        message: String,
    },
    /// Bad text: an OBJ line, a PLY header line or ASCII PLY data. Lines count from 1.
    #[error("{}:{line}: {message}", file.display())]
    Line {
        /// The mesh file.
        file: PathBuf,
        /// The 1-based line number.
        line: usize,
        /// What is wrong there.
        message: String,
    },
    /// Bad binary PLY data, at a byte offset from the start of the file.
    #[error("{}: {message} (byte offset {offset})", file.display())]
    Offset {
        /// The mesh file.
        file: PathBuf,
        /// Byte offset of the offending value from the start of the file.
        offset: u64,
        /// What is wrong there.
        message: String,
    },
}

impl MeshLoadError {
    /// The message without file name and location.
    pub fn message(&self) -> String {
        match self {
            MeshLoadError::File { message, .. }
            | MeshLoadError::Line { message, .. }
            | MeshLoadError::Offset { message, .. } => message.clone(),
        }
    }

    /// The file the error is about.
    pub fn file(&self) -> &Path {
        match self {
            MeshLoadError::File { file, .. }
            | MeshLoadError::Line { file, .. }
            | MeshLoadError::Offset { file, .. } => file,
        }
    }

    /// The 1-based line of the error, for text content.
    pub fn line(&self) -> Option<usize> {
        match self {
            MeshLoadError::Line { line, .. } => Some(*line),
            _ => None,
        }
    }

    /// The byte offset of the error, for binary content.
    pub fn offset(&self) -> Option<u64> {
        match self {
            MeshLoadError::Offset { offset, .. } => Some(*offset),
            _ => None,
        }
    }
}

/// Where inside the content a parser failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Loc {
    /// 1-based line number.
    Line(usize),
    /// Byte offset from the start of the file.
    Offset(u64),
}

/// A parser failure before the file name is attached.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Failure {
    pub loc: Loc,
    pub message: String,
}

impl Failure {
    /// A failure on a 1-based line.
    pub fn line(line: usize, message: impl Into<String>) -> Failure {
        Failure { loc: Loc::Line(line), message: message.into() }
    }

    /// A failure at a byte offset.
    pub fn offset(offset: usize, message: impl Into<String>) -> Failure {
        Failure { loc: Loc::Offset(offset as u64), message: message.into() }
    }

    /// Attaches the file name.
    pub fn into_error(self, file: &Path) -> MeshLoadError {
        let file = file.to_path_buf();
        match self.loc {
            Loc::Line(line) => MeshLoadError::Line { file, line, message: self.message },
            Loc::Offset(offset) => MeshLoadError::Offset { file, offset, message: self.message },
        }
    }
}

/// Quotes a piece of input for a one-line message: lossy UTF-8, control characters escaped,
/// at most 40 characters.
pub(crate) fn quote(bytes: &[u8]) -> String {
    let text = String::from_utf8_lossy(bytes);
    let mut short: String = text.chars().take(40).collect();
    if text.chars().count() > 40 {
        short.push('…');
    }
    format!("{short:?}")
}
