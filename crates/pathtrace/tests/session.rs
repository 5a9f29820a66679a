//! The render session: waves, progress, cancel, time limits.

use pathtrace::light::Emission;
use pathtrace::material::{Lambertian, Material};
use pathtrace::math::{Rgb, Transform, Vec3};
use pathtrace::render::RenderError;
use pathtrace::shape::{Shape, Sphere};
use pathtrace::{AdaptiveSettings, CameraDesc, RenderSession, RenderSettings, Scene, SceneBuilder};
use std::sync::Arc;
use std::time::Duration;

fn scene() -> Arc<Scene> {
    let mut b = SceneBuilder::new();
    let wall = b.material_with_emission(
        Material::Lambertian(Lambertian { albedo: Rgb::splat(0.5) }),
        Emission { radiance: Rgb::splat(1.0), two_sided: true },
    );
    b.shape(Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0).unwrap()), wall, &Transform::IDENTITY).unwrap();
    b.camera(CameraDesc { look_at: Vec3::X, ..Default::default() });
    Arc::new(b.build().unwrap())
}

#[test]
fn a_finished_render_holds_exactly_the_requested_samples() {
    let s = RenderSettings { width: 20, height: 10, spp: 37, ..Default::default() };
    let out = RenderSession::start(scene(), s).unwrap().wait();
    assert_eq!(out.film.spp_range(), (37, 37));
    assert_eq!(out.progress.spp_done, 37);
    assert_eq!(out.progress.samples, 20 * 10 * 37);
    assert!(out.progress.finished && !out.progress.cancelled);
    assert_eq!(out.progress.rays.camera_rays, 20 * 10 * 37);
    // Progress reports the film's noise estimate after each whole wave; no target without one.
    assert_eq!(out.progress.error_estimate, out.film.relative_rms_error_estimate());
    assert!(out.progress.error_estimate.is_some_and(|e| e > 0.0));
    assert_eq!(out.progress.target_error, None);
}

#[test]
fn cancel_keeps_what_was_rendered() {
    let s = RenderSettings { width: 64, height: 64, spp: 1_000_000, ..Default::default() };
    let session = RenderSession::start(scene(), s).unwrap();
    while session.progress().spp_done < 2 {
        std::thread::sleep(Duration::from_millis(5));
    }
    session.cancel();
    let out = session.wait();
    let (lo, hi) = out.film.spp_range();
    assert!(lo >= 2 && hi < 1_000_000, "{lo}..{hi}");
    assert!(out.progress.cancelled);
    // What was kept is a valid estimate: L = E/(1-a) = 2 in this furnace.
    let est = out.film.region_estimate(0, 0, 64, 64);
    assert!((est.mean[1] - 2.0).abs() < 0.2, "{:?}", est.mean);
}

#[test]
fn an_open_ended_render_needs_a_budget_and_a_target_error_is_one() {
    let s = RenderSettings { width: 8, height: 8, spp: 0, ..Default::default() };
    assert!(matches!(RenderSession::start(scene(), s.clone()), Err(RenderError::NoBudget)));
    let adaptive = AdaptiveSettings { min_spp: 4, target_error: Some(0.2), ..Default::default() };
    let out = RenderSession::start(scene(), RenderSettings { adaptive: Some(adaptive), ..s }).unwrap().wait();
    assert!(out.progress.finished && out.progress.error_estimate.is_some_and(|e| e <= 0.2));
}

#[test]
fn time_limits_stop_open_ended_renders() {
    let s = RenderSettings {
        width: 32,
        height: 32,
        spp: 0,
        time_limit: Some(Duration::from_millis(300)),
        ..Default::default()
    };
    let out = RenderSession::start(scene(), s).unwrap().wait();
    assert!(out.progress.elapsed < Duration::from_secs(5));
    assert!(out.film.spp_range().0 >= 1);
}

#[test]
fn snapshots_are_available_while_rendering() {
    let s = RenderSettings { width: 16, height: 16, spp: 64, ..Default::default() };
    let session = RenderSession::start(scene(), s).unwrap();
    let img = session.snapshot();
    assert_eq!((img.width, img.height), (16, 16));
    let out = session.wait();
    assert!(out.film.image().pixels.iter().all(|p| p.g > 0.0));
}

#[test]
fn a_render_needs_a_budget_and_a_valid_camera() {
    let s = RenderSettings { spp: 0, time_limit: None, ..Default::default() };
    assert!(matches!(RenderSession::start(scene(), s), Err(RenderError::NoBudget)));
    let s = RenderSettings { width: 0, ..Default::default() };
    assert!(matches!(RenderSession::start(scene(), s), Err(RenderError::Camera(_))));
}

/// An emissive ball off to the side, so where the camera looks changes the image.
fn ball_scene(camera: CameraDesc) -> Arc<Scene> {
    let mut b = SceneBuilder::new();
    let lamp = b.emissive(Emission { radiance: Rgb::splat(1.0), two_sided: true });
    b.shape(Shape::Sphere(Sphere::new(Vec3::new(1.0, 0.0, 0.0), 0.5).unwrap()), lamp, &Transform::IDENTITY).unwrap();
    b.camera(camera);
    Arc::new(b.build().unwrap())
}

#[test]
fn a_camera_override_renders_as_if_the_scene_had_that_camera() {
    let a = CameraDesc { look_from: Vec3::new(0.0, 0.0, 5.0), look_at: Vec3::ZERO, ..Default::default() };
    let b = CameraDesc { look_at: Vec3::new(2.0, 0.5, 0.0), ..a };
    let s = RenderSettings { width: 24, height: 16, spp: 4, ..Default::default() };
    let render = |scene: Arc<Scene>, camera: Option<&CameraDesc>| {
        let session = match camera {
            Some(c) => RenderSession::start_with_camera(scene, c, s.clone()),
            None => RenderSession::start(scene, s.clone()),
        };
        session.unwrap().wait().film.image()
    };
    let overridden = render(ball_scene(a), Some(&b));
    assert_eq!(overridden, render(ball_scene(b), None));
    assert_ne!(overridden, render(ball_scene(a), None));
}

#[test]
fn wait_finished_times_out_while_running_and_returns_once_ended() {
    let s = RenderSettings { width: 64, height: 64, spp: 1_000_000, ..Default::default() };
    let session = RenderSession::start(scene(), s).unwrap();
    let end = session.end_signal();
    assert!(!session.wait_finished(Duration::from_millis(20)), "a million spp takes longer");
    assert!(!end.wait(Duration::ZERO) && !session.is_finished());
    session.cancel();
    // Wakes on the end (well before the generous timeout), with the session then finished.
    let began = std::time::Instant::now();
    assert!(end.wait(Duration::from_secs(60)));
    assert!(began.elapsed() < Duration::from_secs(30));
    assert!(session.is_finished() && session.wait_finished(Duration::ZERO));
    assert!(session.wait().progress.cancelled);
}
