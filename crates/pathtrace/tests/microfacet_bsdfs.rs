//! Microfacet and coated materials: sampling matches the pdf (chi-square), the pdf integrates
//! to 1 (or to the probability of the non-Dirac part), sample weights equal f·cos/pdf, the
//! models are reciprocal (rough glass in the generalised η² form), no model reflects more
//! than it receives, and a rough conductor with F = 1 loses exactly the single-scattering
//! deficit that an independent quadrature of its BRDF predicts.

use pathtrace::material::{
    Material, Microfacet, MicrofacetKind, Plastic, RoughConductor, RoughDielectric, RoughPlastic,
};
use pathtrace::math::special::gauss_legendre;
use pathtrace::math::{Rgb, Vec2, Vec3};
use pathtrace_testkit::{ChiSquareTest, MeanEstimate, TestRng};

const GGX: MicrofacetKind = MicrofacetKind::Ggx;
const BECKMANN: MicrofacetKind = MicrofacetKind::Beckmann;

fn dir(theta_deg: f32, phi_deg: f32) -> Vec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

/// ∫ f dω over the sphere by a Gauss–Legendre product rule in (cos θ, φ), each hemisphere
/// separately (the BSDFs jump at the horizon). The testkit's adaptive quadrature crawls on the
/// kinks of microfacet lobes; this fixed dense rule is accurate to ~1e-4 for these lobes.
fn sphere_integral(f: impl Fn(Vec3) -> f64) -> f64 {
    let (mu_rule, phi_rule) = (gauss_legendre(160), gauss_legendre(320));
    let mut sum = 0.0;
    for hemisphere in [-1.0f64, 1.0] {
        for (x, wx) in &mu_rule {
            let mu = hemisphere * 0.5 * (x + 1.0);
            let sin = (1.0 - mu * mu).max(0.0).sqrt();
            for (y, wy) in &phi_rule {
                let phi = std::f64::consts::PI * (y + 1.0);
                let w = Vec3::new((sin * phi.cos()) as f32, (sin * phi.sin()) as f32, mu as f32);
                sum += wx * wy * f(w);
            }
        }
    }
    sum * 0.5 * std::f64::consts::PI
}

fn white_conductor(d: Microfacet) -> Material {
    // η = 0, k = 1 gives F = 1 at every angle (Mitsuba's `none`).
    Material::RoughConductor(RoughConductor {
        distribution: d,
        eta: Rgb::splat(0.0),
        k: Rgb::splat(1.0),
        reflectance: Rgb::WHITE,
    })
}

fn gold(d: Microfacet) -> Material {
    let (eta, k) = pathtrace::material::metal("Au").unwrap();
    Material::RoughConductor(RoughConductor {
        distribution: d,
        eta: Rgb::from_array(eta),
        k: Rgb::from_array(k),
        reflectance: Rgb::WHITE,
    })
}

fn glass(d: Microfacet) -> Material {
    Material::RoughDielectric(RoughDielectric { distribution: d, ior: 1.5, tint: Rgb::WHITE })
}

/// Every new non-Dirac model, at several roughnesses (isotropic and anisotropic).
fn models() -> Vec<Material> {
    vec![
        gold(Microfacet::isotropic(GGX, 0.3)),
        white_conductor(Microfacet::new(GGX, 0.2, 0.6)),
        white_conductor(Microfacet::isotropic(BECKMANN, 0.5)),
        gold(Microfacet::new(BECKMANN, 0.6, 0.25)),
        glass(Microfacet::isotropic(GGX, 0.3)),
        glass(Microfacet::new(BECKMANN, 0.2, 0.5)),
        Material::RoughPlastic(RoughPlastic::new(
            Microfacet::isotropic(GGX, 0.3),
            Rgb::new(0.2, 0.5, 0.8),
            Rgb::WHITE,
            1.49,
            false,
        )),
        Material::RoughPlastic(RoughPlastic::new(
            Microfacet::isotropic(BECKMANN, 0.4),
            Rgb::splat(0.5),
            Rgb::WHITE,
            1.6,
            true,
        )),
        Material::Plastic(Plastic::new(Rgb::new(0.3, 0.6, 0.1), Rgb::WHITE, 1.49, false)),
    ]
}

