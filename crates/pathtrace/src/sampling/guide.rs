//! A guide table over a cumulative distribution: inverting the cdf in expected O(1) steps,
//! with exactly the answer of a binary search.
//!
//! The cutpoint method (Chen & Asau 1974; Devroye, "Non-Uniform Random Variate Generation",
//! 1986, §III.2.4): the unit interval is cut into `m` equal buckets and bucket k records the
//! first item whose cdf exceeds k/m. A number u in bucket k = ⌊u·m⌋ then lies between the items
//! its bucket and the next one record, and the search only looks there. Summed over the
//! buckets, the items between consecutive records number at most n + m, so with m buckets a search looks
//! at no more than 1 + n/m items on average, whatever the distribution.
//!
//! Unlike an alias table, the map from u to the item stays monotone, so stratified and
//! low-discrepancy numbers keep their structure; and the search ends on the very item a binary
//! search would (`cdf.partition_point(|c| c <= u)`), so replacing one by the other changes no
//! sample. Rounding in k/m against ⌊u·m⌋ can put u one bucket off; the final check steps to the
//! neighbouring item in that case.

/// Items per bucket, on average: the table stays a quarter of the cdf's size (an environment
/// map's rows keep it in the L2 cache), and a search looks at about five items (one or two
/// cache lines of the cdf) in a binary search over its bucket's span.
const ITEMS_PER_BUCKET: usize = 4;

/// Up to this many items a plain scan is as quick as the table (a scene's few lights, where
/// a single light needs no search at all), and no table is kept.
pub(super) const SCAN_ITEMS: usize = 8;

/// A cdf's number type: `f32` (distributions over images and lights) or `f64` (the pixel
/// filter's table).
pub(crate) trait CdfValue: Copy + PartialOrd {
    /// The left edge k/m of bucket k.
    fn edge(k: usize, m: usize) -> Self;
    /// ⌊u·m⌋, saturating (u < 0 goes to bucket 0), at most m − 1.
    fn bucket(self, m: usize) -> usize;
}

impl CdfValue for f32 {
    #[inline(always)]
    fn edge(k: usize, m: usize) -> Self {
        k as f32 / m as f32
    }

    #[inline(always)]
    fn bucket(self, m: usize) -> usize {
        ((self * m as f32) as usize).min(m - 1)
    }
}

impl CdfValue for f64 {
    #[inline(always)]
    fn edge(k: usize, m: usize) -> Self {
        k as f64 / m as f64
    }

    #[inline(always)]
    fn bucket(self, m: usize) -> usize {
        ((self * m as f64) as usize).min(m - 1)
    }
}

/// First-item records of equal buckets over a cdf of `n` items.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct CdfGuide {
    /// `m + 1` entries for `m` buckets: bucket k's search starts at `first[k]` and ends by
    /// `first[k + 1]`.
    first: Vec<u32>,
}

impl CdfGuide {
    /// The guide of the cdf `cdf(0..n)` (non-decreasing; 1 ≤ n < 2³²).
    pub(crate) fn new<T: CdfValue>(n: usize, cdf: impl Fn(usize) -> T) -> Self {
        if n <= SCAN_ITEMS {
            return Self { first: Vec::new() };
        }
        let m = n.div_ceil(ITEMS_PER_BUCKET);
        // Edges and the cdf both increase: one walk along the items finds every record.
        let mut i = 0;
        let first = (0..=m)
            .map(|k| {
                let edge = T::edge(k, m);
                while i < n && cdf(i) <= edge {
                    i += 1;
                }
                i.min(n - 1) as u32
            })
            .collect();
        Self { first }
    }

    /// The first item whose cdf exceeds `u` (the last item if none does): the index
    /// `partition_point(|c| c <= u).min(n - 1)` over the `n` values of the `cdf` this guide was
    /// made from.
    /// Always inlined: picking one of a scene's few lights happens per lane inside the SIMD
    /// loop, where the out-of-line call was 1% of the Cornell box's profile.
    #[inline(always)]
    pub(crate) fn find<T: CdfValue>(&self, n: usize, cdf: impl Fn(usize) -> T, u: T) -> usize {
        if n <= SCAN_ITEMS {
            let mut i = 0;
            while i + 1 < n && cdf(i) <= u {
                i += 1;
            }
            return i;
        }
        self.find_guided(n, cdf, u)
    }

    /// [`CdfGuide::find`] through the table.
    #[inline(never)]
    fn find_guided<T: CdfValue>(&self, n: usize, cdf: impl Fn(usize) -> T, u: T) -> usize {
        let mut span = self.span(u);
        while span.size > 1 {
            span.halve(|i| cdf(i) <= u);
        }
        settle(n, cdf, u, span.base)
    }

    /// The range of items bucket ⌊u·m⌋ records, where the answer lies (up to rounding).
    #[inline(always)]
    fn span<T: CdfValue>(&self, u: T) -> Span {
        let m = self.first.len() - 1;
        let k = u.bucket(m);
        let (lo, hi) = (self.first[k] as usize, self.first[k + 1] as usize + 1);
        Span { base: lo, size: hi - lo }
    }
}

