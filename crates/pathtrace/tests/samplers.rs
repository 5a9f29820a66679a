//! Samplers on an analytic integrand: the variance of the estimate of ∫∫ f over the unit square
//! orders as theory says (independent > stratified > Owen-scrambled Sobol'), and the stratified
//! variance matches the textbook formula for one jittered sample per stratum:
//! Var = (1/n²) Σᵢ σᵢ², with σᵢ² the variance of f within stratum i (equal strata,
//! proportional allocation; e.g. Owen, "Monte Carlo theory, methods and examples", §10.1).

use pathtrace::sampling::{Sampler, SamplerKind};

fn f(x: f64, y: f64) -> f64 {
    (3.0 * x).sin() * (1.0 + y * y) + x * y
}

/// Mean and variance over `pixels` independent estimates, each from `n` samples of one pixel.
fn estimates(kind: SamplerKind, n: u32, pixels: u32) -> (f64, f64) {
    let mut s = Sampler::new(kind, 11, n);
    let values: Vec<f64> = (0..pixels)
        .map(|p| {
            let sum: f64 = (0..n)
                .map(|i| {
                    s.start(p % 1000, p / 1000, i);
                    let u = s.next_2d();
                    f(u.x as f64, u.y as f64)
                })
                .sum();
            sum / n as f64
        })
        .collect();
    let mean = values.iter().sum::<f64>() / values.len() as f64;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (values.len() - 1) as f64;
    (mean, var)
}

/// Variance of f within the cell [x0, x0+h) × [y0, y0+h), by a fine midpoint rule.
fn cell_variance(x0: f64, y0: f64, h: f64) -> f64 {
    let m = 64;
    let (mut s1, mut s2) = (0.0, 0.0);
    for j in 0..m {
        for i in 0..m {
            let v = f(x0 + (i as f64 + 0.5) * h / m as f64, y0 + (j as f64 + 0.5) * h / m as f64);
            s1 += v;
            s2 += v * v;
        }
    }
    let n = (m * m) as f64;
    s2 / n - (s1 / n).powi(2)
}

#[test]
fn variance_orders_as_theory_says_and_stratified_matches_the_formula() {
    let n = 64u32;
    let pixels = 4000;
    // Exact integral: ∫ sin(3x) dx ∫ (1 + y²) dy + 1/4 = ((1 − cos 3)/3)(4/3) + 1/4.
    let exact = (1.0 - 3f64.cos()) / 3.0 * (4.0 / 3.0) + 0.25;
    let (m_ind, v_ind) = estimates(SamplerKind::Independent, n, pixels);
    let (m_str, v_str) = estimates(SamplerKind::Stratified, n, pixels);
    let (m_sob, v_sob) = estimates(SamplerKind::Sobol, n, pixels);
    for (name, m, v) in [("independent", m_ind, v_ind), ("stratified", m_str, v_str), ("sobol", m_sob, v_sob)] {
        let z = (m - exact).abs() / (v / pixels as f64).sqrt();
        assert!(z < 4.5, "{name}: mean {m} vs exact {exact} (z = {z:.2})");
    }
    assert!(v_str < 0.2 * v_ind, "stratified {v_str} vs independent {v_ind}");
    assert!(v_sob < 0.5 * v_str, "sobol {v_sob} vs stratified {v_str}");

    // Textbook stratified variance for the 8 × 8 grid.
    let k = 8;
    let h = 1.0 / k as f64;
    let mut sum = 0.0;
    for j in 0..k {
        for i in 0..k {
            sum += cell_variance(i as f64 * h, j as f64 * h, h);
        }
    }
    let predicted = sum / (n as f64 * n as f64);
    // The sample variance of 4000 estimates has relative standard error ≈ √(2/3999) ≈ 2.2%.
    let ratio = v_str / predicted;
    assert!((ratio - 1.0).abs() < 0.1, "measured {v_str:.3e} vs textbook {predicted:.3e} (ratio {ratio:.3})");
    // And the independent variance is σ²/n.
    let sigma2 = cell_variance(0.0, 0.0, 1.0);
    let ratio = v_ind / (sigma2 / n as f64);
    assert!((ratio - 1.0).abs() < 0.1, "independent: ratio {ratio:.3}");
}
