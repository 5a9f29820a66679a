//! A range of sample indices: the part of a render one machine takes when a render is split
//! across several (docs/distributed.md). A pixel's sample `i` depends only on (scene, settings,
//! seed, pixel, i), and the stratified sampler spreads its strata over the whole render's `spp`,
//! so rendering `[a, b)` here and `[b, c)` elsewhere, then merging the films, gives the bits of
//! rendering `[a, c)` at once.

use std::fmt;
use std::str::FromStr;

/// Sample indices `start .. end` of every pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SampleRange {
    pub start: u32,
    pub end: u32,
}

impl SampleRange {
    pub fn new(start: u32, end: u32) -> Self {
        Self { start, end }
    }

    /// Samples per pixel in the range.
    pub fn len(&self) -> u32 {
        self.end.saturating_sub(self.start)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Whether the two ranges share a sample index.
    pub fn overlaps(&self, other: &SampleRange) -> bool {
        self.start < other.end && other.start < self.end
    }

    /// Splits `[0, spp)` into `parts` ranges of nearly equal length (the first `spp % parts`
    /// one longer); fewer when `spp < parts`.
    pub fn split(spp: u32, parts: u32) -> Vec<SampleRange> {
        let parts = parts.clamp(1, spp.max(1));
        let (base, extra) = (spp / parts, spp % parts);
        let mut start = 0;
        (0..parts)
            .map(|i| {
                let end = start + base + u32::from(i < extra);
                let r = SampleRange::new(start, end);
                start = end;
                r
            })
            .collect()
    }

    /// The parts of `[0, spp)` none of `ranges` covers, in order.
    pub fn missing(spp: u32, ranges: &[SampleRange]) -> Vec<SampleRange> {
        let mut sorted: Vec<SampleRange> = ranges.iter().copied().filter(|r| !r.is_empty()).collect();
        sorted.sort();
        let mut out = Vec::new();
        let mut at = 0;
        for r in sorted {
            if r.start > at {
                out.push(SampleRange::new(at, r.start.min(spp)));
            }
            at = at.max(r.end);
        }
        if at < spp {
            out.push(SampleRange::new(at, spp));
        }
        out.retain(|r| !r.is_empty());
        out
    }
}

impl fmt::Display for SampleRange {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}..{}", self.start, self.end)
    }
}

impl FromStr for SampleRange {
    type Err = String;

    /// `A..B` (B > A), as Rust writes a half-open range.
    fn from_str(s: &str) -> Result<Self, String> {
        let bad = || format!("'{s}' is not a sample range: write A..B with whole numbers A < B, e.g. 0..64");
        let (a, b) = s.split_once("..").ok_or_else(bad)?;
        let (start, end) = (a.trim().parse::<u32>().map_err(|_| bad())?, b.trim().parse::<u32>().map_err(|_| bad())?);
        if end <= start {
            return Err(bad());
        }
        Ok(SampleRange::new(start, end))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_splits_and_finds_gaps() {
        assert_eq!("3..10".parse::<SampleRange>(), Ok(SampleRange::new(3, 10)));
        assert!("10..3".parse::<SampleRange>().is_err());
        assert!("5".parse::<SampleRange>().is_err());
        assert!("-1..3".parse::<SampleRange>().is_err());
        let parts = SampleRange::split(10, 3);
        assert_eq!(parts, vec![SampleRange::new(0, 4), SampleRange::new(4, 7), SampleRange::new(7, 10)]);
        assert_eq!(SampleRange::split(2, 5).len(), 2);
        assert!(SampleRange::new(0, 4).overlaps(&SampleRange::new(3, 5)));
        assert!(!SampleRange::new(0, 4).overlaps(&SampleRange::new(4, 5)));
        let have = [SampleRange::new(4, 7), SampleRange::new(0, 2)];
        assert_eq!(SampleRange::missing(10, &have), vec![SampleRange::new(2, 4), SampleRange::new(7, 10)]);
        assert_eq!(SampleRange::missing(10, &parts), vec![]);
    }
}
