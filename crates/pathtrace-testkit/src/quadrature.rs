//! Numerical integration of densities over the unit sphere.
//!
//! Directions are parameterised by `u = cos θ ∈ [-1, 1]` (θ from +z) and
//! `φ ∈ [0, 2π)`; the solid-angle element is then simply `dω = du dφ`, so a
//! rectangle in `(u, φ)` has area equal to its solid angle.

use glam::Vec3;
use std::cell::Cell;
use std::f64::consts::TAU;

/// Accuracy controls for [`integrate_region`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Quadrature {
    /// Initial segments per axis, each then refined adaptively.
    pub segments: usize,
    /// Absolute error tolerance for the whole region's integral.
    pub tolerance: f64,
    /// Relative error tolerance of each piece (keeps refinement above rounding noise).
    pub relative: f64,
    /// Maximum bisection depth of each adaptive segment.
    pub max_depth: u32,
    /// Maximum number of integrand evaluations for the whole region (a safety net
    /// against integrands that never meet the tolerance, e.g. discontinuous ones).
    pub max_evaluations: u64,
}

impl Default for Quadrature {
    fn default() -> Self {
        Quadrature {
            segments: 4,
            tolerance: 1e-10,
            // Densities take `f32` directions, whose rounding makes a peaked lobe
            // noisy at about 1e-5 relative; asking for much less only burns budget.
            relative: 1e-6,
            max_depth: 24,
            max_evaluations: 4_000_000,
        }
    }
}

/// The unit direction with `cos θ = u` and azimuth `phi`.
pub(crate) fn direction(u: f64, phi: f64) -> Vec3 {
    let u = u.clamp(-1.0, 1.0);
    let sin_theta = (1.0 - u * u).max(0.0).sqrt();
    Vec3::new((sin_theta * phi.cos()) as f32, (sin_theta * phi.sin()) as f32, u as f32)
}

/// ∫∫ pdf(ω) dω over `u ∈ [u0, u1]`, `φ ∈ [phi0, phi1]`, by nested adaptive Simpson.
pub(crate) fn integrate_region(
    pdf: &dyn Fn(Vec3) -> f64,
    (u0, u1): (f64, f64),
    (phi0, phi1): (f64, f64),
    q: Quadrature,
) -> f64 {
    let budget = Cell::new(q.max_evaluations);
    // An error ε in the inner integral adds at most ε·(u1 − u0) to the outer one.
    let inner_q = Quadrature { tolerance: 0.5 * q.tolerance / (u1 - u0).abs().max(1e-300), ..q };
    let inner = |u: f64| adaptive_simpson(&|phi| pdf(direction(u, phi)), (phi0, phi1), inner_q, &budget);
    adaptive_simpson(&inner, (u0, u1), q, &budget)
}

/// ∫ `pdf` dω over the whole sphere.
///
/// The sphere is cut into `theta_res × phi_res` cells, equal in `cos θ` and `φ` (so of
/// equal solid angle), and each cell is integrated by nested adaptive Simpson
/// quadrature (4 initial segments per axis, absolute tolerance 1e-10 overall, relative
/// 1e-6 per piece). Narrow peaks such as a Phong lobe with exponent 1000 are resolved
/// as long as the initial samples (8 per cell per axis) see part of them. Zero
/// resolutions count as 1.
pub fn integrate_over_sphere(pdf: impl Fn(Vec3) -> f64, theta_res: usize, phi_res: usize) -> f64 {
    let (nu, nphi) = (theta_res.max(1), phi_res.max(1));
    let q = Quadrature { tolerance: 1e-10 / (nu * nphi) as f64, ..Quadrature::default() };
    let mut total = 0.0;
    for i in 0..nu {
        let u_range = cell_range(i, nu, -1.0, 2.0);
        for j in 0..nphi {
            total += integrate_region(&pdf, u_range, cell_range(j, nphi, 0.0, TAU), q);
        }
    }
    total
}

/// The `i`-th of `n` equal sub-intervals of `[start, start + length]`.
pub(crate) fn cell_range(i: usize, n: usize, start: f64, length: f64) -> (f64, f64) {
    let step = length / n as f64;
    (start + i as f64 * step, start + (i + 1) as f64 * step)
}

/// ∫ f over `[a, b]`: `q.segments` equal segments, each by adaptive Simpson quadrature
/// (Lyness, "Notes on the adaptive Simpson quadrature routine", JACM 1969), with the
/// tolerance shared out evenly and Richardson's correction (S₂ + (S₂ − S₁)/15).
/// Each evaluation of `f` takes one unit of `budget`; at zero, refinement stops.
pub(crate) fn adaptive_simpson(f: &dyn Fn(f64) -> f64, (a, b): (f64, f64), q: Quadrature, budget: &Cell<u64>) -> f64 {
    let n = q.segments.max(1);
    let piece = Quadrature { tolerance: q.tolerance / n as f64, ..q };
    (0..n)
        .map(|i| {
            let (lo, hi) = cell_range(i, n, a, b - a);
            spend(budget, 3);
            let (flo, fmid, fhi) = (f(lo), f(0.5 * (lo + hi)), f(hi));
            let whole = simpson(lo, hi, flo, fmid, fhi);
            refine(f, (lo, hi), (flo, fmid, fhi), whole, piece, q.max_depth, budget)
        })
        .sum()
}

