//! Portable Float Map (PFM) encoding and decoding.
//!
//! Layout (Paul Debevec's HDRShop description of PFM, as used by `pfmtools`):
//! a text header `PF` (colour) or `Pf` (greyscale), then width and height, then a
//! scale whose sign gives the byte order (negative = little-endian), each separated
//! by whitespace with exactly one whitespace byte after the scale; then 32-bit floats,
//! RGB interleaved for `PF`, with rows stored from the **bottom** of the image up.

use std::io::{self, Write};

use pathtrace::film::Image;
use pathtrace::math::Rgb;

/// Writes `image` as little-endian colour PFM. The caller checks that the image is
/// non-empty and consistent.
pub(crate) fn encode(out: &mut impl Write, image: &Image) -> io::Result<()> {
    write!(out, "PF\n{} {}\n-1.0\n", image.width, image.height)?;
    let width = image.width as usize;
    if width == 0 {
        return Ok(());
    }
    // PFM rows run bottom-to-top; ours top-to-bottom.
    for row in image.pixels.chunks_exact(width).rev() {
        for p in row {
            for c in p.to_array() {
                out.write_all(&c.to_le_bytes())?;
            }
        }
    }
    Ok(())
}

/// Parses a PFM file held in memory. Errors are human-readable reasons.
pub(crate) fn decode(bytes: &[u8]) -> Result<Image, String> {
    let mut header = Header { bytes, pos: 0 };
    let channels = match header.token("the PF/Pf magic")? {
        "PF" => 3,
        "Pf" => 1,
        other => return Err(format!("not a PFM file: starts with {:?}, expected \"PF\" or \"Pf\"", truncate(other))),
    };
    let width = header.dimension("width")?;
    let height = header.dimension("height")?;
    let scale_token = header.token("the scale")?;
    let scale: f32 = scale_token.parse().map_err(|_| format!("scale {:?} is not a number", truncate(scale_token)))?;
    if scale == 0.0 || !scale.is_finite() {
        return Err(format!("scale {scale} must be a non-zero finite number (its sign gives the byte order)"));
    }
    let little_endian = scale < 0.0;
    header.single_whitespace()?;

    let floats = (width as usize)
        .checked_mul(height as usize)
        .and_then(|n| n.checked_mul(channels))
        .ok_or_else(|| format!("{width}x{height} is too large"))?;
    let needed = floats.checked_mul(4).ok_or_else(|| format!("{width}x{height} is too large"))?;
    let mut data = &bytes[header.pos..];
    // Tolerate a CRLF after the scale (written by some Windows tools).
    if data.len() == needed + 1 && bytes[header.pos - 1] == b'\r' && data[0] == b'\n' {
        data = &data[1..];
    }
    if data.len() < needed {
        return Err(format!(
            "truncated: a {width}x{height} {} image needs {needed} bytes of pixel data, found {}",
            if channels == 3 { "colour" } else { "greyscale" },
            data.len()
        ));
    }

    let read = |chunk: &[u8]| -> f32 {
        let b = [chunk[0], chunk[1], chunk[2], chunk[3]];
        if little_endian {
            f32::from_le_bytes(b)
        } else {
            f32::from_be_bytes(b)
        }
    };
    let row_bytes = width as usize * channels * 4;
    let mut pixels = Vec::with_capacity(width as usize * height as usize);
    // File rows are bottom-to-top: walk them in reverse to build top-to-bottom rows.
    for row in data[..needed].chunks_exact(row_bytes).rev() {
        for px in row.chunks_exact(channels * 4) {
            pixels.push(if channels == 3 {
                Rgb::new(read(&px[0..4]), read(&px[4..8]), read(&px[8..12]))
            } else {
                Rgb::splat(read(px))
            });
        }
    }
    Image::from_pixels(width, height, pixels).ok_or_else(|| "internal size mismatch".to_owned())
}

/// A cursor over the text header.
struct Header<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl<'a> Header<'a> {
    /// Skips whitespace and returns the next whitespace-delimited token.
    fn token(&mut self, what: &str) -> Result<&'a str, String> {
        while self.bytes.get(self.pos).is_some_and(u8::is_ascii_whitespace) {
            self.pos += 1;
        }
        let start = self.pos;
        while self.bytes.get(self.pos).is_some_and(|b| !b.is_ascii_whitespace()) {
            self.pos += 1;
            if self.pos - start > 64 {
                return Err(format!("header is garbled where {what} should be"));
            }
        }
        if start == self.pos {
            return Err(format!("truncated header: missing {what}"));
        }
        std::str::from_utf8(&self.bytes[start..self.pos])
            .map_err(|_| format!("header is not text where {what} should be"))
    }

    /// Parses the next token as a positive image dimension.
    fn dimension(&mut self, what: &str) -> Result<u32, String> {
        let token = self.token(what)?;
        match token.parse::<u32>() {
            Ok(0) => Err(format!("{what} is 0")),
            Ok(v) => Ok(v),
            Err(_) => Err(format!("{what} {:?} is not a positive integer", truncate(token))),
        }
    }

    /// Consumes exactly one whitespace byte: the separator before the pixel data.
    fn single_whitespace(&mut self) -> Result<(), String> {
        match self.bytes.get(self.pos) {
            Some(b) if b.is_ascii_whitespace() => {
                self.pos += 1;
                Ok(())
            }
            _ => Err("truncated header: no whitespace after the scale".to_owned()),
        }
    }
}

