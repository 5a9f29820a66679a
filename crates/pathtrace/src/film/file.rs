//! The film file (`.ptfilm`): a [`RangedFilm`] as bytes, so parts of a render made on different
//! machines can be sent, stored and merged. Little-endian throughout:
//!
//! ```text
//! magic    8 bytes  "PTFILM\n\0"
//! version  u32      FORMAT_VERSION
//! width, height, spp        u32 ×3
//! key      u64      render_key (scene and settings)
//! build    u32 length + UTF-8 engine build
//! ranges   u32 count + (start u32, end u32) × count
//! dropped  u64      NaN/Inf samples dropped
//! features u32      1 if the film carries feature buffers, else 0
//! splat    u32      1 if the film carries splatted sums (a filter wider than the pixel), else 0
//! pixels   width × height × (count u32, sum i128 ×3, sum_sq u128 ×3), row by row
//! splat pixels (only with splat = 1)
//!          width × height × (weight i128, sum i128 ×3), row by row
//! feature pixels (only with features = 1)
//!          width × height × (count u32, albedo i128 ×3, normal i128 ×3, depth i128), row by row
//! check    u64      FNV-1a 64 of every byte before it
//! ```
//!
//! 100 bytes per pixel: 6.6 MB for 256², 830 MB for 3840×2160; 64 more with splatted sums, 116
//! more with feature buffers. Version 2 was the same without the `splat` field and the splat
//! pixels, version 1 also without the `features` field and the feature pixels: both are still
//! read (as films without splatted sums; a film of either cannot merge with a version 3 film, as
//! the engine builds differ).

use super::accumulator::PixelStats;
use super::allocation::try_pixels;
use super::features::{FeatureBuffers, FeaturePixel};
use super::film::Film;
use super::fingerprint::Fnv64;
use super::ranged::RangedFilm;
use super::splat::SplatPixel;
use crate::render::SampleRange;

const MAGIC: &[u8; 8] = b"PTFILM\n\0";

/// The version of the layout above, which this build writes; it reads this one and version 1.
pub const FORMAT_VERSION: u32 = 3;

/// The version before feature buffers, still read.
const VERSION_WITHOUT_FEATURES: u32 = 1;

/// The version before splatted sums, still read.
const VERSION_WITHOUT_SPLAT: u32 = 2;

/// Bytes per pixel in the file.
pub const FILE_BYTES_PER_PIXEL: usize = 4 + 3 * 16 + 3 * 16;

/// Bytes per pixel of the feature buffers in the file.
pub const FILE_FEATURE_BYTES_PER_PIXEL: usize = 4 + 7 * 16;

/// Bytes per pixel of the splatted sums in the file.
pub const FILE_SPLAT_BYTES_PER_PIXEL: usize = 4 * 16;

/// Why bytes are not a film.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum FilmFileError {
    #[error("not a pathtrace film file (it does not start with the PTFILM signature)")]
    NotAFilm,
    #[error("film format version {0}, but this build reads versions {VERSION_WITHOUT_FEATURES} to {FORMAT_VERSION}: merge it with the pathtrace that wrote it")]
    Version(u32),
    #[error("the film file is truncated (it ends inside the {0}); copy it again")]
    Truncated(&'static str),
    #[error("the film file is corrupt (its checksum does not match); copy or render it again")]
    Checksum,
    #[error("the film file is invalid: {0}")]
    Invalid(String),
}

