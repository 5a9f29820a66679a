//! Thin-lens and orthographic cameras: the lens disk is sampled uniformly (chi-square over
//! equal-area cells), a point on the plane of focus is reached from one pixel whatever the lens
//! point (and a point off it is blurred by exactly the thin-lens circle of confusion), and the
//! orthographic camera's rays are parallel and tile a `height` × aspect rectangle.

use pathtrace::camera::CameraError;
use pathtrace::math::{Ray, Vec2, Vec3};
use pathtrace::{Camera, CameraDesc, Lens};
use pathtrace_testkit::{chi_square_p_value, TestRng};

const APERTURE: f32 = 20.0;
const FOCUS: f32 = 600.0;

/// The Cornell view (looking along +z from z = −800) through a thin lens.
fn thin_lens() -> CameraDesc {
    CameraDesc {
        look_from: Vec3::new(278.0, 273.0, -800.0),
        look_at: Vec3::new(278.0, 273.0, 0.0),
        lens: Lens::ThinLens { aperture_radius: APERTURE, focus_distance: FOCUS },
        ..Default::default()
    }
}

/// Where `ray` meets the plane z = `z`.
fn at_depth(ray: &Ray, z: f32) -> Vec3 {
    ray.at((z - ray.origin.z) / ray.dir.z)
}

fn v2(u: [f64; 2]) -> Vec2 {
    Vec2::new(u[0] as f32, u[1] as f32)
}

/// Chi-square statistic of lens points (in units of the aperture radius) over 8 rings of equal
/// area × 16 sectors: every cell has probability 1/128 under a uniform disk.
fn disk_cells_p_value(points: impl Iterator<Item = (f32, f32)>) -> f64 {
    const RINGS: usize = 8;
    const SECTORS: usize = 16;
    let mut counts = [0u32; RINGS * SECTORS];
    let mut n = 0u32;
    for (x, y) in points {
        let r2 = (x * x + y * y) as f64;
        assert!(r2 <= 1.0 + 1e-4, "lens point ({x}, {y}) outside the aperture");
        let ring = ((r2 * RINGS as f64) as usize).min(RINGS - 1);
        let phi = (y as f64).atan2(x as f64).rem_euclid(std::f64::consts::TAU);
        let sector = ((phi / std::f64::consts::TAU * SECTORS as f64) as usize).min(SECTORS - 1);
        counts[ring * SECTORS + sector] += 1;
        n += 1;
    }
    let expected = n as f64 / (RINGS * SECTORS) as f64;
    let stat: f64 = counts.iter().map(|&c| (c as f64 - expected).powi(2) / expected).sum();
    chi_square_p_value(stat, RINGS * SECTORS - 1)
}

#[test]
fn thin_lens_samples_its_aperture_uniformly() {
    let cam = Camera::new(&thin_lens(), 64, 64).unwrap();
    let mut rng = TestRng::new(7);
    let origin = thin_lens().look_from;
    let points: Vec<(f32, f32)> = (0..200_000)
        .map(|_| {
            let ray = cam.generate_ray(20, 40, Vec2::splat(0.5), v2(rng.next_2d()));
            // The lens lies in the plane z = −800; its axes are ±x and y.
            assert!((ray.origin.z - origin.z).abs() < 1e-3);
            ((ray.origin.x - origin.x) / APERTURE, (ray.origin.y - origin.y) / APERTURE)
        })
        .collect();
    let p = disk_cells_p_value(points.iter().copied());
    assert!(p > 1e-3, "chi-square rejects the lens sampling: p = {p}");
    // The test can fail: a disk sampled with r = u (too many points near the centre) is rejected.
    let mut rng = TestRng::new(8);
    let biased = (0..200_000).map(|_| {
        let [u, v] = rng.next_2d();
        let phi = v * std::f64::consts::TAU;
        ((u * phi.cos()) as f32, (u * phi.sin()) as f32)
    });
    assert!(disk_cells_p_value(biased) < 1e-6);
}

