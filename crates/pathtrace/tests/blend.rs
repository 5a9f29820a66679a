//! The `blend` material's mixture (Mitsuba 3's `blendbsdf`): sampling matches its density
//! (chi-square), the density integrates to the fraction of samples drawn, sample weights are
//! f·|cos|/pdf of the whole mixture, and its value is the weighted sum of its models' values.

use pathtrace::material::{Lambertian, Material, Microfacet, MicrofacetKind, Mixture, RoughConductor, RoughPlastic};
use pathtrace::math::special::gauss_legendre;
use pathtrace::math::{Rgb, Vec2, Vec3};
use pathtrace_testkit::{ChiSquareTest, TestRng};

fn dir(theta_deg: f32, phi_deg: f32) -> Vec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

/// ∫ f dω over the upper hemisphere (the models are reflective) by a Gauss–Legendre product rule
/// in (cos θ, φ), dense enough for the narrow lobes here (as in microfacet_bsdfs.rs).
fn hemisphere_integral(f: impl Fn(Vec3) -> f64) -> f64 {
    let (mu_rule, phi_rule) = (gauss_legendre(160), gauss_legendre(320));
    let mut sum = 0.0;
    for (x, wx) in &mu_rule {
        let mu = 0.5 * (x + 1.0);
        let sin = (1.0 - mu * mu).max(0.0).sqrt();
        for (y, wy) in &phi_rule {
            let phi = std::f64::consts::PI * (y + 1.0);
            sum += wx * wy * f(Vec3::new((sin * phi.cos()) as f32, (sin * phi.sin()) as f32, mu as f32));
        }
    }
    sum * 0.5 * std::f64::consts::PI
}

fn metal(alpha_u: f32, alpha_v: f32) -> Material {
    Material::RoughConductor(RoughConductor {
        distribution: Microfacet::new(MicrofacetKind::Ggx, alpha_u, alpha_v),
        eta: Rgb::splat(0.0),
        k: Rgb::splat(1.0),
        reflectance: Rgb::new(0.95, 0.7, 0.4),
    })
}

/// glTF's pair (a Lambertian base and a GGX metal) at several weights, and a coated base with an
/// anisotropic metal.
fn mixtures() -> Vec<Mixture> {
    let base = Material::Lambertian(Lambertian { albedo: Rgb::new(0.2, 0.5, 0.8) });
    let plastic = Material::RoughPlastic(RoughPlastic::new(
        Microfacet::isotropic(MicrofacetKind::Ggx, 0.3),
        Rgb::new(0.6, 0.3, 0.2),
        Rgb::WHITE,
        1.5,
        false,
    ));
    vec![
        Mixture { weight: 0.3, bsdfs: [base, metal(0.15, 0.15)] },
        Mixture { weight: 0.8, bsdfs: [base, metal(0.05, 0.05)] },
        Mixture { weight: 0.5, bsdfs: [plastic, metal(0.1, 0.4)] },
    ]
}

fn views() -> [Vec3; 3] {
    [dir(0.0, 0.0), dir(35.0, 20.0), dir(70.0, 250.0)]
}

#[test]
fn sampling_matches_the_density_and_the_density_integrates_to_the_drawn_fraction() {
    for (k, m) in mixtures().iter().enumerate() {
        for wo in views() {
            let pdf = |wi: Vec3| if wi.z > 0.0 { m.pdf(wo, wi) as f64 } else { 0.0 };
            // Directions a microfacet reflects below the horizon are not drawn: ∫pdf equals the
            // fraction of samples that are, counted here independently.
            let mut rng = TestRng::new(4);
            let n = 200_000;
            let drawn = (0..n)
                .filter(|_| {
                    let (lobe, u) = (rng.next_f32(), Vec2::new(rng.next_f32(), rng.next_f32()));
                    m.sample(wo, lobe, u).is_some()
                })
                .count();
            let expected = drawn as f64 / n as f64;
            let integral = hemisphere_integral(pdf);
            assert!((integral - expected).abs() < 3e-3, "mixture {k} at wo={wo}: ∫pdf = {integral}, drawn {expected}");
            let mut lobes = TestRng::new(11);
            let test = ChiSquareTest { samples: 300_000, integration_res: 8, ..Default::default() };
            let outcome =
                test.run(|u| m.sample(wo, lobes.next_f32(), Vec2::new(u[0] as f32, u[1] as f32)).map(|s| s.wi), pdf);
            assert!(outcome.passed, "mixture {k} at wo={wo}: chi-square rejected\n{}", outcome.summary());
        }
    }
}

