//! The building blocks of participating media: phase functions integrate to 1 and are sampled
//! by their own density (chi-square), Henyey–Greenstein's `g` is the mean cosine with Mitsuba's
//! sign (g > 0 scatters forwards), transmittance is exp(−σt·d), and chromatic free-flight
//! sampling is unbiased per channel for both outcomes (crossing a slab, scattering inside it).

use pathtrace::math::{Rgb, Vec2, Vec3};
use pathtrace::medium::{HomogeneousMedium, PhaseFunction};
use pathtrace_testkit::{integrate_over_sphere, ChiSquareTest, TestRng};

fn v2(u: [f64; 2]) -> Vec2 {
    Vec2::new(u[0] as f32, u[1] as f32)
}

/// The path arrives travelling along `travel`; `wo` points back.
fn wo() -> Vec3 {
    -Vec3::new(0.3, -0.5, 0.8).normalize()
}

fn phases() -> Vec<PhaseFunction> {
    let mut v = vec![PhaseFunction::Isotropic];
    v.extend([-0.7, -0.2, 0.0005, 0.3, 0.8, 0.95].map(|g| PhaseFunction::HenyeyGreenstein { g }));
    v
}

#[test]
fn phase_functions_integrate_to_one_and_are_sampled_by_their_density() {
    let test = ChiSquareTest::default();
    for phase in phases() {
        let integral = integrate_over_sphere(|wi| phase.eval(wo(), wi) as f64, 128, 256);
        assert!((integral - 1.0).abs() < 2e-3, "{phase:?}: integrates to {integral}");
        let outcome = test.run(
            |u| {
                let s = phase.sample(wo(), v2(u));
                assert!((s.pdf - phase.eval(wo(), s.wi)).abs() <= 1e-3 * s.pdf, "{phase:?}: pdf {s:?}");
                Some(s.wi)
            },
            |wi| phase.eval(wo(), wi) as f64,
        );
        assert!(outcome.passed, "{phase:?}: chi-square rejects the sampling\n{}", outcome.summary());
    }
    // The chi-square test can fail: HG samples with the sign of g flipped are rejected.
    let hg = PhaseFunction::HenyeyGreenstein { g: 0.5 };
    let flipped = PhaseFunction::HenyeyGreenstein { g: -0.5 };
    let outcome = test.run(|u| Some(flipped.sample(wo(), v2(u)).wi), |wi| hg.eval(wo(), wi) as f64);
    assert!(!outcome.passed, "a mirrored HG lobe went unnoticed");
}

#[test]
fn henyey_greenstein_g_is_the_mean_cosine_forwards() {
    let mut rng = TestRng::new(5);
    let travel = -wo();
    for g in [-0.6f32, 0.0, 0.4, 0.85] {
        let n = 200_000;
        let phase = PhaseFunction::HenyeyGreenstein { g };
        let (mut sum, mut sum2) = (0.0f64, 0.0f64);
        for _ in 0..n {
            let c = phase.sample(wo(), v2(rng.next_2d())).wi.dot(travel) as f64;
            sum += c;
            sum2 += c * c;
        }
        let mean = sum / n as f64;
        let se = ((sum2 / n as f64 - mean * mean) / n as f64).sqrt();
        assert!((mean - g as f64).abs() < 4.0 * se + 1e-4, "g = {g}: mean cosine {mean} ± {se}");
    }
}

#[test]
fn transmittance_through_a_slab_is_beer_lambert() {
    let medium =
        HomogeneousMedium::from_extinction(Rgb::new(0.5, 1.0, 2.0), Rgb::splat(0.8), 1.5, PhaseFunction::Isotropic);
    let sigma_t = medium.sigma_t();
    assert!((sigma_t - Rgb::new(0.75, 1.5, 3.0)).max_component().abs() < 1e-6);
    assert!((medium.sigma_s - Rgb::new(0.6, 1.2, 2.4)).max_component().abs() < 1e-6);
    let d = 0.8;
    let t = medium.transmittance(d).to_array();
    for (k, s) in sigma_t.to_array().into_iter().enumerate() {
        assert!((t[k] - (-s * d).exp()).abs() < 1e-6);
    }
    assert_eq!(medium.transmittance(0.0), Rgb::splat(1.0));
    // A grey medium's free flights cross the slab with probability exp(−σt·d) (binomial z-test).
    let grey = HomogeneousMedium::from_extinction(Rgb::splat(1.3), Rgb::splat(0.5), 1.0, PhaseFunction::Isotropic);
    let mut rng = TestRng::new(9);
    let n = 400_000;
    let crossed = (0..n).filter(|_| !grey.sample_distance(d, rng.next_f32(), rng.next_f32()).scattered).count();
    let p = (-1.3f64 * d as f64).exp();
    let z = (crossed as f64 / n as f64 - p) / (p * (1.0 - p) / n as f64).sqrt();
    assert!(z.abs() < 4.0, "crossed {crossed} of {n}, expected fraction {p}: z = {z}");
}

/// Mean and standard error of each channel of `n` weights.
fn channel_means(n: usize, mut weight: impl FnMut() -> Rgb) -> [(f64, f64); 3] {
    let (mut s, mut s2) = ([0.0f64; 3], [0.0f64; 3]);
    for _ in 0..n {
        for (k, w) in weight().to_array().into_iter().enumerate() {
            s[k] += w as f64;
            s2[k] += (w as f64).powi(2);
        }
    }
    std::array::from_fn(|k| {
        let m = s[k] / n as f64;
        (m, ((s2[k] / n as f64 - m * m) / n as f64).sqrt())
    })
}

#[test]
fn chromatic_free_flight_sampling_is_unbiased_per_channel() {
    // Channels of very different extinction (one clear): following one channel's density and
    // weighting by the channel average must still give each channel its own expectations:
    //   E[weight · 1(crossed)]   = T_c(d)                          = exp(−σt,c·d)
    //   E[weight · 1(scattered)] = ∫₀ᵈ T_c(t)·σs,c dt              = σs,c/σt,c · (1 − exp(−σt,c·d))
    let medium = HomogeneousMedium {
        sigma_a: Rgb::new(0.2, 0.0, 1.0),
        sigma_s: Rgb::new(0.5, 0.0, 3.0),
        phase: PhaseFunction::Isotropic,
    };
    let d = 0.7f32;
    let mut rng = TestRng::new(21);
    let n = 400_000;
    let mut scattered_weights = Vec::with_capacity(n);
    let crossed = channel_means(n, || {
        let f = medium.sample_distance(d, rng.next_f32(), rng.next_f32());
        assert!(f.weight.is_finite() && f.t <= d);
        scattered_weights.push(if f.scattered { f.weight } else { Rgb::BLACK });
        if f.scattered {
            Rgb::BLACK
        } else {
            f.weight
        }
    });
    let mut it = scattered_weights.into_iter();
    let scattered = channel_means(n, || it.next().unwrap());
    let sigma_t = medium.sigma_t().to_array();
    let sigma_s = medium.sigma_s.to_array();
    for k in 0..3 {
        let tr = (-(sigma_t[k] as f64) * d as f64).exp();
        let (m, se) = crossed[k];
        assert!((m - tr).abs() < 4.0 * se + 1e-6, "channel {k} crossing: {m} ± {se} vs {tr}");
        let expected = if sigma_t[k] > 0.0 { sigma_s[k] as f64 / sigma_t[k] as f64 * (1.0 - tr) } else { 0.0 };
        let (m, se) = scattered[k];
        assert!((m - expected).abs() < 4.0 * se + 1e-6, "channel {k} scattering: {m} ± {se} vs {expected}");
    }
}