/// Takes `n` units from `budget` (saturating at zero).
fn spend(budget: &Cell<u64>, n: u64) {
    budget.set(budget.get().saturating_sub(n));
}

/// Simpson's rule on `[a, b]` from the values at `a`, the midpoint and `b`.
fn simpson(a: f64, b: f64, fa: f64, fm: f64, fb: f64) -> f64 {
    (b - a) / 6.0 * (fa + 4.0 * fm + fb)
}

/// One adaptive Simpson step: compare the whole-interval estimate with the sum of the
/// two halves, and bisect until they agree to `15 · tolerance` (Lyness's criterion).
fn refine(
    f: &dyn Fn(f64) -> f64,
    (a, b): (f64, f64),
    (fa, fm, fb): (f64, f64, f64),
    whole: f64,
    q: Quadrature,
    depth: u32,
    budget: &Cell<u64>,
) -> f64 {
    let m = 0.5 * (a + b);
    let (lm, rm) = (0.5 * (a + m), 0.5 * (m + b));
    spend(budget, 2);
    let (flm, frm) = (f(lm), f(rm));
    let left = simpson(a, m, fa, flm, fm);
    let right = simpson(m, b, fm, frm, fb);
    let delta = left + right - whole;
    let tolerance = q.tolerance.max(q.relative * (left + right).abs());
    // Non-finite values cannot be refined away: stop rather than bisect forever.
    if depth == 0 || budget.get() == 0 || !delta.is_finite() || delta.abs() <= 15.0 * tolerance {
        return left + right + delta / 15.0;
    }
    let half = Quadrature { tolerance: 0.5 * q.tolerance, ..q };
    refine(f, (a, m), (fa, flm, fm), left, half, depth - 1, budget)
        + refine(f, (m, b), (fm, frm, fb), right, half, depth - 1, budget)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn simpson_1d_polynomial_and_peak() {
        let q = |segments| Quadrature { segments, tolerance: 1e-12, ..Quadrature::default() };
        let budget = Cell::new(u64::MAX);
        let cubic = adaptive_simpson(&|x| x * x * x - x, (0.0, 2.0), q(1), &budget);
        assert!((cubic - 2.0).abs() < 1e-12);
        // A narrow Gaussian of width 1e-3 centred between initial samples.
        let s = 1e-3;
        let g = |x: f64| (-(x - 0.3) * (x - 0.3) / (2.0 * s * s)).exp() / (s * (2.0 * PI).sqrt());
        let v = adaptive_simpson(&g, (0.0, 1.0), q(64), &budget);
        assert!((v - 1.0).abs() < 1e-8, "{v}");
    }

    #[test]
    fn uniform_density_integrates_to_one() {
        let v = integrate_over_sphere(|_| 1.0 / (4.0 * PI), 4, 8);
        assert!((v - 1.0).abs() < 1e-12, "{v}");
        let v = integrate_over_sphere(|_| 1.0 / (4.0 * PI), 0, 0);
        assert!((v - 1.0).abs() < 1e-12, "{v}");
    }

    #[test]
    fn cosine_hemisphere_integrates_to_one() {
        let v = integrate_over_sphere(|w| (f64::from(w.z) / PI).max(0.0), 10, 20);
        assert!((v - 1.0).abs() < 1e-7, "{v}");
    }

    #[test]
    fn phong_1000_lobe_integrates_to_one() {
        // ∫ cos^n α dω over the hemisphere around the axis = 2π/(n + 1).
        let n = 1000.0;
        for axis in [Vec3::new(0.3, -0.5, 0.8).normalize(), Vec3::Z, -Vec3::X] {
            let lobe = |w: Vec3| (n + 1.0) / (2.0 * PI) * f64::from(w.dot(axis)).max(0.0).powf(n);
            let v = integrate_over_sphere(lobe, 10, 20);
            // f32 rounding of the axis alone shifts cos^1000 by ~1e-4.
            assert!((v - 1.0).abs() < 2e-4, "{axis}: {v}");
        }
    }

    #[test]
    fn budget_stops_runaway_refinement() {
        // A zero tolerance is (almost) never met, but the budget ends the work.
        let q = Quadrature { tolerance: 0.0, relative: 0.0, max_depth: 60, max_evaluations: 1000, segments: 1 };
        let budget = Cell::new(q.max_evaluations);
        let v = adaptive_simpson(&|x: f64| x.sin(), (0.0, 1.0), q, &budget);
        assert!((v - (1.0 - 1f64.cos())).abs() < 1e-6, "{v}");
        assert_eq!(budget.get(), 0);
    }

    #[test]
    fn direction_is_unit_and_oriented() {
        assert!((direction(1.0, 0.3) - Vec3::Z).length() < 1e-6);
        assert!((direction(0.0, 0.0) - Vec3::X).length() < 1e-6);
        assert!((direction(0.0, PI / 2.0) - Vec3::Y).length() < 1e-6);
        assert!((direction(0.3, 2.0).length() - 1.0).abs() < 1e-6);
    }
}
