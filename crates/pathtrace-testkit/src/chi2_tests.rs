//! Tests of the chi-square test itself, on samplers with known densities.

use glam::Vec3;
use std::f64::consts::{PI, TAU};

use crate::{ChiSquareTest, TestRng};

/// Uniform on the sphere: z = 1 − 2u, φ = 2πv (pdf 1/(4π)).
fn uniform_sphere([u, v]: [f64; 2]) -> Option<Vec3> {
    let z = 1.0 - 2.0 * u;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = TAU * v;
    Some(Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32))
}

/// Cosine-weighted about +z via Malley's method: a uniform disk point lifted to the
/// hemisphere (pdf cos θ / π).
fn cosine_hemisphere([u, v]: [f64; 2]) -> Option<Vec3> {
    let r = u.sqrt();
    let phi = TAU * v;
    let z = (1.0 - u).max(0.0).sqrt();
    Some(Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32))
}

fn cosine_pdf(w: Vec3) -> f64 {
    (f64::from(w.z) / PI).max(0.0)
}

fn uniform_hemisphere_pdf(w: Vec3) -> f64 {
    if w.z > 0.0 {
        1.0 / TAU
    } else {
        0.0
    }
}

/// Samples a normalised Phong lobe (n + 1)/(2π) cos^n α about `axis`:
/// cos α = u^(1/(n+1)), β = 2πv around the axis.
fn phong_sampler(axis: Vec3, n: f64) -> impl FnMut([f64; 2]) -> Option<Vec3> {
    let (t, b) = axis.any_orthonormal_pair();
    move |[u, v]| {
        let cos_a = u.powf(1.0 / (n + 1.0));
        let sin_a = (1.0 - cos_a * cos_a).max(0.0).sqrt();
        let beta = TAU * v;
        let local = (sin_a * beta.cos(), sin_a * beta.sin(), cos_a);
        Some((t * local.0 as f32 + b * local.1 as f32 + axis * local.2 as f32).normalize())
    }
}

/// The Phong lobe's pdf, evaluated in f64: with exponent 1000, an f32 axis that is
/// 6e-8 off unit length alone biases cos^n by 6e-5, i.e. 60 samples in 10⁶.
fn phong_pdf(axis: Vec3, n: f64) -> impl Fn(Vec3) -> f64 {
    let axis = axis.as_dvec3().normalize();
    move |w| (n + 1.0) / TAU * w.as_dvec3().normalize().dot(axis).max(0.0).powf(n)
}

#[test]
fn uniform_sphere_passes_with_full_dof() {
    let outcome = ChiSquareTest::default().run(uniform_sphere, |_| 1.0 / (4.0 * PI));
    assert!(outcome.passed, "{outcome}");
    assert_eq!(outcome.dof, 199, "{outcome}");
    assert_eq!(outcome.pooled_bins, 0);
    assert!((outcome.pdf_integral - 1.0).abs() < 1e-9);
}

#[test]
fn cosine_hemisphere_passes_with_its_pdf() {
    let outcome = ChiSquareTest::default().run(cosine_hemisphere, cosine_pdf);
    assert!(outcome.passed, "{outcome}");
}

#[test]
fn cosine_hemisphere_fails_with_uniform_hemisphere_pdf() {
    let outcome = ChiSquareTest::default().run(cosine_hemisphere, uniform_hemisphere_pdf);
    assert!(!outcome.passed, "{outcome}");
    assert!(outcome.p_value < 1e-10);
    assert!(outcome.problems.is_empty(), "{outcome}");
}

#[test]
fn sharp_phong_lobe_passes_and_a_wrong_exponent_fails() {
    // The lobe is ~0.03 rad wide: finer bins give it ~25 degrees of freedom, enough to
    // tell exponent 1000 from 950.
    let axis = Vec3::new(0.3, -0.5, 0.8).normalize();
    let test = ChiSquareTest { theta_bins: 40, phi_bins: 80, ..ChiSquareTest::default() };
    let good = test.run(phong_sampler(axis, 1000.0), phong_pdf(axis, 1000.0));
    assert!(good.passed, "{good}");
    assert!(good.dof > 10, "{good}");
    let bad = test.run(phong_sampler(axis, 1000.0), phong_pdf(axis, 950.0));
    assert!(!bad.passed, "{bad}");
}

#[test]
fn rejected_samples_are_compared_with_the_missing_mass() {
    // Absorb 30%: the pdf of the returned directions integrates to 0.7.
    let absorbing = |[u, v]: [f64; 2]| {
        if u < 0.3 {
            None
        } else {
            uniform_sphere([(u - 0.3) / 0.7, v])
        }
    };
    let test = ChiSquareTest::default();
    let good = test.run(absorbing, |_| 0.7 / (4.0 * PI));
    assert!(good.passed, "{good}");
    assert!((good.missing_expected - 300_000.0).abs() < 1.0);
    let bad = test.run(absorbing, |_| 0.75 / (4.0 * PI));
    assert!(!bad.passed, "{bad}");
    let claims_no_absorption = test.run(absorbing, |_| 1.0 / (4.0 * PI));
    assert!(!claims_no_absorption.passed);
    assert!(!claims_no_absorption.problems.is_empty(), "{claims_no_absorption}");
}

