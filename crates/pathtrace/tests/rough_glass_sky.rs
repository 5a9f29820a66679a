//! A rough glass sphere under a uniform sky, seen from outside so that it fills the frame.
//!
//! Light reaches the vertices inside the glass only through the interface, so next-event
//! estimation there must connect through it: a light sample on the far side of the surface is
//! a transmission. Every unbiased strategy must give the same mean. When light samples were
//! refused on the far side while MIS still counted their density against the refracted
//! material samples, MIS lost 3.3% of the image at GGX α = 0.5 and 1.6% at α = 0.1 (against
//! material sampling alone and against Mitsuba 3).

use pathtrace::film::RegionEstimate;
use pathtrace::integrator::Strategy;
use pathtrace::light::EnvironmentLight;
use pathtrace::material::{Material, Microfacet, MicrofacetKind, RoughDielectric};
use pathtrace::math::{Rgb, Transform, Vec3};
use pathtrace::shape::{Shape, Sphere};
use pathtrace::{render, CameraDesc, RenderSettings, SceneBuilder};
use std::sync::Arc;

const SIZE: u32 = 24;

fn glass_under_sky(distribution: Microfacet, strategy: Strategy) -> RegionEstimate {
    let mut b = SceneBuilder::new();
    let glass = b.material(Material::RoughDielectric(RoughDielectric { distribution, ior: 1.5, tint: Rgb::WHITE }));
    b.shape(Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0).unwrap()), glass, &Transform::IDENTITY).unwrap();
    b.environment(EnvironmentLight::constant(Rgb::WHITE)).unwrap();
    // 4·tan(10°) = 0.71 < 1: every pixel sees the sphere.
    b.camera(CameraDesc {
        look_from: Vec3::new(0.0, 0.0, 4.0),
        look_at: Vec3::ZERO,
        up: Vec3::Y,
        vfov_degrees: 20.0,
        focal_length: 1.0,
        ..Default::default()
    });
    let scene = Arc::new(b.build().unwrap());
    let mut s = RenderSettings { width: SIZE, height: SIZE, spp: 512, seed: 11, ..Default::default() };
    s.path.strategy = strategy;
    s.path.max_depth = -1;
    let out = render(scene, s).unwrap();
    assert_eq!(out.progress.dropped_samples, 0);
    out.film.region_estimate(0, 0, SIZE, SIZE)
}

#[test]
fn every_unbiased_strategy_sees_the_sky_through_rough_glass_alike() {
    for distribution in
        [Microfacet::isotropic(MicrofacetKind::Ggx, 0.5), Microfacet::isotropic(MicrofacetKind::Beckmann, 0.1)]
    {
        let ests: Vec<_> = [Strategy::Bsdf, Strategy::Mixture, Strategy::Mis, Strategy::MisBalance]
            .iter()
            .map(|&s| (s, glass_under_sky(distribution, s)))
            .collect();
        for (s, est) in &ests {
            // No absorption, and single-scattering microfacets lose some energy: below the
            // sky's 1, and well above 0. Precise enough to tell the 3% the old rule lost at
            // α = 0.5 (measured across seeds: 0.2–0.4% standard error at 512 spp, the mixture
            // the noisiest; Beckmann α = 0.1 about 0.03%).
            assert!(est.mean[0] > 0.5 && est.mean[0] < 1.0, "{distribution:?} {s}: {:?}", est.mean);
            assert!(est.variance_of_mean[0].sqrt() < 0.006 * est.mean[0], "{distribution:?} {s}: too noisy to judge");
        }
        for pair in ests.windows(2) {
            let ((a, ea), (b, eb)) = (&pair[0], &pair[1]);
            let z = ea.max_z_score(eb);
            assert!(z < 4.5, "{distribution:?}: {a} {:?} vs {b} {:?} (z = {z:.2})", ea.mean, eb.mean);
        }
    }
}