/// Viewing directions: above the surface, and for glass also from inside.
fn views(m: &Material) -> Vec<Vec3> {
    let mut v = vec![dir(0.0, 0.0), dir(40.0, 30.0), dir(75.0, 200.0)];
    if !m.is_two_sided() {
        v.push(-dir(25.0, 100.0));
        v.push(-dir(60.0, 300.0)); // beyond the critical angle of 1.5 for most facets
    }
    v
}

/// The lobe number: fixed per test sample so the 2D sampler sees uniform points.
fn lobe_sampler(seed: u64) -> impl FnMut() -> f32 {
    let mut rng = TestRng::new(seed);
    move || rng.next_f32()
}

#[test]
fn sampling_matches_the_pdf_and_the_pdf_integrates_to_one() {
    for m in models() {
        for wo in views(&m) {
            let pdf = |wi: Vec3| m.pdf(wo, wi) as f64;
            let integral = sphere_integral(pdf);
            // The pdf covers the samples that leave in a smooth lobe: not plastic's Dirac coating,
            // nor directions a microfacet reflects below the horizon (sampling fails there). So
            // ∫pdf must equal the fraction of such samples, counted here independently.
            let mut next = lobe_sampler(3);
            let mut rng = TestRng::new(4);
            let n = 200_000;
            let smooth = (0..n)
                .filter(|_| {
                    let u = Vec2::new(rng.next_f32(), rng.next_f32());
                    m.sample(wo, next(), u).is_some_and(|s| !s.delta)
                })
                .count();
            let expected = smooth as f64 / n as f64;
            assert!(
                (integral - expected).abs() < 3e-3,
                "{} at wo={wo}: ∫pdf = {integral}, expected {expected}",
                m.name()
            );
            let mut next = lobe_sampler(11);
            let test = ChiSquareTest { samples: 300_000, integration_res: 8, ..Default::default() };
            let outcome = test.run(
                |u| m.sample(wo, next(), Vec2::new(u[0] as f32, u[1] as f32)).filter(|s| !s.delta).map(|s| s.wi),
                pdf,
            );
            assert!(outcome.passed, "{} at wo={wo}: chi-square rejected\n{}", m.name(), outcome.summary());
        }
    }
}

#[test]
fn sample_weights_equal_f_cos_over_pdf() {
    let mut rng = TestRng::new(5);
    for m in models() {
        for wo in views(&m) {
            for _ in 0..3000 {
                let u = Vec2::new(rng.next_f32(), rng.next_f32());
                let Some(s) = m.sample(wo, rng.next_f32(), u) else { continue };
                if s.delta {
                    continue;
                }
                let pdf = m.pdf(wo, s.wi);
                let expected = m.eval(wo, s.wi) * (1.0 / pdf);
                let err = (s.weight - expected).max_component().abs();
                assert!(
                    err <= 2e-3 * expected.max_component().max(1e-3),
                    "{}: {:?} vs {:?}",
                    m.name(),
                    s.weight,
                    expected
                );
                assert!((s.pdf - pdf).abs() <= 2e-3 * pdf, "{}: pdf {} vs {}", m.name(), s.pdf, pdf);
            }
        }
    }
}

/// Index of refraction on the side of `w` for the glass in [`models`] (1.5 inside).
fn index_at(m: &Material, w: Vec3) -> f32 {
    if m.is_two_sided() || w.z > 0.0 {
        1.0
    } else {
        1.5
    }
}