#[test]
fn samples_where_the_pdf_is_zero_fail() {
    // A "hemisphere" sampler that leaks 1% of its samples below the horizon.
    let leaky = |[u, v]: [f64; 2]| {
        let d = cosine_hemisphere([u, v])?;
        Some(if u < 0.01 { -d } else { d })
    };
    let test = ChiSquareTest { samples: 100_000, ..ChiSquareTest::default() };
    let outcome = test.run(leaky, cosine_pdf);
    assert!(!outcome.passed);
    assert!(outcome.problems.iter().any(|p| p.contains("pdf integrates to 0")), "{outcome}");
}

#[test]
fn non_unit_directions_fail() {
    let test = ChiSquareTest { samples: 10_000, ..ChiSquareTest::default() };
    let nan = test.run(|_| Some(Vec3::NAN), |_| 1.0 / (4.0 * PI));
    assert!(!nan.passed && nan.invalid_samples == 10_000, "{nan}");
    let long = test.run(|uv| uniform_sphere(uv).map(|d| d * 2.0), |_| 1.0 / (4.0 * PI));
    assert!(!long.passed && long.invalid_samples == 10_000);
}

#[test]
fn pdf_with_too_much_mass_fails() {
    let test = ChiSquareTest { samples: 10_000, ..ChiSquareTest::default() };
    let outcome = test.run(uniform_sphere, |_| 1.1 / (4.0 * PI));
    assert!(!outcome.passed);
    assert!(outcome.problems.iter().any(|p| p.contains("> 1")), "{outcome}");
    let nan = test.run(uniform_sphere, |_| f64::NAN);
    assert!(!nan.passed && !nan.problems.is_empty());
}

#[test]
fn small_bins_are_pooled() {
    // 2 000 samples over 200 bins expect 10 each: all below 20, so all pool into one
    // bin, which is then the whole distribution (dof 0: nothing to test).
    let test = ChiSquareTest { samples: 2_000, min_expected: 20.0, ..ChiSquareTest::default() };
    let outcome = test.run(uniform_sphere, |_| 1.0 / (4.0 * PI));
    assert_eq!(outcome.pooled_bins, 200);
    assert_eq!(outcome.dof, 0);
    assert_eq!(outcome.p_value, 1.0);
    assert!(outcome.passed, "{outcome}");

    // Cosine lobe, 2 000 samples: the 20 bins with cos θ ∈ [0, 0.2] expect
    // 2000 · 0.04/20 = 4 each, so they pool (with the near-empty missing-sample bin,
    // if the integral left any mass for it); the other 80 upper bins expect ≥ 12.
    let test = ChiSquareTest { samples: 2_000, ..ChiSquareTest::default() };
    let outcome = test.run(cosine_hemisphere, cosine_pdf);
    assert!((20..=21).contains(&outcome.pooled_bins), "{outcome}");
    let cells = 100 + usize::from(outcome.missing_expected > 0.0);
    assert_eq!(outcome.dof, cells - outcome.pooled_bins, "{outcome}");
    assert!(outcome.passed, "{outcome}");
}

#[test]
fn same_seed_same_outcome_and_bad_config_is_reported() {
    let test = ChiSquareTest { samples: 10_000, ..ChiSquareTest::default() };
    let a = test.run(uniform_sphere, |_| 1.0 / (4.0 * PI));
    let b = test.run(uniform_sphere, |_| 1.0 / (4.0 * PI));
    assert_eq!(a, b);
    let empty = ChiSquareTest { theta_bins: 0, ..test };
    let outcome = empty.run(uniform_sphere, |_| 1.0 / (4.0 * PI));
    assert!(!outcome.passed && !outcome.problems.is_empty());
}

#[test]
fn summary_shows_tables() {
    let test = ChiSquareTest { theta_bins: 3, phi_bins: 4, samples: 1_000, ..ChiSquareTest::default() };
    let text = test.run(cosine_hemisphere, cosine_pdf).to_string();
    for needle in ["PASSED", "observed", "expected", "residual", "dof"] {
        assert!(text.contains(needle), "{text}");
    }
    // A title line plus 3 rows per table.
    assert_eq!(text.lines().filter(|l| l.contains('|')).count(), 9, "{text}");
}

#[test]
fn rng_feeds_the_sampler_uniform_points() {
    // The sampler sees exactly TestRng(seed)'s 2D points.
    let test = ChiSquareTest { samples: 3, seed: 99, ..ChiSquareTest::default() };
    let mut seen = Vec::new();
    test.run(
        |uv| {
            seen.push(uv);
            uniform_sphere(uv)
        },
        |_| 1.0 / (4.0 * PI),
    );
    let mut rng = TestRng::new(99);
    let expected: Vec<[f64; 2]> = (0..3).map(|_| rng.next_2d()).collect();
    assert_eq!(seen, expected);
}