/// A chi-square test that can fail: the same samples judged against the density of the chosen
/// model alone (what a blend that forgot to mix its densities would report) are rejected.
#[test]
fn the_chi_square_test_rejects_an_unmixed_density() {
    let m = &mixtures()[0];
    let wo = dir(35.0, 20.0);
    let mut lobes = TestRng::new(11);
    let test = ChiSquareTest { samples: 300_000, integration_res: 8, ..Default::default() };
    let outcome = test.run(
        |u| m.sample(wo, lobes.next_f32(), Vec2::new(u[0] as f32, u[1] as f32)).map(|s| s.wi),
        |wi| if wi.z > 0.0 { m.bsdfs[1].pdf(wo, wi) as f64 } else { 0.0 },
    );
    assert!(!outcome.passed, "{}", outcome.summary());
}

#[test]
fn values_mix_linearly_and_weights_are_the_mixtures() {
    let mut rng = TestRng::new(5);
    for m in mixtures() {
        for wo in views() {
            for _ in 0..3000 {
                let (lobe, u) = (rng.next_f32(), Vec2::new(rng.next_f32(), rng.next_f32()));
                let Some(s) = m.sample(wo, lobe, u) else { continue };
                assert!(!s.delta);
                let w = m.weight;
                let f = m.bsdfs[0].eval(wo, s.wi) * (1.0 - w) + m.bsdfs[1].eval(wo, s.wi) * w;
                let pdf = (1.0 - w) * m.bsdfs[0].pdf(wo, s.wi) + w * m.bsdfs[1].pdf(wo, s.wi);
                assert!((m.eval(wo, s.wi) - f).max_component().abs() <= 1e-5 * f.max_component().max(1.0));
                assert!((s.pdf - pdf).abs() <= 1e-4 * pdf, "pdf {} vs {pdf}", s.pdf);
                let expected = f * (1.0 / pdf);
                let err = (s.weight - expected).max_component().abs();
                assert!(err <= 1e-3 * expected.max_component().max(1e-3), "{:?} vs {expected:?}", s.weight);
            }
        }
    }
}

/// Mitsuba's convention: a lobe number below the weight draws from model 1.
#[test]
fn the_weight_is_model_ones_share() {
    let base = Material::Lambertian(Lambertian { albedo: Rgb::splat(0.5) });
    let m = Mixture { weight: 0.25, bsdfs: [base, metal(0.001, 0.001)] };
    let wo = dir(30.0, 0.0);
    let mirror = Vec3::new(-wo.x, -wo.y, wo.z);
    let mut rng = TestRng::new(9);
    let n = 100_000;
    let near_mirror = (0..n)
        .filter(|_| {
            let (lobe, u) = (rng.next_f32(), Vec2::new(rng.next_f32(), rng.next_f32()));
            m.sample(wo, lobe, u).is_some_and(|s| s.wi.dot(mirror) > 0.999)
        })
        .count() as f64
        / n as f64;
    // The metal (GGX α = 0.001) puts all but 0.2% of its samples within 2.6° of the mirror
    // direction (GGX's tail beyond a half-vector slope t holds α²/(α² + t²), t = tan 1.28°);
    // the Lambertian base puts 0.2% there (the cone's cosine-weighted share, ≈ sin²2.6°).
    assert!((near_mirror - 0.25).abs() < 0.01, "{near_mirror}");
}
