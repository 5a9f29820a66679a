//! Microfacet distributions: D is normalised in projected area (∫ D(m) cos θm dωm = 1), the
//! Smith masking satisfies the visible-area identity ∫ G1(v, m) max(0, v·m) D(m) dωm = cos θv
//! (so the visible-normal pdf integrates to 1), and visible-normal sampling matches that pdf
//! (chi-square) — for GGX and Beckmann, isotropic and anisotropic, at several view angles.

use pathtrace::material::{Microfacet, MicrofacetKind};
use pathtrace::math::special::gauss_legendre;
use pathtrace::math::{Vec2, Vec3};
use pathtrace_testkit::ChiSquareTest;

fn dir(theta_deg: f32, phi_deg: f32) -> Vec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

/// ∫ f dω over the upper hemisphere by a 256 × 512 Gauss–Legendre product rule in (cos θ, φ).
/// These integrands have kinks (where v·m = 0) and a jump at the horizon that make the testkit's
/// adaptive quadrature crawl; a fixed dense rule is accurate to ~1e-4 here, ample for 2e-3.
fn hemisphere_integral(f: impl Fn(Vec3) -> f64) -> f64 {
    let (mu_rule, phi_rule) = (gauss_legendre(256), gauss_legendre(512));
    let mut sum = 0.0;
    for (x, wx) in &mu_rule {
        let mu = 0.5 * (x + 1.0);
        let sin = (1.0 - mu * mu).max(0.0).sqrt();
        for (y, wy) in &phi_rule {
            let phi = std::f64::consts::PI * (y + 1.0);
            let m = Vec3::new((sin * phi.cos()) as f32, (sin * phi.sin()) as f32, mu as f32);
            sum += wx * wy * f(m);
        }
    }
    // Jacobians: dμ = dx/2, dφ = π dy.
    sum * 0.5 * std::f64::consts::PI
}

/// Roughnesses for the normalisation checks (a dense fixed rule resolves narrow lobes).
fn distributions() -> Vec<Microfacet> {
    let mut out = Vec::new();
    for kind in [MicrofacetKind::Ggx, MicrofacetKind::Beckmann] {
        out.push(Microfacet::isotropic(kind, 0.1));
        out.push(Microfacet::isotropic(kind, 0.5));
        out.push(Microfacet::isotropic(kind, 1.0));
        out.push(Microfacet::new(kind, 0.1, 0.4));
    }
    out
}

/// Roughnesses for the chi-square test: lobes wide enough to spread over several of its
/// 10 × 20 bins (a lobe inside one row of bins would test little).
fn sampled_distributions() -> Vec<Microfacet> {
    let mut out = Vec::new();
    for kind in [MicrofacetKind::Ggx, MicrofacetKind::Beckmann] {
        out.push(Microfacet::isotropic(kind, 0.3));
        out.push(Microfacet::isotropic(kind, 0.9));
        out.push(Microfacet::new(kind, 0.2, 0.6));
    }
    out
}

const VIEWS: [(f32, f32); 4] = [(0.0, 0.0), (30.0, 60.0), (65.0, 200.0), (85.0, 10.0)];

#[test]
fn distribution_is_normalised_in_projected_area() {
    for d in distributions() {
        let integral = hemisphere_integral(|m| (d.d(m) * m.z) as f64);
        assert!((integral - 1.0).abs() < 1e-3, "{d:?}: ∫ D cos = {integral}");
    }
}

#[test]
fn visible_normal_pdf_integrates_to_one() {
    for d in distributions() {
        for (theta, phi) in VIEWS {
            let v = dir(theta, phi);
            let integral = hemisphere_integral(|m| d.pdf_visible(v, m) as f64);
            assert!((integral - 1.0).abs() < 2e-3, "{d:?} at θv={theta}: ∫ D_v = {integral}");
        }
    }
}

#[test]
fn visible_normal_sampling_matches_its_pdf() {
    for d in sampled_distributions() {
        for (theta, phi) in VIEWS {
            let v = dir(theta, phi);
            let test = ChiSquareTest { samples: 300_000, integration_res: 8, ..Default::default() };
            let outcome = test.run(
                |u| Some(d.sample_visible(v, Vec2::new(u[0] as f32, u[1] as f32))),
                |m| d.pdf_visible(v, m) as f64,
            );
            assert!(outcome.passed, "{d:?} at θv={theta}: chi-square rejected\n{}", outcome.summary());
        }
    }
}

#[test]
fn smith_masking_is_one_at_normal_incidence_and_falls_towards_grazing() {
    for d in distributions() {
        assert!((d.g1(Vec3::Z, Vec3::Z) - 1.0).abs() < 1e-6);
        let mut last = 1.0;
        for theta in [20.0, 50.0, 80.0, 89.0] {
            let v = dir(theta, 30.0);
            let g = d.g1(v, Vec3::Z);
            assert!(g <= last + 1e-6 && g > 0.0, "{d:?}: G1 at {theta}° = {g}");
            last = g;
        }
        // A facet seen from behind is masked.
        assert_eq!(d.g1(dir(60.0, 0.0), dir(70.0, 180.0)), 0.0);
    }
}