impl RangedFilm {
    /// The film file's bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        let pixels = self.film.pixels();
        let splat = self.film.splat_pixels();
        let per_pixel = FILE_BYTES_PER_PIXEL
            + if self.features.is_some() { FILE_FEATURE_BYTES_PER_PIXEL } else { 0 }
            + if splat.is_some() { FILE_SPLAT_BYTES_PER_PIXEL } else { 0 };
        let mut out = Vec::with_capacity(64 + self.build.len() + 8 * self.ranges.len() + pixels.len() * per_pixel);
        out.extend_from_slice(MAGIC);
        for v in [FORMAT_VERSION, self.film.width(), self.film.height(), self.spp] {
            out.extend_from_slice(&v.to_le_bytes());
        }
        out.extend_from_slice(&self.key.to_le_bytes());
        out.extend_from_slice(&(self.build.len() as u32).to_le_bytes());
        out.extend_from_slice(self.build.as_bytes());
        out.extend_from_slice(&(self.ranges.len() as u32).to_le_bytes());
        for r in &self.ranges {
            out.extend_from_slice(&r.start.to_le_bytes());
            out.extend_from_slice(&r.end.to_le_bytes());
        }
        out.extend_from_slice(&self.film.dropped_samples.to_le_bytes());
        out.extend_from_slice(&u32::from(self.features.is_some()).to_le_bytes());
        out.extend_from_slice(&u32::from(splat.is_some()).to_le_bytes());
        for p in pixels {
            out.extend_from_slice(&p.count.to_le_bytes());
            p.sum.iter().for_each(|s| out.extend_from_slice(&s.to_le_bytes()));
            p.sum_sq.iter().for_each(|s| out.extend_from_slice(&s.to_le_bytes()));
        }
        for p in splat.into_iter().flatten() {
            for s in [&p.weight].into_iter().chain(&p.sum) {
                out.extend_from_slice(&s.to_le_bytes());
            }
        }
        for p in self.features.iter().flat_map(|f| f.pixels()) {
            out.extend_from_slice(&p.count.to_le_bytes());
            for s in p.albedo.iter().chain(&p.normal).chain([&p.depth]) {
                out.extend_from_slice(&s.to_le_bytes());
            }
        }
        let check = Fnv64::default().write(&out).finish();
        out.extend_from_slice(&check.to_le_bytes());
        out
    }

    /// Reads a film file's bytes; the error says what is wrong.
    pub fn from_bytes(bytes: &[u8]) -> Result<RangedFilm, FilmFileError> {
        if bytes.len() < MAGIC.len() || &bytes[..MAGIC.len()] != MAGIC {
            return Err(FilmFileError::NotAFilm);
        }
        let mut r = Reader { bytes, at: MAGIC.len() };
        let version = r.u32("header")?;
        if !(VERSION_WITHOUT_FEATURES..=FORMAT_VERSION).contains(&version) {
            return Err(FilmFileError::Version(version));
        }
        if bytes.len() < MAGIC.len() + 8 {
            return Err(FilmFileError::Truncated("header"));
        }
        let (body, check) = bytes.split_at(bytes.len() - 8);
        if Fnv64::default().write(body).finish().to_le_bytes() != check {
            // A short file fails here too; say which it is.
            return Err(FilmFileError::Checksum);
        }
        let mut r = Reader { bytes: body, at: r.at };
        let (width, height, spp) = (r.u32("header")?, r.u32("header")?, r.u32("header")?);
        let key = r.u64("header")?;
        let build_len = r.u32("header")? as usize;
        let build = String::from_utf8(r.take(build_len, "engine build")?.to_vec())
            .map_err(|_| FilmFileError::Invalid("the engine build is not UTF-8".into()))?;
        let n_ranges = r.u32("range list")? as usize;
        let mut ranges = Vec::with_capacity(n_ranges.min(1 << 16));
        for _ in 0..n_ranges {
            let range = SampleRange::new(r.u32("range list")?, r.u32("range list")?);
            if range.is_empty() || range.end > spp {
                return Err(FilmFileError::Invalid(format!("sample range {range} is not within 0..{spp}")));
            }
            if let Some(prev) = ranges.iter().find(|p: &&SampleRange| p.overlaps(&range)) {
                return Err(FilmFileError::Invalid(format!("sample ranges {prev} and {range} overlap")));
            }
            ranges.push(range);
        }
        let dropped = r.u64("header")?;
        let mut flag = |since: u32, what: &str| -> Result<bool, FilmFileError> {
            if version < since {
                return Ok(false);
            }
            match r.u32("header")? {
                0 => Ok(false),
                1 => Ok(true),
                other => Err(FilmFileError::Invalid(format!("{what} flag {other} (expected 0 or 1)"))),
            }
        };
        let has_features = flag(VERSION_WITHOUT_FEATURES + 1, "feature")?;
        let has_splat = flag(VERSION_WITHOUT_SPLAT + 1, "splat")?;
        let len = u64::from(width) * u64::from(height);
        let per_pixel = FILE_BYTES_PER_PIXEL
            + if has_features { FILE_FEATURE_BYTES_PER_PIXEL } else { 0 }
            + if has_splat { FILE_SPLAT_BYTES_PER_PIXEL } else { 0 };
        if (body.len() - r.at) as u64 != len * per_pixel as u64 {
            let with = match (has_features, has_splat) {
                (false, false) => "",
                (true, false) => " with feature buffers",
                (false, true) => " with splatted sums",
                (true, true) => " with splatted sums and feature buffers",
            };
            return Err(FilmFileError::Invalid(format!(
                "{} bytes of pixels for a {width}x{height} film{with}, which needs {}",
                body.len() - r.at,
                len * per_pixel as u64
            )));
        }
        let mut pixels: Vec<PixelStats> = try_pixels(len)
            .ok_or_else(|| FilmFileError::Invalid(format!("a {width}x{height} film does not fit in memory")))?;
        for p in &mut pixels {
            *p = PixelStats {
                count: r.u32("pixels")?,
                sum: [r.i128("pixels")?, r.i128("pixels")?, r.i128("pixels")?],
                sum_sq: [r.u128("pixels")?, r.u128("pixels")?, r.u128("pixels")?],
            };
        }
        let splat = match has_splat {
            false => None,
            true => {
                let mut pixels: Vec<SplatPixel> = try_pixels(len).ok_or_else(|| {
                    FilmFileError::Invalid(format!("{width}x{height} splatted sums do not fit in memory"))
                })?;
                for p in &mut pixels {
                    p.weight = r.i128("splat pixels")?;
                    for s in &mut p.sum {
                        *s = r.i128("splat pixels")?;
                    }
                }
                Some(pixels)
            }
        };
        let mut film = Film::from_pixels(width, height, pixels, splat);
        film.dropped_samples = dropped;
        let features = match has_features {
            false => None,
            true => {
                let mut pixels: Vec<FeaturePixel> = try_pixels(len).ok_or_else(|| {
                    FilmFileError::Invalid(format!("{width}x{height} feature buffers do not fit in memory"))
                })?;
                for p in &mut pixels {
                    p.count = r.u32("feature pixels")?;
                    for s in p.albedo.iter_mut().chain(&mut p.normal).chain([&mut p.depth]) {
                        *s = r.i128("feature pixels")?;
                    }
                }
                Some(FeatureBuffers::from_pixels(width, height, pixels))
            }
        };
        ranges.sort();
        Ok(RangedFilm { film, key, build, spp, ranges, features })
    }
}

struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize, part: &'static str) -> Result<&'a [u8], FilmFileError> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.bytes.len()).ok_or(FilmFileError::Truncated(part))?;
        let s = &self.bytes[self.at..end];
        self.at = end;
        Ok(s)
    }

    fn array<const K: usize>(&mut self, part: &'static str) -> Result<[u8; K], FilmFileError> {
        let mut a = [0u8; K];
        a.copy_from_slice(self.take(K, part)?);
        Ok(a)
    }

    fn u32(&mut self, part: &'static str) -> Result<u32, FilmFileError> {
        self.array(part).map(u32::from_le_bytes)
    }

    fn u64(&mut self, part: &'static str) -> Result<u64, FilmFileError> {
        self.array(part).map(u64::from_le_bytes)
    }

    fn i128(&mut self, part: &'static str) -> Result<i128, FilmFileError> {
        self.array(part).map(i128::from_le_bytes)
    }

    fn u128(&mut self, part: &'static str) -> Result<u128, FilmFileError> {
        self.array(part).map(u128::from_le_bytes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::FeatureSample;
    use crate::math::{Rgb, Vec3};

    fn sample_film() -> RangedFilm {
        let mut film = Film::new(3, 2);
        film.add_sample(1, 1, Rgb::new(0.5, 1e6, -2.0));
        film.add_sample(2, 0, Rgb::splat(1e-7));
        film.add_sample(2, 0, Rgb::splat(f32::NAN));
        RangedFilm::new(film, 0xdead_beef, "pathtrace test".into(), 16, SampleRange::new(3, 9))
    }

    #[test]
    fn round_trips_and_refuses_damaged_bytes() {
        let f = sample_film();
        let bytes = f.to_bytes();
        assert_eq!(bytes.len(), 8 + 16 + 8 + 4 + 14 + 4 + 8 + 8 + 4 + 4 + 6 * FILE_BYTES_PER_PIXEL + 8);
        assert_eq!(RangedFilm::from_bytes(&bytes), Ok(f));
        assert_eq!(RangedFilm::from_bytes(b"P3\n1 1"), Err(FilmFileError::NotAFilm));
        assert_eq!(RangedFilm::from_bytes(&bytes[..bytes.len() - 1]), Err(FilmFileError::Checksum));
        assert_eq!(RangedFilm::from_bytes(&bytes[..10]), Err(FilmFileError::Truncated("header")));
        let mut flipped = bytes.clone();
        flipped[100] ^= 1;
        assert_eq!(RangedFilm::from_bytes(&flipped), Err(FilmFileError::Checksum));
        let mut future = bytes;
        future[8] = 4;
        assert_eq!(RangedFilm::from_bytes(&future), Err(FilmFileError::Version(4)));
    }

    fn with_features(f: RangedFilm) -> RangedFilm {
        let mut features = FeatureBuffers::try_new(3, 2).unwrap();
        let s = FeatureSample { albedo: Rgb::new(0.2, 0.5, 1.0), normal: Vec3::new(0.0, -0.6, 0.8), depth: 3.5 };
        features.add_sample(1, 1, &s, 0.75);
        features.add_sample(2, 0, &FeatureSample { depth: 1e9, ..s }, -0.1);
        f.with_features(Some(features))
    }

    #[test]
    fn feature_buffers_round_trip_and_are_checked() {
        let f = with_features(sample_film());
        let bytes = f.to_bytes();
        assert_eq!(bytes.len(), sample_film().to_bytes().len() + 6 * FILE_FEATURE_BYTES_PER_PIXEL);
        let back = RangedFilm::from_bytes(&bytes).unwrap();
        assert_eq!(back, f);
        assert_eq!(back.features.unwrap().pixels()[5].depth, f.features.as_ref().unwrap().pixels()[5].depth);
        // A flag that says "features" over a body without them is refused (with a fixed checksum,
        // so the size check is what answers).
        let plain = sample_film().to_bytes();
        let mut lying = plain[..plain.len() - 8].to_vec();
        let flag_at = lying.len() - 6 * FILE_BYTES_PER_PIXEL - 8;
        lying[flag_at] = 1;
        let check = Fnv64::default().write(&lying).finish();
        lying.extend_from_slice(&check.to_le_bytes());
        let err = RangedFilm::from_bytes(&lying).unwrap_err();
        assert!(err.to_string().contains("with feature buffers"), "{err}");
    }

    /// The bytes of `sample_film()` as version `version` wrote them: version 2 is version 3
    /// without the splat flag, version 1 also without the feature flag.
    fn older(version: u32) -> Vec<u8> {
        let v3 = sample_film().to_bytes();
        let flags_at = v3.len() - 8 - 6 * FILE_BYTES_PER_PIXEL - 8;
        let kept_flags = if version == 2 { 4 } else { 0 };
        let mut old = [&v3[..flags_at + kept_flags], &v3[flags_at + 8..v3.len() - 8]].concat();
        old[8..12].copy_from_slice(&version.to_le_bytes());
        let check = Fnv64::default().write(&old).finish();
        old.extend_from_slice(&check.to_le_bytes());
        old
    }

    #[test]
    fn versions_1_and_2_are_read_as_films_without_features_or_splats() {
        assert_eq!(RangedFilm::from_bytes(&older(1)), Ok(sample_film()));
        assert_eq!(RangedFilm::from_bytes(&older(2)), Ok(sample_film()));
    }

    fn splatting_film() -> RangedFilm {
        let filter = crate::film::PixelFilter::by_name("gaussian").unwrap();
        let mut film = Film::try_new(3, 2, true).unwrap();
        let mut block = crate::film::SplatBlock::for_tile(&filter, (0, 0, 3, 2), 3, 2);
        block.splat(&filter, 1, 1, crate::math::Vec2::new(0.3, 0.9), Rgb::new(0.5, 1e6, -2.0));
        block.splat(&filter, 2, 0, crate::math::Vec2::new(0.0, 0.5), Rgb::splat(1e-7));
        film.merge_splat_block(&block);
        film.add_sample(1, 1, Rgb::new(0.5, 1e6, -2.0));
        film.add_sample(2, 0, Rgb::splat(1e-7));
        RangedFilm::new(film, 1, "pathtrace test".into(), 4, SampleRange::new(0, 2))
    }

    #[test]
    fn splatted_sums_round_trip_with_and_without_features() {
        let f = splatting_film();
        assert!(f.film.splat_pixels().unwrap().iter().all(|p| p.weight > 0));
        let bytes = f.to_bytes();
        let plain = RangedFilm { film: Film::new(3, 2), ..f.clone() }.to_bytes();
        assert_eq!(bytes.len(), plain.len() + 6 * FILE_SPLAT_BYTES_PER_PIXEL);
        assert_eq!(RangedFilm::from_bytes(&bytes), Ok(f.clone()));
        let both = with_features(splatting_film());
        assert_eq!(RangedFilm::from_bytes(&both.to_bytes()), Ok(both));
        // The splat flag over a body without splat pixels is refused by the size check.
        let mut lying = plain[..plain.len() - 8].to_vec();
        let flag_at = lying.len() - 6 * FILE_BYTES_PER_PIXEL - 4;
        lying[flag_at] = 1;
        let check = Fnv64::default().write(&lying).finish();
        lying.extend_from_slice(&check.to_le_bytes());
        let err = RangedFilm::from_bytes(&lying).unwrap_err();
        assert!(err.to_string().contains("with splatted sums"), "{err}");
    }
}
