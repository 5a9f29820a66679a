//! Comparing Monte Carlo estimates: sample means, their variances and z-scores.

/// A sample mean with the estimated variance of that mean.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeanEstimate {
    /// The sample mean.
    pub mean: f64,
    /// The estimated variance of `mean`: sample variance / count. Infinite when fewer
    /// than two samples give no variance estimate; 0 for an exact value.
    pub variance_of_mean: f64,
    /// The number of samples (0 for an exact value).
    pub count: usize,
}

impl MeanEstimate {
    /// The mean of `samples` and its variance, by Welford's one-pass algorithm
    /// (Welford, "Note on a method for calculating corrected sums of squares and
    /// products", Technometrics 1962) with the unbiased (n − 1) sample variance.
    pub fn from_samples(samples: &[f64]) -> MeanEstimate {
        let mut mean = 0.0;
        let mut m2 = 0.0;
        for (k, &x) in samples.iter().enumerate() {
            let delta = x - mean;
            mean += delta / (k + 1) as f64;
            m2 += delta * (x - mean);
        }
        let n = samples.len();
        let variance_of_mean = if n < 2 { f64::INFINITY } else { m2 / (n - 1) as f64 / n as f64 };
        MeanEstimate { mean: if n == 0 { f64::NAN } else { mean }, variance_of_mean, count: n }
    }

    /// A known value (e.g. an analytic result): zero variance, count 0.
    pub fn exact(value: f64) -> MeanEstimate {
        MeanEstimate { mean: value, variance_of_mean: 0.0, count: 0 }
    }

    /// The standard error: √variance_of_mean.
    pub fn std_error(&self) -> f64 {
        self.variance_of_mean.sqrt()
    }
}

/// (a.mean − b.mean) / √(a.variance_of_mean + b.variance_of_mean): how many standard
/// errors apart two independent estimates are. Equal exact values give 0; different
/// exact values give ±∞; NaN means or variances give NaN.
pub fn z_score(a: &MeanEstimate, b: &MeanEstimate) -> f64 {
    let diff = a.mean - b.mean;
    let variance = a.variance_of_mean + b.variance_of_mean;
    if variance == 0.0 && diff == 0.0 {
        return 0.0;
    }
    diff / variance.sqrt()
}

/// Panics with a readable message unless `|z_score(a, b)| ≤ max_z`; also panics when
/// either estimate has too few samples for a variance (that comparison would prove
/// nothing) or anything is NaN. For tests: a failure is the point.
#[track_caller]
pub fn assert_agree(a: &MeanEstimate, b: &MeanEstimate, max_z: f64) {
    let describe = |m: &MeanEstimate| {
        if m.count == 0 && m.variance_of_mean == 0.0 {
            format!("{} (exact)", m.mean)
        } else {
            format!("{} ± {} (n = {})", m.mean, m.std_error(), m.count)
        }
    };
    for m in [a, b] {
        assert!(!m.mean.is_nan() && !m.variance_of_mean.is_nan(), "estimate {} contains NaN", describe(m));
        assert!(
            m.variance_of_mean.is_finite(),
            "estimate {} has no variance estimate (needs at least 2 samples)",
            describe(m)
        );
    }
    let z = z_score(a, b);
    assert!(
        z.abs() <= max_z,
        "estimates disagree: {} vs {}: z = {z:.3}, allowed |z| ≤ {max_z}",
        describe(a),
        describe(b)
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::TestRng;

    #[test]
    fn known_mean_and_variance() {
        let m = MeanEstimate::from_samples(&[2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0]);
        assert_eq!(m.count, 8);
        assert!((m.mean - 5.0).abs() < 1e-15);
        // Sample variance 32/7; variance of the mean (32/7)/8 = 4/7.
        assert!((m.variance_of_mean - 4.0 / 7.0).abs() < 1e-15);
    }

    #[test]
    fn too_few_samples() {
        let empty = MeanEstimate::from_samples(&[]);
        assert!(empty.mean.is_nan() && empty.variance_of_mean.is_infinite());
        let one = MeanEstimate::from_samples(&[3.0]);
        assert_eq!(one.mean, 3.0);
        assert!(one.variance_of_mean.is_infinite());
    }

    #[test]
    fn welford_is_stable_with_a_large_offset() {
        let xs: Vec<f64> = (0..1000).map(|i| 1e9 + (i % 2) as f64).collect();
        let m = MeanEstimate::from_samples(&xs);
        // Variance of alternating 0/1 is 0.25·n/(n − 1).
        let expected = 0.25 * 1000.0 / 999.0 / 1000.0;
        assert!((m.variance_of_mean - expected).abs() < 1e-12, "{}", m.variance_of_mean);
    }

    #[test]
    fn z_scores() {
        let a = MeanEstimate { mean: 1.0, variance_of_mean: 0.01, count: 100 };
        let b = MeanEstimate { mean: 1.5, variance_of_mean: 0.03, count: 100 };
        assert!((z_score(&a, &b) + 2.5).abs() < 1e-12);
        assert!((z_score(&b, &a) - 2.5).abs() < 1e-12);
        assert_eq!(z_score(&MeanEstimate::exact(2.0), &MeanEstimate::exact(2.0)), 0.0);
        assert!(z_score(&MeanEstimate::exact(2.0), &MeanEstimate::exact(3.0)).is_infinite());
    }

    #[test]
    fn uniform_mean_agrees_with_one_half() {
        let mut rng = TestRng::new(3);
        let xs: Vec<f64> = (0..100_000).map(|_| rng.next_f64()).collect();
        let m = MeanEstimate::from_samples(&xs);
        assert_agree(&m, &MeanEstimate::exact(0.5), 4.0);
        // Standard error of U(0,1) means: √(1/12/n).
        assert!((m.std_error() - (1.0 / 12.0 / 1e5f64).sqrt()).abs() < 1e-5);
    }

    #[test]
    #[should_panic(expected = "estimates disagree")]
    fn disagreement_panics() {
        let mut rng = TestRng::new(4);
        let xs: Vec<f64> = (0..10_000).map(|_| rng.next_f64()).collect();
        assert_agree(&MeanEstimate::from_samples(&xs), &MeanEstimate::exact(0.52), 4.0);
    }

    #[test]
    #[should_panic(expected = "no variance estimate")]
    fn single_sample_cannot_agree() {
        assert_agree(&MeanEstimate::from_samples(&[0.5]), &MeanEstimate::exact(0.5), 4.0);
    }

    #[test]
    #[should_panic(expected = "NaN")]
    fn nan_cannot_agree() {
        let m = MeanEstimate::from_samples(&[f64::NAN, 1.0, 2.0]);
        assert_agree(&m, &MeanEstimate::exact(1.0), 4.0);
    }
}
