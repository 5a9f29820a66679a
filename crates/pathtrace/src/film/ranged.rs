//! A film that knows which samples it holds: the render it belongs to (a key over scene and
//! settings), the engine build that made it, the whole render's spp and the exact set of sample
//! ranges. Merging checks all of that, so a render split over machines is put back together only
//! from parts of itself, each sample once. The feature buffers of a render that recorded them
//! travel and merge with it.

use super::features::FeatureBuffers;
use super::film::Film;
use crate::render::SampleRange;

/// A film with the sample ranges it holds (sorted, disjoint).
#[derive(Clone, Debug, PartialEq)]
pub struct RangedFilm {
    pub film: Film,
    /// [`super::render_key`] of the render.
    pub key: u64,
    /// [`super::engine_build`] of the engine that rendered it.
    pub build: String,
    /// The whole render's samples per pixel.
    pub spp: u32,
    pub ranges: Vec<SampleRange>,
    /// The feature buffers over the same samples, for a render that recorded them.
    pub features: Option<FeatureBuffers>,
}

/// Why two films cannot be merged.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum MergeError {
    #[error("it is {0}x{1} pixels but the others are {2}x{3}")]
    Size(u32, u32, u32, u32),
    #[error("it belongs to another scene or other settings (key {0:016x}, the others {1:016x})")]
    Key(u64, u64),
    #[error("it was rendered by another engine build ({0}; the others: {1})")]
    Build(String, String),
    #[error("it is part of a {0} spp render but the others of a {1} spp render")]
    Spp(u32, u32),
    #[error("its samples {0} overlap samples {1} already merged")]
    Overlap(SampleRange, SampleRange),
    /// `true`: the film has feature buffers and the others have none; `false`: the reverse.
    /// `true`: the film has splatted sums and the others have none; `false`: the reverse.
    #[error("{}: render every part with the same pixel filter", if *.0 { "it has splatted sums (a filter wider than the pixel) but the others have none" } else { "it has no splatted sums but the others have (a filter wider than the pixel)" })]
    Splat(bool),
    #[error("{}: render every part with the feature buffers (--aov or --denoise; aov=True in Python) or every part without", if *.0 { "it has feature buffers but the others have none" } else { "it has no feature buffers but the others have" })]
    Features(bool),
}

impl RangedFilm {
    /// A film holding samples `range` of a `spp` render.
    pub fn new(film: Film, key: u64, build: String, spp: u32, range: SampleRange) -> Self {
        Self { film, key, build, spp, ranges: vec![range], features: None }
    }

    /// The same film with the feature buffers of its samples (`None`: it has none).
    pub fn with_features(self, features: Option<FeatureBuffers>) -> Self {
        Self { features, ..self }
    }

    /// Whether `other` may be merged into this film; the error says what differs.
    pub fn check_mergeable(&self, other: &RangedFilm) -> Result<(), MergeError> {
        let (a, b) = (&self.film, &other.film);
        if (a.width(), a.height()) != (b.width(), b.height()) {
            return Err(MergeError::Size(b.width(), b.height(), a.width(), a.height()));
        }
        if self.key != other.key {
            return Err(MergeError::Key(other.key, self.key));
        }
        if self.build != other.build {
            return Err(MergeError::Build(other.build.clone(), self.build.clone()));
        }
        if self.spp != other.spp {
            return Err(MergeError::Spp(other.spp, self.spp));
        }
        if a.splat_pixels().is_some() != b.splat_pixels().is_some() {
            return Err(MergeError::Splat(b.splat_pixels().is_some()));
        }
        if self.features.is_some() != other.features.is_some() {
            return Err(MergeError::Features(other.features.is_some()));
        }
        for r in &other.ranges {
            if let Some(mine) = self.ranges.iter().find(|m| m.overlaps(r)) {
                return Err(MergeError::Overlap(*r, *mine));
            }
        }
        Ok(())
    }