/// Several searches of [`CdfGuide::find`] at once, each over its own cdf slice, with the
/// results `find` gives one by one. Each search waits on a cache miss or two (an environment
/// map's row is far from the last one sampled); made in lockstep, a step of every search is
/// issued before the next step of any, so the misses of all of them overlap rather than queue
/// (one search after another kept about one miss in flight: two thirds of `find_guided`'s
/// time on the bunny went to two loads).
#[inline(always)]
pub(crate) fn find_interleaved<T: CdfValue, const N: usize>(searches: &[(&CdfGuide, &[T], T); N]) -> [usize; N] {
    let mut spans = [Span { base: 0, size: 0 }; N];
    let mut found = [0usize; N];
    for (k, &(guide, cdf, u)) in searches.iter().enumerate() {
        if cdf.len() <= SCAN_ITEMS {
            found[k] = guide.find(cdf.len(), |i| cdf[i], u);
        } else {
            spans[k] = guide.span(u);
        }
    }
    loop {
        let mut searching = false;
        for (span, &(_, cdf, u)) in spans.iter_mut().zip(searches) {
            if span.size > 1 {
                span.halve(|i| cdf[i] <= u);
                searching = true;
            }
        }
        if !searching {
            break;
        }
    }
    for (k, &(_, cdf, u)) in searches.iter().enumerate() {
        if cdf.len() > SCAN_ITEMS {
            found[k] = settle(cdf.len(), |i| cdf[i], u, spans[k].base);
        }
    }
    found
}

/// The answer's range `[base, base + size]` of a guided search.
#[derive(Clone, Copy)]
struct Span {
    base: usize,
    size: usize,
}

impl Span {
    /// One step of a binary search for the first item whose cdf exceeds u (`at_or_below(i)`
    /// is cdf(i) ≤ u): it narrows the range by a select instead of a branch. Which half holds
    /// the answer is a coin flip the branch predictor loses half the time, and on an
    /// environment map the mispredictions made this search 8% of a matpreview render.
    #[inline(always)]
    fn halve(&mut self, at_or_below: impl Fn(usize) -> bool) {
        let half = self.size / 2;
        let mid = self.base + half;
        // `select_unpredictable`: a plain `if` here was compiled back into a branch.
        self.base = std::hint::select_unpredictable(at_or_below(mid), mid, self.base);
        self.size -= half;
    }
}

/// The bucket's bounds hold up to rounding: from the end of the binary search at `base`,
/// settles on the item where the cdf crosses u (at most `n − 1`).
#[inline(always)]
fn settle<T: CdfValue>(n: usize, cdf: impl Fn(usize) -> T, u: T, base: usize) -> usize {
    let mut i = base + usize::from(cdf(base) <= u);
    while i > 0 && cdf(i - 1) > u {
        i -= 1;
    }
    while i < n && cdf(i) <= u {
        i += 1;
    }
    i.min(n - 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn binary_search(cdf: &[f32], u: f32) -> usize {
        cdf.partition_point(|&c| c <= u).min(cdf.len() - 1)
    }

    fn cdf_of(weights: &[f32]) -> Vec<f32> {
        let total: f64 = weights.iter().map(|&w| f64::from(w)).sum();
        let mut acc = 0.0;
        let mut cdf: Vec<f32> = weights
            .iter()
            .map(|&w| {
                acc += f64::from(w);
                (acc / total) as f32
            })
            .collect();
        *cdf.last_mut().unwrap() = 1.0;
        cdf
    }

    #[test]
    fn finds_what_a_binary_search_finds() {
        // A peaked distribution, runs of zero weight, a single item, and every item equal.
        let mut peaked: Vec<f32> = (0..300).map(|i| if i % 7 == 0 { 0.0 } else { 1e-6 * i as f32 }).collect();
        peaked[150] = 1e3;
        let cases = [
            peaked,
            vec![1.0],
            vec![0.0, 0.0, 1.0, 0.0],
            vec![1.0; 1000],
            vec![1.0; 8],
            vec![1.0; 9],
            vec![1e-30, 1.0, 1e-30],
        ];
        for weights in &cases {
            let cdf = cdf_of(weights);
            let guide = CdfGuide::new(cdf.len(), |i| cdf[i]);
            let mut us: Vec<f32> = (0..=100_000).map(|k| k as f32 / 100_000.0).collect();
            // Every cdf value and its neighbours, where an off-by-one would show.
            for &c in &cdf {
                us.extend([c, f32::from_bits(c.to_bits().saturating_sub(1)), f32::from_bits(c.to_bits() + 1)]);
            }
            us.extend([0.0, 1.0 - f32::EPSILON / 2.0, 1.0, -0.5, 2.0]);
            for u in us {
                let found = guide.find(cdf.len(), |i| cdf[i], u);
                assert_eq!(found, binary_search(&cdf, u), "u = {u}, {} items", cdf.len());
            }
        }
    }

    /// Searches made in lockstep find what each finds alone, whatever mix of lengths (scanned
    /// and guided) and numbers they are given together.
    #[test]
    fn interleaved_searches_find_what_each_finds_alone() {
        let weights: [Vec<f32>; 4] = [
            (0..517).map(|i| ((i * 7919) % 101) as f32).collect(),
            vec![1.0, 0.0, 2.0],
            (0..64).map(|i| if i == 40 { 1e4 } else { 1e-3 }).collect(),
            vec![1.0; 9],
        ];
        let cdfs: Vec<Vec<f32>> = weights.iter().map(|w| cdf_of(w)).collect();
        let guides: Vec<CdfGuide> = cdfs.iter().map(|c| CdfGuide::new(c.len(), |i| c[i])).collect();
        let mut rng = crate::sampling::Pcg32::new(7, 3);
        for _ in 0..20_000 {
            let searches: [(&CdfGuide, &[f32], f32); 5] = std::array::from_fn(|_| {
                let k = (rng.next_u32() % 4) as usize;
                (&guides[k], cdfs[k].as_slice(), rng.next_f32())
            });
            let together = find_interleaved(&searches);
            for (&(guide, cdf, u), found) in searches.iter().zip(together) {
                assert_eq!(found, guide.find(cdf.len(), |i| cdf[i], u), "u = {u}, {} items", cdf.len());
            }
        }
    }
}
