//! A discrete distribution over `n` items proportional to non-negative weights (used to pick a
//! light by power, and a row or column of an environment map), sampled by inverting its
//! cumulative distribution through a guide table (expected O(1) steps; see guide.rs).

use super::guide::{CdfGuide, SCAN_ITEMS};
use crate::wide::simd::{F32s, Ms};

/// Piecewise-constant discrete distribution.
#[derive(Clone, Debug, Default)]
pub struct Distribution1D {
    /// Probability of each item and the ones before it (1 for the last). An item's own
    /// probability is the step from its predecessor: no pmf is stored beside it, which halves
    /// an environment map's rows (512 × 256 cells: 1.2 MB with the pmf, more than this
    /// machine's 1 MB L2 cache per core, where its sampling was 12% of the bunny's profile).
    cdf: Vec<f32>,
    guide: CdfGuide,
}

impl Distribution1D {
    /// `None` if there are no items or the weights do not sum to a positive finite value.
    pub fn new(weights: &[f32]) -> Option<Self> {
        let total: f64 = weights.iter().map(|&w| w.max(0.0) as f64).sum();
        if weights.is_empty() || !(total > 0.0 && total.is_finite()) {
            return None;
        }
        let mut cdf = Vec::with_capacity(weights.len());
        let mut acc = 0.0f64;
        for &w in weights {
            acc += w.max(0.0) as f64;
            cdf.push((acc / total) as f32);
        }
        // From the last item of positive weight on, the cdf is 1: rounding leaves no sliver of
        // the unit interval to the items of zero weight after it.
        let last = weights.iter().rposition(|&w| w > 0.0).unwrap_or(weights.len() - 1);
        cdf[last..].fill(1.0);
        let guide = CdfGuide::new(cdf.len(), |i| cdf[i]);
        Some(Self { cdf, guide })
    }

    pub fn len(&self) -> usize {
        self.cdf.len()
    }

    pub fn is_empty(&self) -> bool {
        self.cdf.is_empty()
    }

    /// Probability of item `i`: the width of its cdf interval, which is the probability with
    /// which [`Distribution1D::sample`] picks it (the difference is exact where the two cdf values
    /// are within a factor of two, by Sterbenz's lemma, and within half an ulp otherwise). An item
    /// too light to move the f32 cdf has pmf 0 and is never picked, so the sampler and the pdf
    /// that MIS weighs it by agree.
    #[inline(always)]
    pub fn pmf(&self, i: usize) -> f32 {
        match i {
            0 => self.cdf.first().copied().unwrap_or(0.0),
            _ if i < self.cdf.len() => self.cdf[i] - self.cdf[i - 1],
            _ => 0.0,
        }
    }

    /// Asks the caches for what [`Distribution1D::pmf`] of item `i` reads (see
    /// [`crate::wide::prefetch`]).
    #[inline(always)]
    pub fn prefetch(&self, i: usize) {
        if i < self.cdf.len() {
            crate::wide::prefetch::prefetch(&self.cdf[i.saturating_sub(1)..=i]);
        }
    }

    /// Picks an item for `u ∈ [0,1)`; returns (index, probability). Items of zero weight are
    /// never returned.
    #[inline(always)]
    pub fn sample(&self, u: f32) -> (usize, f32) {
        // The first item whose cdf exceeds u.
        let i = self.guide.find(self.cdf.len(), |i| self.cdf[i], u);
        (i, self.pmf(i))
    }

    /// [`Distribution1D::sample`] for each lane of `active` (the other lanes' items are
    /// meaningless): the items as indices, and their probabilities.
    ///
    /// A few items (a scene's lights, searched by a plain scan): in SIMD, counting per lane the
    /// items before the last whose cdf is at most `u`. The cdf does not decrease, so those are
    /// exactly the items the scan steps over, and the count is its answer; the probability is
    /// then [`Distribution1D::pmf`] of the counted item, selected. Picked lane by lane, a
    /// teapot lit by two point lights spent 4.5% of its render in the per-lane search.
    #[inline(always)]
    pub fn sample_lanes<const N: usize>(&self, u: &F32s<N>, active: Ms<N>) -> ([u32; N], F32s<N>) {
        let n = self.cdf.len();
        if n <= SCAN_ITEMS {
            let mut count = F32s::<N>::ZERO;
            for &c in &self.cdf[..n.saturating_sub(1)] {
                count = count + F32s::select(F32s::splat(c).le(*u), F32s::ONE, F32s::ZERO);
            }
            let mut pmf = F32s::splat(self.pmf(0));
            for i in 1..n {
                pmf = F32s::select(count.eq(F32s::splat(i as f32)), F32s::splat(self.pmf(i)), pmf);
            }
            return (count.0.map(|c| c as u32), pmf);
        }
        let mut items = [0; N];
        let mut pmf = F32s::ZERO;
        for i in active.lanes() {
            let (item, p) = self.sample(u.0[i]);
            (items[i], pmf.0[i]) = (item as u32, p);
        }
        (items, pmf)
    }