#[test]
fn models_are_reciprocal() {
    let mut rng = TestRng::new(8);
    for m in models() {
        let mut checked = 0;
        for _ in 0..4000 {
            let mut a = pathtrace::sampling::warp::square_to_uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32()));
            let mut b = pathtrace::sampling::warp::square_to_uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32()));
            if m.is_two_sided() {
                a.z = a.z.abs();
                b.z = b.z.abs();
            }
            if a.z.abs() < 1e-2 || b.z.abs() < 1e-2 {
                continue;
            }
            // f(a→b) = eval(a, b)/|cos θb|; for glass f(a, b)/η_a² = f(b, a)/η_b² (Veach's thesis
            // eq. 5.14: the radiance scaling makes the BTDF reciprocal only in this form).
            let fab = m.eval(a, b) * (1.0 / (b.z.abs() * index_at(&m, a).powi(2)));
            let fba = m.eval(b, a) * (1.0 / (a.z.abs() * index_at(&m, b).powi(2)));
            let scale = fab.max_component().max(fba.max_component());
            // Relative to values of at least 1e-2: f32 rounding in the refraction half vector
            // leaves ~3e-3 relative noise on values near 1e-4.
            assert!((fab - fba).max_component().abs() <= 2e-3 * scale.max(1e-2), "{}: {fab:?} vs {fba:?}", m.name());
            checked += (scale > 0.0) as usize;
        }
        assert!(checked > 500, "{}: only {checked} non-zero pairs", m.name());
    }
}

#[test]
fn no_model_reflects_more_than_it_receives() {
    for m in models() {
        for wo in views(&m) {
            // ∫ f cos dωi (eval includes the cosine); for glass count transmitted flux, i.e.
            // undo the radiance scaling by (η_wi/η_wo)².
            let albedo = sphere_integral(|wi| {
                let scale = (index_at(&m, wi) / index_at(&m, wo)).powi(2);
                (m.eval(wo, wi).max_component() * scale) as f64
            });
            // Plastic's Dirac coating reflects F(cos θo) on top.
            let coat = match m {
                Material::Plastic(_) => pathtrace::material::fresnel_dielectric(wo.z, 1.49).0 as f64,
                _ => 0.0,
            };
            assert!(albedo + coat <= 1.0 + 2e-3, "{} at wo={wo}: albedo {}", m.name(), albedo + coat);
        }
    }
}

/// Directional albedo of the F = 1 GGX conductor by quadrature of its BRDF, and by Monte Carlo
/// over its own samples: they must agree within the Monte Carlo confidence interval. At α = 1
/// and normal incidence it has a closed form: D = 1/π for every m, only facets within 45° of
/// the normal reflect above the horizon, G1(wi) = 2 cos θi/(1 + cos θi) with cos θi = 2μ² − 1
/// (μ = cos θm), so E = ∫ D G1 μ dωm = 2∫_{1/√2}^1 (2μ − 1/μ) dμ = 1 − ln 2 ≈ 0.3069: single
/// scattering loses 69% of the energy there.
#[test]
fn perfect_rough_conductor_loses_exactly_the_single_scattering_deficit() {
    let mut rng = TestRng::new(21);
    for (alpha, theta) in [(1.0f32, 0.0f32), (1.0, 60.0), (0.5, 0.0), (0.3, 70.0)] {
        let m = white_conductor(Microfacet::isotropic(GGX, alpha));
        let wo = dir(theta, 0.0);
        let quadrature = sphere_integral(|wi| m.eval(wo, wi).g as f64);
        let n = 400_000;
        let samples: Vec<f64> = (0..n)
            .map(|_| {
                let u = Vec2::new(rng.next_f32(), rng.next_f32());
                m.sample(wo, 0.5, u).map_or(0.0, |s| s.weight.g as f64)
            })
            .collect();
        let mc = MeanEstimate::from_samples(&samples);
        let z = (mc.mean - quadrature) / mc.std_error();
        assert!(
            z.abs() < 4.0,
            "α={alpha} θ={theta}: Monte Carlo {} ± {} vs quadrature {quadrature}",
            mc.mean,
            mc.std_error()
        );
        assert!(quadrature < 1.0);
        if alpha == 1.0 && theta == 0.0 {
            let exact = 1.0 - std::f64::consts::LN_2;
            assert!((quadrature - exact).abs() < 1e-4, "GGX α=1 albedo {quadrature} vs 1 − ln 2");
            let z_exact = (mc.mean - exact) / mc.std_error();
            assert!(z_exact.abs() < 4.0, "GGX α=1: Monte Carlo {} vs 1 − ln 2 (z = {z_exact})", mc.mean);
        }
    }
}