#[test]
fn a_point_on_the_plane_of_focus_comes_from_one_pixel() {
    let (w, h) = (64, 48);
    let cam = Camera::new(&thin_lens(), w, h).unwrap();
    let pinhole = Camera::new(&CameraDesc { lens: Lens::Pinhole, ..thin_lens() }, w, h).unwrap();
    let focus_z = thin_lens().look_from.z + FOCUS;
    let mut rng = TestRng::new(3);
    for (x, y) in [(0, 0), (31, 20), (63, 47), (10, 40)] {
        let jitter = v2(rng.next_2d());
        let sharp = at_depth(&pinhole.generate_ray(x, y, jitter, Vec2::splat(0.5)), focus_z);
        let pixel_size = 2.0 * (20f32.to_radians()).tan() * FOCUS / h as f32;
        for _ in 0..256 {
            let ray = cam.generate_ray(x, y, jitter, v2(rng.next_2d()));
            let p = at_depth(&ray, focus_z);
            // Every lens point reaches the pinhole's point: well inside one pixel (relative f32 error).
            assert!((p - sharp).length() < 1e-3 * pixel_size, "pixel ({x}, {y}): {p:?} vs {sharp:?}");
            // Off the plane of focus the rays spread over the thin-lens circle of confusion:
            // a lens point at offset L reaches the depth z at offset L·(1 − d/f) from the sharp ray,
            // d being z's distance from the lens.
            let d = 1.5 * FOCUS;
            let off = at_depth(&ray, thin_lens().look_from.z + d);
            let sharp_off =
                at_depth(&pinhole.generate_ray(x, y, jitter, Vec2::splat(0.5)), thin_lens().look_from.z + d);
            let lens_offset = ray.origin - thin_lens().look_from;
            let expected = lens_offset * (1.0 - d / FOCUS);
            assert!((off - sharp_off - expected).length() < 1e-2, "{off:?} {sharp_off:?} {expected:?}");
        }
    }
}

#[test]
fn orthographic_rays_are_parallel_and_span_the_view() {
    let desc = CameraDesc {
        look_from: Vec3::new(1.0, 2.0, -5.0),
        look_at: Vec3::new(1.0, 2.0, 0.0),
        lens: Lens::Orthographic { height: 4.0 },
        ..Default::default()
    };
    let cam = Camera::new(&desc, 200, 100).unwrap();
    let corner = |x, y, j: f32| cam.generate_ray(x, y, Vec2::splat(j), Vec2::splat(0.5));
    for ray in [corner(0, 0, 0.0), corner(199, 99, 1.0), corner(100, 50, 0.5)] {
        assert!((ray.dir - Vec3::Z).length() < 1e-6, "{:?}", ray.dir);
        assert!((ray.origin.z + 5.0).abs() < 1e-6);
    }
    // The view is 4 high and 8 wide (aspect 2), centred on look-from; +x is on the image's left
    // (u = up × w), as for the pinhole.
    let top_left = corner(0, 0, 0.0).origin;
    let bottom_right = corner(199, 99, 1.0).origin;
    assert!((top_left - Vec3::new(5.0, 4.0, -5.0)).length() < 1e-5, "{top_left:?}");
    assert!((bottom_right - Vec3::new(-3.0, 0.0, -5.0)).length() < 1e-5, "{bottom_right:?}");
}

#[test]
fn bad_lens_parameters_are_errors() {
    let with = |lens| Camera::new(&CameraDesc { lens, ..thin_lens() }, 8, 8);
    assert_eq!(with(Lens::ThinLens { aperture_radius: -1.0, focus_distance: 1.0 }), Err(CameraError::Aperture(-1.0)));
    assert_eq!(
        with(Lens::ThinLens { aperture_radius: 1.0, focus_distance: 0.0 }),
        Err(CameraError::FocusDistance(0.0))
    );
    assert_eq!(with(Lens::Orthographic { height: 0.0 }), Err(CameraError::ViewHeight(0.0)));
    assert_eq!(with(Lens::ThinLens { aperture_radius: f32::NAN, focus_distance: 1.0 }), Err(CameraError::NotFinite));
}
