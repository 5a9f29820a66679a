//! The result of a [`ChiSquareTest`](crate::ChiSquareTest), with a readable report.

use std::fmt::{self, Write as _};

use crate::chi2::ChiSquareTest;

/// The result of [`ChiSquareTest::run`]. `Display` prints [`ChiSquareOutcome::summary`].
#[derive(Clone, Debug, PartialEq)]
pub struct ChiSquareOutcome {
    /// Pearson's statistic Σ (observed − expected)² / expected over the pooled bins.
    pub statistic: f64,
    /// Degrees of freedom: pooled bin count − 1.
    pub dof: usize,
    /// P(χ²(dof) ≥ statistic).
    pub p_value: f64,
    /// True when `p_value ≥ significance` and `problems` is empty.
    pub passed: bool,
    /// The significance level the test used.
    pub significance: f64,
    /// Bins in `cos θ`.
    pub theta_bins: usize,
    /// Bins in `φ`.
    pub phi_bins: usize,
    /// Sample counts per bin, index `i * phi_bins + j` with `i` counting `cos θ` bins
    /// up from −1 and `j` counting `φ` bins up from 0.
    pub observed: Vec<f64>,
    /// Expected counts per bin, indexed like `observed`.
    pub expected: Vec<f64>,
    /// Samples the sampler rejected (returned `None`).
    pub missing_observed: f64,
    /// `samples · (1 − ∫ pdf dω)`.
    pub missing_expected: f64,
    /// ∫ pdf dω over the sphere, as integrated.
    pub pdf_integral: f64,
    /// Sampled directions that were not finite unit vectors (they make the test fail).
    pub invalid_samples: usize,
    /// How many bins (including the missing-sample bin) were pooled into one.
    pub pooled_bins: usize,
    /// Problems that make the test fail regardless of the p-value.
    pub problems: Vec<String>,
}

impl ChiSquareOutcome {
    /// An outcome with zero counts and no verdict, sized for `test`.
    pub(crate) fn empty(test: &ChiSquareTest) -> ChiSquareOutcome {
        let bins = test.theta_bins * test.phi_bins;
        ChiSquareOutcome {
            statistic: 0.0,
            dof: 0,
            p_value: 1.0,
            passed: false,
            significance: test.significance,
            theta_bins: test.theta_bins,
            phi_bins: test.phi_bins,
            observed: vec![0.0; bins],
            expected: vec![0.0; bins],
            missing_observed: 0.0,
            missing_expected: 0.0,
            pdf_integral: 0.0,
            invalid_samples: 0,
            pooled_bins: 0,
            problems: Vec::new(),
        }
    }

    /// Checks for impossible samples, pools small bins and sets `statistic` and `dof`.
    pub(crate) fn finish(&mut self, min_expected: f64) {
        let mut cells: Vec<(f64, f64)> = self.observed.iter().copied().zip(self.expected.iter().copied()).collect();
        cells.push((self.missing_observed, self.missing_expected));

        let impossible: f64 = cells.iter().filter(|&&(o, e)| e <= 0.0 && o > 0.0).map(|&(o, _)| o).sum();
        if impossible > 0.0 {
            self.problems.push(format!(
                "{impossible} samples fell where the pdf integrates to 0 (or were rejected \
                 although the pdf integrates to 1)"
            ));
        }
        // Cells that expect nothing and got nothing carry no information.
        cells.retain(|&(o, e)| e > 0.0 || o > 0.0);

        // Pool every cell below `min_expected`; if the pool itself is still below it,
        // keep adding the smallest remaining cells (cf. Mitsuba 3's chi2 pooling).
        cells.sort_by(|a, b| a.1.total_cmp(&b.1));
        let mut split = cells.iter().take_while(|c| c.1 < min_expected).count();
        let mut pool_expected: f64 = cells[..split].iter().map(|c| c.1).sum();
        while split > 0 && pool_expected < min_expected && split < cells.len() {
            pool_expected += cells[split].1;
            split += 1;
        }
        self.pooled_bins = split;
        let pool = cells[..split].iter().fold((0.0, 0.0), |acc, c| (acc.0 + c.0, acc.1 + c.1));
        let mut kept: Vec<(f64, f64)> = cells[split..].to_vec();
        if split > 0 {
            kept.push(pool);
        }

        self.statistic = kept.iter().filter(|c| c.1 > 0.0).map(|&(o, e)| (o - e) * (o - e) / e).sum();
        self.dof = kept.len().saturating_sub(1);
    }

    /// A multi-line report: the verdict, any problems, and observed / expected /
    /// standardised-residual tables with `cos θ` decreasing down the rows.
    pub fn summary(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "chi-square test {}: statistic {:.2}, dof {}, p-value {:.4e} (significance {})",
            if self.passed { "PASSED" } else { "FAILED" },
            self.statistic,
            self.dof,
            self.p_value,
            self.significance
        );
        let _ = writeln!(
            s,
            "∫pdf dω = {:.6}; missing samples: observed {}, expected {:.1}; {} bins pooled; \
             {} invalid samples",
            self.pdf_integral, self.missing_observed, self.missing_expected, self.pooled_bins, self.invalid_samples
        );
        for p in &self.problems {
            let _ = writeln!(s, "problem: {p}");
        }
        self.table(&mut s, "observed", |o, _| o);
        self.table(&mut s, "expected", |_, e| e);
        self.table(&mut s, "residual (o − e)/√e", |o, e| {
            if e > 0.0 {
                (o - e) / e.sqrt()
            } else if o > 0.0 {
                f64::INFINITY
            } else {
                0.0
            }
        });
        s
    }

    /// Appends one table of `cell(observed, expected)` values.
    fn table(&self, s: &mut String, title: &str, cell: impl Fn(f64, f64) -> f64) {
        let _ = writeln!(s, "{title} (rows: cos θ from +1 down to −1; columns: φ from 0):");
        for i in (0..self.theta_bins).rev() {
            let upper = -1.0 + 2.0 * (i + 1) as f64 / self.theta_bins as f64;
            let _ = write!(s, "{upper:+6.2} |");
            for j in 0..self.phi_bins {
                let k = i * self.phi_bins + j;
                let v = cell(self.observed[k], self.expected[k]);
                let _ = write!(s, " {}", compact(v));
            }
            s.push('\n');
        }
    }
}

/// A number in at most 7 characters.
fn compact(v: f64) -> String {
    if v == 0.0 || (v.abs() >= 0.01 && v.abs() < 1e5) {
        format!("{v:7.1}")
    } else {
        format!("{v:7.0e}")
    }
}

impl fmt::Display for ChiSquareOutcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.summary())
    }
}
