//! Where PLY body values come from: binary slices decoded in place, or ASCII tokens.

use super::header::Scalar;
use crate::mesh::error::{quote, Failure};

/// A stream of PLY body values.
pub(crate) trait Source {
    /// The next value, converted to f32 (not yet checked for finiteness).
    fn float(&mut self, ty: Scalar) -> Result<f32, Failure>;
    /// The next value of an integer type.
    fn int(&mut self, ty: Scalar) -> Result<i64, Failure>;
    /// Skips `n` values of one type.
    fn skip(&mut self, ty: Scalar, n: u64) -> Result<(), Failure>;
    /// Fails unless `count` records could still fit in the file, each taking at least
    /// `size.0` bytes in binary or `size.1` values in ASCII.
    fn check_fits(&self, count: u64, size: MinSize, what: &str) -> Result<(), Failure>;
    /// How many more records of at least `size` could fit: a safe capacity bound.
    fn fits(&self, size: MinSize) -> u64;
    /// A failure located at the start of the last value read.
    fn fail(&self, message: String) -> Failure;
}

/// The smallest a record can be: (bytes in binary, values in ASCII).
pub(crate) type MinSize = (usize, usize);

/// A binary body, little or big endian.
pub(crate) struct Binary<'a> {
    bytes: &'a [u8],
    pos: usize,
    last: usize,
    big: bool,
}

impl<'a> Binary<'a> {
    /// Reads `bytes` from `start`.
    pub fn new(bytes: &'a [u8], start: usize, big: bool) -> Binary<'a> {
        Binary { bytes, pos: start, last: start, big }
    }

    /// The next `N` bytes.
    #[inline(always)]
    fn take<const N: usize>(&mut self) -> Result<[u8; N], Failure> {
        self.last = self.pos;
        let slice = self.bytes.get(self.pos..self.pos + N).ok_or_else(|| self.truncated())?;
        self.pos += N;
        let mut out = [0; N];
        out.copy_from_slice(slice);
        Ok(out)
    }

    fn truncated(&self) -> Failure {
        Failure::offset(self.pos, "the file ends in the middle of the data")
    }
}

macro_rules! decode {
    ($self:ident, $ty:ident, $conv:ty) => {{
        let big = $self.big;
        match $ty {
            Scalar::I8 => $self.take::<1>()?[0] as i8 as $conv,
            Scalar::U8 => $self.take::<1>()?[0] as $conv,
            Scalar::I16 => {
                $self.take::<2>().map(|b| if big { i16::from_be_bytes(b) } else { i16::from_le_bytes(b) })? as $conv
            }
            Scalar::U16 => {
                $self.take::<2>().map(|b| if big { u16::from_be_bytes(b) } else { u16::from_le_bytes(b) })? as $conv
            }
            Scalar::I32 => {
                $self.take::<4>().map(|b| if big { i32::from_be_bytes(b) } else { i32::from_le_bytes(b) })? as $conv
            }
            Scalar::U32 => {
                $self.take::<4>().map(|b| if big { u32::from_be_bytes(b) } else { u32::from_le_bytes(b) })? as $conv
            }
            Scalar::F32 => {
                $self.take::<4>().map(|b| if big { f32::from_be_bytes(b) } else { f32::from_le_bytes(b) })? as $conv
            }
            Scalar::F64 => {
                $self.take::<8>().map(|b| if big { f64::from_be_bytes(b) } else { f64::from_le_bytes(b) })? as $conv
            }
        }
    }};
}

impl Source for Binary<'_> {
    #[inline]
    fn float(&mut self, ty: Scalar) -> Result<f32, Failure> {
        Ok(decode!(self, ty, f32))
    }

    #[inline]
    fn int(&mut self, ty: Scalar) -> Result<i64, Failure> {
        if !ty.is_integer() {
            return Err(Failure::offset(self.pos, "an index or count must have an integer type"));
        }
        Ok(decode!(self, ty, i64))
    }

    fn skip(&mut self, ty: Scalar, n: u64) -> Result<(), Failure> {
        self.last = self.pos;
        let len = n.checked_mul(ty.size() as u64).filter(|&l| l <= (self.bytes.len() - self.pos) as u64);
        let Some(len) = len else { return Err(self.truncated()) };
        self.pos += len as usize;
        Ok(())
    }

    fn check_fits(&self, count: u64, size: MinSize, what: &str) -> Result<(), Failure> {
        if count > self.fits(size) {
            let left = self.bytes.len() - self.pos;
            let message = format!("the header declares {count} {what}, more than the {left} bytes left can hold");
            return Err(Failure::offset(self.pos, message));
        }
        Ok(())
    }

    fn fits(&self, size: MinSize) -> u64 {
        ((self.bytes.len() - self.pos) / size.0.max(1)) as u64
    }

    fn fail(&self, message: String) -> Failure {
        Failure::offset(self.last, message)
    }
}

/// An ASCII body: whitespace-separated tokens, with line numbers for errors.
pub(crate) struct Ascii<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: usize,
    last_line: usize,
}

impl<'a> Ascii<'a> {
    /// Reads `bytes` from `start`, which is on line `line`.
    pub fn new(bytes: &'a [u8], start: usize, line: usize) -> Ascii<'a> {
        Ascii { bytes, pos: start, line, last_line: line }
    }

    /// The next token.
    fn token(&mut self) -> Result<&'a [u8], Failure> {
        while let Some(&b) = self.bytes.get(self.pos) {
            if !b.is_ascii_whitespace() {
                break;
            }
            if b == b'\n' {
                self.line += 1;
            }
            self.pos += 1;
        }
        self.last_line = self.line;
        let start = self.pos;
        while self.bytes.get(self.pos).is_some_and(|b| !b.is_ascii_whitespace()) {
            self.pos += 1;
        }
        if start == self.pos {
            return Err(Failure::line(self.line, "the file ends in the middle of the data"));
        }
        Ok(&self.bytes[start..self.pos])
    }
}

impl Source for Ascii<'_> {
    fn float(&mut self, ty: Scalar) -> Result<f32, Failure> {
        if ty.is_integer() {
            return self.int(ty).map(|i| i as f32);
        }
        let token = self.token()?;
        let value: Option<f64> = std::str::from_utf8(token).ok().and_then(|s| s.parse().ok());
        value.map(|v| v as f32).ok_or_else(|| self.fail(format!("malformed number {}", quote(token))))
    }

    fn int(&mut self, ty: Scalar) -> Result<i64, Failure> {
        let token = self.token()?;
        if !ty.is_integer() {
            return Err(self.fail("an index or count must have an integer type".to_string()));
        }
        std::str::from_utf8(token)
            .ok()
            .and_then(|s| s.parse().ok())
            .ok_or_else(|| self.fail(format!("malformed integer {}", quote(token))))
    }

    fn skip(&mut self, _ty: Scalar, n: u64) -> Result<(), Failure> {
        for _ in 0..n {
            self.token()?;
        }
        Ok(())
    }

    fn check_fits(&self, count: u64, size: MinSize, what: &str) -> Result<(), Failure> {
        if count > self.fits(size) {
            let message = format!("the header declares {count} {what}, more than the rest of the file can hold");
            return Err(Failure::line(self.line, message));
        }
        Ok(())
    }

    fn fits(&self, size: MinSize) -> u64 {
        // Each value takes at least one character and one separator.
        let left = self.bytes.len() - self.pos + 1;
        (left / (2 * size.1.max(1))) as u64
    }

    fn fail(&self, message: String) -> Failure {
        Failure::line(self.last_line, message)
    }
}
