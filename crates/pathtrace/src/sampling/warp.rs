//! Warps from the unit square `[0,1)²` to disks, hemispheres, spheres, cones and triangles,
//! each with the density it produces (solid-angle pdfs for directions, with +z as the pole).
//!
//! Tested in `tests/warps.rs`: every pdf integrates to 1 and a chi-square test accepts each
//! sampler against its pdf.

use crate::math::{Vec2, Vec3, INV_2PI, INV_4PI, INV_PI};
use crate::wide::simd::{F32s, Ms};
use crate::wide::warp as lanes;

/// Concentric map from square to unit disk (Shirley & Chiu, "A Low Distortion Map Between Disk
/// and Square", JGT 1997); uniform density 1/π. The one-lane instance of the lane-parallel map.
pub fn square_to_uniform_disk(u: Vec2) -> Vec2 {
    let (x, y) = lanes::square_to_uniform_disk(F32s([u.x]), F32s([u.y]));
    Vec2::new(x.0[0], y.0[0])
}

/// Uniform direction on the unit sphere: z = 1 - 2u, φ = 2πv; pdf = 1/(4π). The one-lane
/// instance of the lane-parallel warp.
pub fn square_to_uniform_sphere(u: Vec2) -> Vec3 {
    lanes::square_to_uniform_sphere(F32s([u.x]), F32s([u.y])).lane(0)
}

pub fn uniform_sphere_pdf() -> f32 {
    INV_4PI
}

/// Uniform direction on the upper hemisphere (z ≥ 0): z = u, φ = 2πv; pdf = 1/(2π).
pub fn square_to_uniform_hemisphere(u: Vec2) -> Vec3 {
    lanes::square_to_uniform_hemisphere(F32s([u.x]), F32s([u.y]), Ms::ALL).lane(0)
}

pub fn uniform_hemisphere_pdf(w: Vec3) -> f32 {
    if w.z >= 0.0 {
        INV_2PI
    } else {
        0.0
    }
}

/// Cosine-weighted hemisphere by Malley's method (project a uniform disk point up);
/// pdf = cos θ / π. The one-lane instance of the lane-parallel warp.
pub fn square_to_cosine_hemisphere(u: Vec2) -> Vec3 {
    lanes::square_to_cosine_hemisphere(F32s([u.x]), F32s([u.y])).lane(0)
}

pub fn cosine_hemisphere_pdf(w: Vec3) -> f32 {
    cosine_hemisphere_pdf_lanes(F32s([w.z])).0[0]
}

/// [`cosine_hemisphere_pdf`] in every lane, from the directions' cos θ.
#[inline(always)]
pub fn cosine_hemisphere_pdf_lanes<const N: usize>(cos_theta: F32s<N>) -> F32s<N> {
    F32s::select(cos_theta.gt(F32s::ZERO), cos_theta * INV_PI, F32s::ZERO)
}

/// Uniform direction in the cone of half-angle θ_max around +z: cos θ = 1 - u(1 - cos θ_max);
/// pdf = 1 / (2π (1 - cos θ_max)).
pub fn square_to_uniform_cone(u: Vec2, cos_theta_max: f32) -> Vec3 {
    lanes::square_to_uniform_cone(F32s([u.x]), F32s([u.y]), F32s([cos_theta_max])).lane(0)
}

pub fn uniform_cone_pdf(w: Vec3, cos_theta_max: f32) -> f32 {
    if w.z >= cos_theta_max && cos_theta_max < 1.0 {
        INV_2PI / (1.0 - cos_theta_max)
    } else {
        0.0
    }
}

/// Power-cosine lobe around +z, density ∝ cosⁿ θ over the sphere cap z > 0:
/// cos θ = u^(1/(n+1)); pdf = (n+1)/(2π) cosⁿ θ (the Phong lobe of Lafortune & Willems 1994).
pub fn square_to_power_cosine(u: Vec2, exponent: f32) -> Vec3 {
    lanes::square_to_power_cosine(F32s([u.x]), F32s([u.y]), F32s([exponent]), Ms::ALL).lane(0)
}

pub fn power_cosine_pdf(w: Vec3, exponent: f32) -> f32 {
    if w.z > 0.0 {
        (exponent + 1.0) * INV_2PI * w.z.powf(exponent)
    } else {
        0.0
    }
}

/// Uniform barycentric coordinates (b1, b2) on a triangle (the square-root parameterisation,
/// pbrt-v3 §13.6.4); the point is (1-b1-b2)·p0 + b1·p1 + b2·p2 with density 1/area.
pub fn square_to_uniform_triangle(u: Vec2) -> Vec2 {
    let (a, b) = lanes::square_to_uniform_triangle(F32s([u.x]), F32s([u.y]));
    Vec2::new(a.0[0], b.0[0])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn disk_points_lie_in_the_unit_disk() {
        for i in 0..32 {
            for j in 0..32 {
                let p = square_to_uniform_disk(Vec2::new(i as f32 / 31.0, j as f32 / 31.0));
                assert!(p.length() <= 1.0 + 1e-6);
            }
        }
    }

    #[test]
    fn triangle_barycentrics_stay_inside() {
        for i in 0..32 {
            for j in 0..32 {
                let b = square_to_uniform_triangle(Vec2::new(i as f32 / 31.0, j as f32 / 31.0));
                assert!(b.x >= 0.0 && b.y >= 0.0 && b.x + b.y <= 1.0 + 1e-6);
            }
        }
    }
}