    /// Like [`Distribution1D::sample`], also returning `u` rescaled to `[0,1)` within the picked
    /// item's cdf interval, so one random number can place a continuous sample inside the bin
    /// (pbrt-v4 §A.4.2 `PiecewiseConstant1D::Sample`).
    #[inline]
    pub fn sample_remapped(&self, u: f32) -> (usize, f32, f32) {
        let (i, _) = self.sample(u);
        let (p, t) = self.remap(i, u);
        (i, p, t)
    }

    /// The probability of item `i`, picked for `u`, and `u` rescaled to `[0,1)` within its cdf
    /// interval.
    #[inline(always)]
    pub(super) fn remap(&self, i: usize, u: f32) -> (f32, f32) {
        let p = self.pmf(i);
        let lo = if i == 0 { 0.0 } else { self.cdf[i - 1] };
        let t = if p > 0.0 { ((u - lo) / p).clamp(0.0, ONE_BELOW) } else { 0.5 };
        (p, t)
    }

    /// The cdf and its guide table, for searches made several at a time
    /// ([`super::guide::find_interleaved`]).
    #[inline(always)]
    pub(super) fn search_table(&self) -> (&CdfGuide, &[f32]) {
        (&self.guide, &self.cdf)
    }
}

/// The largest f32 below 1, so a remapped sample never reaches the next bin.
const ONE_BELOW: f32 = 1.0 - f32::EPSILON / 2.0;

#[cfg(test)]
mod tests {
    use super::*;

    /// The lanes' picks are `sample`'s, bit for bit, for few items (the SIMD count) and many
    /// (the search lane by lane), at the cdf's own values, just beside them, and at 0 and
    /// just below 1; zero-weight items are skipped the same way.
    #[test]
    fn lanes_pick_what_sample_picks() {
        const N: usize = 8;
        for n in 1..=12usize {
            let weights: Vec<f32> = (0..n).map(|i| if i % 3 == 1 { 0.0 } else { 1.0 + (i * 7 % 5) as f32 }).collect();
            let Some(d) = Distribution1D::new(&weights) else { continue };
            let mut us = vec![0.0, ONE_BELOW, 0.5];
            for &c in &d.cdf {
                us.extend([c, f32::from_bits(c.to_bits() - 1), f32::from_bits(c.to_bits() + 1)]);
            }
            us.extend((0..64).map(|k| k as f32 / 64.0));
            for chunk in us.chunks(N) {
                let u = F32s::<N>::from_fn(|i| chunk.get(i).copied().unwrap_or(0.25).min(ONE_BELOW));
                let (items, pmf) = d.sample_lanes(&u, Ms::ALL);
                for ((&lane_item, &lane_pmf), &u) in items.iter().zip(&pmf.0).zip(&u.0) {
                    let (item, p) = d.sample(u);
                    assert_eq!((lane_item as usize, lane_pmf.to_bits()), (item, p.to_bits()), "{n} items, u = {u}");
                }
            }
        }
    }

    #[test]
    fn sampling_follows_the_weights() {
        let d = Distribution1D::new(&[1.0, 0.0, 3.0]).unwrap();
        let n = 100_000;
        let mut counts = [0usize; 3];
        for k in 0..n {
            let (i, p) = d.sample((k as f32 + 0.5) / n as f32);
            assert!(p > 0.0);
            counts[i] += 1;
        }
        assert_eq!(counts[1], 0);
        assert!((counts[0] as f32 / n as f32 - 0.25).abs() < 1e-3);
        assert!((d.pmf(2) - 0.75).abs() < 1e-6);
        assert!(Distribution1D::new(&[0.0]).is_none());
        assert!(Distribution1D::new(&[]).is_none());
    }

    /// The pmf is the probability with which `sample` picks an item: an item too light to move
    /// the f32 cdf and the zero-weight items after the last heavy one are never picked and have
    /// pmf 0, and the pmfs of the items picked sum to 1.
    #[test]
    fn the_pmf_is_the_probability_of_being_picked() {
        let d = Distribution1D::new(&[1.0, 1e-12, 0.0, 0.0]).unwrap();
        assert_eq!((d.pmf(0), d.pmf(1), d.pmf(2), d.pmf(3)), (1.0, 0.0, 0.0, 0.0));
        for k in 0..1000 {
            assert_eq!(d.sample(k as f32 / 1000.0), (0, 1.0));
        }
        let weights: Vec<f32> = (0..1000).map(|i| ((i * 7919) % 113) as f32 * 1e-3).collect();
        let d = Distribution1D::new(&weights).unwrap();
        let total: f64 = (0..d.len()).map(|i| f64::from(d.pmf(i))).sum();
        assert!((total - 1.0).abs() < 1e-6, "pmfs sum to {total}");
        for (i, &w) in weights.iter().enumerate() {
            assert_eq!(w == 0.0, d.pmf(i) == 0.0, "item {i}");
        }
    }
}
