//! A discrete distribution over `n` items proportional to non-negative weights (used to pick a
//! light by power, and a row or column of an environment map), sampled by inverting its
//! cumulative distribution through a guide table (expected O(1) steps; see guide.rs).

use super::guide::CdfGuide;

/// Piecewise-constant discrete distribution.
#[derive(Clone, Debug, Default)]
pub struct Distribution1D {
    /// Each item's cdf beside its pmf: a search ends by reading both, from one cache line.
    items: Vec<Item>,
    guide: CdfGuide,
}

#[derive(Clone, Copy, Debug, Default)]
struct Item {
    /// Probability of this item and the ones before it (1 for the last).
    cdf: f32,
    pmf: f32,
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
        if let Some(last) = cdf.last_mut() {
            *last = 1.0;
        }
        let items: Vec<Item> =
            cdf.iter().zip(weights).map(|(&cdf, &w)| Item { cdf, pmf: (w.max(0.0) as f64 / total) as f32 }).collect();
        let guide = CdfGuide::new(items.len(), |i| items[i].cdf);
        Some(Self { items, guide })
    }

    pub fn len(&self) -> usize {
        self.items.len()
    }

    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Probability of item `i`.
    pub fn pmf(&self, i: usize) -> f32 {
        self.items.get(i).map_or(0.0, |item| item.pmf)
    }

    /// Picks an item for `u ∈ [0,1)`; returns (index, probability). Items of zero weight are
    /// never returned.
    #[inline(always)]
    pub fn sample(&self, u: f32) -> (usize, f32) {
        // The first item whose cdf exceeds u.
        let i = self.guide.find(self.items.len(), |i| self.items[i].cdf, u);
        (i, self.items[i].pmf)
    }

    /// Like [`Distribution1D::sample`], also returning `u` rescaled to `[0,1)` within the picked
    /// item's cdf interval, so one random number can place a continuous sample inside the bin
    /// (pbrt-v4 §A.4.2 `PiecewiseConstant1D::Sample`).
    #[inline]
    pub fn sample_remapped(&self, u: f32) -> (usize, f32, f32) {
        let (i, p) = self.sample(u);
        let lo = if i == 0 { 0.0 } else { self.items[i - 1].cdf };
        let t = if p > 0.0 { ((u - lo) / p).clamp(0.0, ONE_BELOW) } else { 0.5 };
        (i, p, t)
    }
}

/// The largest f32 below 1, so a remapped sample never reaches the next bin.
const ONE_BELOW: f32 = 1.0 - f32::EPSILON / 2.0;

#[cfg(test)]
mod tests {
    use super::*;

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
}