/// Shortens a token for an error message.
fn truncate(s: &str) -> String {
    s.chars().take(16).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn encoded(image: &Image) -> Vec<u8> {
        let mut out = Vec::new();
        encode(&mut out, image).unwrap();
        out
    }

    fn two_by_two() -> Image {
        Image::from_pixels(
            2,
            2,
            vec![Rgb::new(1.0, 2.0, 3.0), Rgb::new(4.0, 5.0, 6.0), Rgb::new(7.0, 8.0, 9.0), Rgb::new(10.0, 11.0, 12.0)],
        )
        .unwrap()
    }

    fn le_floats(values: &[f32]) -> Vec<u8> {
        values.iter().flat_map(|v| v.to_le_bytes()).collect()
    }

    #[test]
    fn layout_is_little_endian_bottom_row_first() {
        let bytes = encoded(&two_by_two());
        let header = b"PF\n2 2\n-1.0\n";
        assert_eq!(&bytes[..header.len()], header);
        let expected = le_floats(&[
            7.0, 8.0, 9.0, 10.0, 11.0, 12.0, // bottom row (y = 1)
            1.0, 2.0, 3.0, 4.0, 5.0, 6.0, // top row (y = 0)
        ]);
        assert_eq!(&bytes[header.len()..], &expected[..]);
    }

    #[test]
    fn round_trip_is_exact() {
        let mut img = two_by_two();
        img.pixels[1] = Rgb::new(f32::MIN_POSITIVE, -0.0, 1e30);
        assert_eq!(decode(&encoded(&img)).unwrap(), img);
    }

    #[test]
    fn big_endian_and_greyscale() {
        let mut bytes = b"Pf 2 1 1.0\n".to_vec();
        for v in [0.25f32, 8.0] {
            bytes.extend_from_slice(&v.to_be_bytes());
        }
        let img = decode(&bytes).unwrap();
        assert_eq!(img.pixels, vec![Rgb::splat(0.25), Rgb::splat(8.0)]);
    }

    #[test]
    fn greyscale_rows_are_flipped() {
        let mut bytes = b"Pf\n1 2\n-1\n".to_vec();
        bytes.extend(le_floats(&[1.0, 2.0]));
        let img = decode(&bytes).unwrap();
        assert_eq!(img.get(0, 0), Rgb::splat(2.0));
        assert_eq!(img.get(0, 1), Rgb::splat(1.0));
    }

    #[test]
    fn crlf_after_scale_is_tolerated() {
        let mut bytes = b"PF\r\n1 1\r\n-1.0\r\n".to_vec();
        bytes.extend(le_floats(&[10.0, 1.0, 0.5]));
        assert_eq!(decode(&bytes).unwrap().pixels, [Rgb::new(10.0, 1.0, 0.5)]);
    }

    #[test]
    fn truncated_data_is_an_error() {
        let bytes = encoded(&two_by_two());
        for cut in [bytes.len() - 1, bytes.len() - 12, 14, 11, 5, 3, 0] {
            let err = decode(&bytes[..cut]).unwrap_err();
            assert!(err.contains("truncated"), "cut {cut}: {err}");
        }
    }

    #[test]
    fn garbage_is_an_error() {
        let cases: &[&[u8]] = &[
            b"P6\n2 2\n255\n",
            b"PF\n-2 2\n-1.0\n",
            b"PF\n0 2\n-1.0\n",
            b"PF\nx 2\n-1.0\n",
            b"PF\n2 2\n0\n",
            b"PF\n2 2\nnan\n",
            b"PF\n2 2\nabc\n",
            b"PF\n99999999999 2\n-1.0\n",
            b"PF\n4294967295 4294967295\n-1.0\n",
            &[0xff, 0xfe, 0x00, 0x01, 0x80, 0x9f],
            &[b'A'; 200],
        ];
        for bytes in cases {
            assert!(decode(bytes).is_err(), "{:?}", String::from_utf8_lossy(bytes));
        }
    }
}