    /// Adds `other`'s samples (exact integer sums: any order of merges gives the same bits).
    pub fn merge(&mut self, other: &RangedFilm) -> Result<(), MergeError> {
        self.check_mergeable(other)?;
        self.film.merge(&other.film);
        if let (Some(mine), Some(theirs)) = (&mut self.features, &other.features) {
            // Same size as the film, checked above.
            mine.merge(theirs);
        }
        self.ranges.extend_from_slice(&other.ranges);
        self.ranges = coalesce(std::mem::take(&mut self.ranges));
        Ok(())
    }

    /// The sample ranges of `0..spp` no part has rendered yet.
    pub fn missing(&self) -> Vec<SampleRange> {
        SampleRange::missing(self.spp, &self.ranges)
    }

    /// Whether every sample of the render is in.
    pub fn is_complete(&self) -> bool {
        self.missing().is_empty()
    }
}

/// Sorts disjoint ranges and joins the adjacent ones.
fn coalesce(mut ranges: Vec<SampleRange>) -> Vec<SampleRange> {
    ranges.sort();
    let mut out: Vec<SampleRange> = Vec::with_capacity(ranges.len());
    for r in ranges {
        match out.last_mut() {
            Some(last) if last.end == r.start => last.end = r.end,
            _ => out.push(r),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::FeatureSample;
    use crate::math::{Rgb, Vec3};

    fn part(range: SampleRange) -> RangedFilm {
        let mut film = Film::new(2, 1);
        for i in range.start..range.end {
            film.add_sample(0, 0, Rgb::splat(i as f32 * 0.37));
        }
        RangedFilm::new(film, 7, "b".into(), 10, range)
    }

    #[test]
    fn merging_tracks_ranges_and_refuses_overlap_and_mismatch() {
        let mut whole = part(SampleRange::new(0, 4));
        whole.merge(&part(SampleRange::new(7, 10))).unwrap();
        assert_eq!(whole.missing(), vec![SampleRange::new(4, 7)]);
        let err = whole.merge(&part(SampleRange::new(3, 5))).unwrap_err();
        assert_eq!(err, MergeError::Overlap(SampleRange::new(3, 5), SampleRange::new(0, 4)));
        whole.merge(&part(SampleRange::new(4, 7))).unwrap();
        assert_eq!(whole.ranges, vec![SampleRange::new(0, 10)]);
        assert!(whole.is_complete());
        assert_eq!(whole.film, part(SampleRange::new(0, 10)).film);
        let mut other = part(SampleRange::new(0, 1));
        other.key = 8;
        assert!(matches!(part(SampleRange::new(1, 2)).merge(&other), Err(MergeError::Key(8, 7))));
        other.key = 7;
        other.spp = 11;
        assert!(matches!(part(SampleRange::new(1, 2)).merge(&other), Err(MergeError::Spp(11, 10))));
    }

    fn part_with_features(range: SampleRange) -> RangedFilm {
        let mut features = FeatureBuffers::try_new(2, 1).unwrap();
        for i in range.start..range.end {
            let s = FeatureSample { albedo: Rgb::splat(i as f32 * 0.1), normal: Vec3::new(0.0, 1.0, 0.0), depth: 2.0 };
            features.add_sample(1, 0, &s, 1.0);
        }
        part(range).with_features(Some(features))
    }

    #[test]
    fn feature_buffers_merge_with_the_film_and_a_mix_with_and_without_is_refused() {
        let mut merged = part_with_features(SampleRange::new(4, 10));
        merged.merge(&part_with_features(SampleRange::new(0, 4))).unwrap();
        assert_eq!(merged, part_with_features(SampleRange::new(0, 10)));
        let plain = part(SampleRange::new(0, 4));
        let err = part_with_features(SampleRange::new(4, 10)).merge(&plain).unwrap_err();
        assert_eq!(err, MergeError::Features(false));
        assert!(err.to_string().contains("it has no feature buffers but the others have"), "{err}");
        let err = part(SampleRange::new(4, 10)).merge(&part_with_features(SampleRange::new(0, 4))).unwrap_err();
        assert!(err.to_string().starts_with("it has feature buffers but the others have none"), "{err}");
    }
}
