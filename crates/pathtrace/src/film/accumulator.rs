//! Per-pixel accumulation: sample count, running mean and running sum of squared deviations
//! per channel (Welford, "Note on a Method for Calculating Corrected Sums of Squares and
//! Products", 1962), kept in f64 so that millions of samples lose no precision.

use crate::math::Rgb;

/// The statistics of one pixel's samples.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelStats {
    pub count: u32,
    pub mean: [f64; 3],
    pub m2: [f64; 3],
}

impl PixelStats {
    /// Adds one sample (Welford's update).
    #[inline]
    pub fn add(&mut self, c: Rgb) {
        self.count += 1;
        let n = self.count as f64;
        for (k, x) in c.to_array().into_iter().enumerate() {
            let x = x as f64;
            let delta = x - self.mean[k];
            self.mean[k] += delta / n;
            self.m2[k] += delta * (x - self.mean[k]);
        }
    }

    /// Combines two sets of samples as if they had been added one by one (Chan, Golub &
    /// LeVeque, "Updating Formulae and a Pairwise Algorithm for Computing Sample Variances", 1979).
    #[inline]
    pub fn merge(&mut self, o: &PixelStats) {
        if o.count == 0 {
            return;
        }
        if self.count == 0 {
            *self = *o;
            return;
        }
        let (na, nb) = (self.count as f64, o.count as f64);
        let n = na + nb;
        for k in 0..3 {
            let delta = o.mean[k] - self.mean[k];
            self.mean[k] += delta * nb / n;
            self.m2[k] += o.m2[k] + delta * delta * na * nb / n;
        }
        self.count += o.count;
    }

    pub fn mean_rgb(&self) -> Rgb {
        Rgb::new(self.mean[0] as f32, self.mean[1] as f32, self.mean[2] as f32)
    }

    /// Unbiased sample variance per channel (zero with fewer than two samples).
    pub fn sample_variance(&self) -> [f64; 3] {
        if self.count < 2 {
            return [0.0; 3];
        }
        let d = (self.count - 1) as f64;
        self.m2.map(|m| m / d)
    }

    /// Estimated variance of the pixel's mean, per channel: s² / n.
    pub fn variance_of_mean(&self) -> [f64; 3] {
        let n = self.count.max(1) as f64;
        self.sample_variance().map(|v| v / n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn welford_and_merge_match_the_two_pass_formulas() {
        let xs: Vec<f32> = (0..50).map(|i| ((i * 37) % 11) as f32 * 0.3 + 1.0).collect();
        let mut all = PixelStats::default();
        let (mut a, mut b) = (PixelStats::default(), PixelStats::default());
        for (i, &x) in xs.iter().enumerate() {
            all.add(Rgb::splat(x));
            if i < 17 {
                a.add(Rgb::splat(x))
            } else {
                b.add(Rgb::splat(x))
            }
        }
        a.merge(&b);
        let n = xs.len() as f64;
        let mean = xs.iter().map(|&x| x as f64).sum::<f64>() / n;
        let var = xs.iter().map(|&x| (x as f64 - mean).powi(2)).sum::<f64>() / (n - 1.0);
        for s in [all, a] {
            assert_eq!(s.count, 50);
            assert!((s.mean[0] - mean).abs() < 1e-12);
            assert!((s.sample_variance()[1] - var).abs() < 1e-9);
        }
    }
}
