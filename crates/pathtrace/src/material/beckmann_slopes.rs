//! Visible slopes of the α = 1 Beckmann distribution seen from elevation cos θ at azimuth 0
//! (Jakob 2014, "An Improved Visible Normal Sampling Routine for the Beckmann Distribution"),
//! drawn by inverting the marginal CDF of the x slope numerically.
//!
//! Up to its normalisation the CDF of the x slope is C(x) = 1 + erf(x) + tanθ/√π · e^(−x²) for
//! x ≤ cot θ, with C'(x) = 2/√π · e^(−x²) · (1 − x tanθ). Jakob solves C = u in the erf domain
//! (b = erf(x)), where each Newton step costs an inverse erf (a logarithm) and an exponential;
//! here the steps are taken on x itself, where erf(x) and e^(−x²) share one exponential
//! ([`erf_and_gaussian_lanes`]). The start comes from a table of the inverse (in the erf domain,
//! where it is smooth), so that one step usually reaches the tolerance. The table only chooses
//! where Newton's method starts: every answer is iterated, inside a shrinking bracket, until the
//! CDF matches to [`TOLERANCE`] of its range, as before the table.
//!
//! Everything is single precision (as Mitsuba 3's routine is): the CDF's erf is a
//! single-precision approximation anyway, and f32 is the number type of the SIMD lanes.

use std::sync::OnceLock;

use std::f32::consts::FRAC_2_SQRT_PI;

use crate::math::special::{erf_and_gaussian_lanes, erf_fast, erfinv_fast, erfinv_lanes};
use crate::wide::simd::{F32s, Ms};

/// 1/√π.
const FRAC_1_SQRT_PI: f32 = FRAC_2_SQRT_PI / 2.0;

/// Largest allowed |C(x) − u·C(cot θ)| as a fraction of C(cot θ) (the unnormalised CDF lies in
/// [0, C(cot θ)], C(cot θ) ∈ [~2, 2 + tanθ/√π]): 2⁻²¹, eight half-ulps of the range, which the
/// f32 evaluation of C (four roundings) always resolves.
const TOLERANCE: f32 = 1.0 / (1u32 << 21) as f32;

/// The numbers are kept inside [2⁻²⁴, 1 − 2⁻²⁴]: 2u − 1 stays inside (−1, 1) in f32, where the
/// inverse erf is finite (the tails cut off hold 2⁻²³ of the distribution).
const U_MIN: f32 = 1.0 / (1u32 << 24) as f32;

/// Below every slope that matters: C(−8) < 10⁻²⁷ (1 + tanθ/√π), far under the smallest target
/// (u₁ ≥ [`U_MIN`] = 2⁻²⁴), so the root is always above it. Only bisection uses it.
const LOWEST_SLOPE: f32 = -8.0;

/// Past this cos θ the view is normal and the visible slopes are the plain Gaussian ones.
const NORMAL_INCIDENCE: f32 = 0.99999;

/// Rows of the start table: r = √(1 − cos θ) ∈ [0, 1] in `ROWS` steps (linear in θ near
/// normal incidence, where the inverse changes fastest with cos θ).
const ROWS: usize = 64;
/// Columns: s = √(1 − u₁) ∈ [0, 1] in `COLUMNS` steps (the inverse has a square-root tip at
/// u₁ → 1, where C'(x) vanishes at x = cot θ).
const COLUMNS: usize = 64;

/// The x and y slopes for uniform numbers `u1` (x, by inverting C) and `u2` (y, which is
/// independent and Gaussian: y = erfinv(2u₂ − 1)), in the lanes of `lanes` (the others'
/// values are unspecified). The lanes iterate together until the last one has converged; the
/// scalar form is the one-lane instance.
#[inline(always)]
pub(super) fn visible_slopes_lanes<const N: usize>(
    cos_theta: F32s<N>,
    u1: F32s<N>,
    u2: F32s<N>,
    lanes: Ms<N>,
) -> (F32s<N>, F32s<N>) {
    let (lo, hi) = (F32s::splat(U_MIN), F32s::splat(1.0 - U_MIN));
    let u1 = u1.max(lo).min(hi);
    let u2 = u2.max(lo).min(hi);
    let sy = erfinv_lanes(2.0 * u2 - 1.0);
    let normal = cos_theta.gt(F32s::splat(NORMAL_INCIDENCE));
    let gaussian_x = if (lanes & normal).any() { erfinv_lanes(2.0 * u1 - 1.0) } else { F32s::ZERO };
    let oblique = lanes & !normal;
    if !oblique.any() {
        return (gaussian_x, sy);
    }
    let cdf = SlopeCdf::new(cos_theta);
    let table = start_table();
    let mut start_erf = F32s::ZERO;
    for i in oblique.lanes() {
        start_erf.0[i] = table.erf_of_root(cos_theta.0[i], u1.0[i], cdf.erf_max.0[i]);
    }
    let x = cdf.invert(u1, erfinv_lanes(start_erf), oblique);
    (F32s::select(normal, gaussian_x, x), sy)
}

/// [`visible_slopes_lanes`] for one view (tests).
#[cfg(test)]
fn visible_slopes_11(cos_theta: f32, u1: f32, u2: f32) -> (f32, f32) {
    let (x, y) = visible_slopes_lanes(F32s([cos_theta]), F32s([u1]), F32s([u2]), Ms::ALL);
    (x.0[0], y.0[0])
}

/// The unnormalised CDF C of the x slope at one elevation per lane.
struct SlopeCdf<const N: usize> {
    tan_theta: F32s<N>,
    /// tanθ/√π, the weight of the Gaussian term.
    k: F32s<N>,
    /// The largest slope, cot θ, and erf of it.
    x_max: F32s<N>,
    erf_max: F32s<N>,
    /// C(cot θ), the normalisation.
    total: F32s<N>,
}

impl<const N: usize> SlopeCdf<N> {
    #[inline(always)]
    fn new(cos_theta: F32s<N>) -> Self {
        let sin_theta = (1.0 - cos_theta * cos_theta).max(F32s::ZERO).sqrt();
        let tan_theta = sin_theta / cos_theta;
        let x_max = cos_theta / sin_theta;
        let k = tan_theta * FRAC_1_SQRT_PI;
        let (erf_max, gaussian) = erf_and_gaussian_lanes(x_max);
        Self { tan_theta, k, x_max, erf_max, total: 1.0 + erf_max + k * gaussian }
    }

    /// The slope x with C(x) = u·C(cot θ) in each lane of `lanes`, from `start`: Newton's
    /// method on x, kept inside a bracket that every evaluation narrows (C increases on
    /// (−∞, cot θ]), with a bisection step whenever Newton would leave it. A lane stops when it
    /// has converged; the loop, when every lane has.
    #[inline(always)]
    fn invert(&self, u: F32s<N>, start: F32s<N>, lanes: Ms<N>) -> F32s<N> {
        let target = u * self.total;
        let tolerance = TOLERANCE * self.total;
        let (mut lo, mut hi) = (F32s::splat(LOWEST_SLOPE), self.x_max);
        let mut x = start;
        let mut active = lanes;
        for _ in 0..64 {
            // Also true for NaN (a step divided by a vanished derivative).
            let outside = !(x.gt(lo) & x.lt(hi));
            x = F32s::select(active & outside, 0.5 * (lo + hi), x);
            let (erf_x, gaussian) = erf_and_gaussian_lanes(x);
            let value = 1.0 + erf_x + self.k * gaussian - target;
            active = active & !value.abs().lt(tolerance);
            let above = value.gt(F32s::ZERO);
            hi = F32s::select(active & above, x, hi);
            lo = F32s::select(active & !above, x, lo);
            // No f32 left between the bracket's ends.
            active = active & !(hi - lo).le(f32::EPSILON * lo.abs().max(hi.abs()));
            if !active.any() {
                break;
            }
            let derivative = FRAC_2_SQRT_PI * gaussian * (1.0 - x * self.tan_theta);
            x = F32s::select(active, x - value / derivative, x);
        }
        x
    }
}

/// Starting points for [`SlopeCdf::invert`]: at (r, s) the root's erf, as the fraction
/// (erf x + 1)/(erf cot θ + 1) ∈ [0, 1] of its range, bilinearly interpolated.
struct StartTable {
    fraction: Box<[f32]>,
}

fn start_table() -> &'static StartTable {
    static TABLE: OnceLock<StartTable> = OnceLock::new();
    TABLE.get_or_init(StartTable::build)
}

impl StartTable {
    /// Solves every grid point from Jakob's start (exact at grazing incidence: erf x =
    /// erf(cot θ) − (erf(cot θ) + 1)·erf(√(−ln u₁))). About 4,000 solves, a millisecond, once.
    fn build() -> Self {
        let mut fraction = Vec::with_capacity((ROWS + 1) * (COLUMNS + 1));
        for row in 0..=ROWS {
            let r = row as f32 / ROWS as f32;
            let cos_theta = (1.0 - r * r).clamp(1e-4, NORMAL_INCIDENCE);
            let cdf = SlopeCdf::new(F32s([cos_theta]));
            let erf_max = cdf.erf_max.0[0];
            for column in 0..=COLUMNS {
                let s = column as f32 / COLUMNS as f32;
                let u = (1.0 - s * s).clamp(U_MIN, 1.0 - U_MIN);
                let jakob = erf_max - (erf_max + 1.0) * erf_fast((-u.ln()).sqrt());
                let x = cdf.invert(F32s([u]), F32s([erfinv_fast(jakob)]), Ms::ALL).0[0];
                fraction.push(((erf_fast(x) + 1.0) / (erf_max + 1.0)).clamp(0.0, 1.0));
            }
        }
        Self { fraction: fraction.into_boxed_slice() }
    }

    /// The interpolated erf of the root for (cos θ, u₁), given erf(cot θ).
    fn erf_of_root(&self, cos_theta: f32, u1: f32, erf_max: f32) -> f32 {
        let cell = |t: f32, n: usize| {
            let f = t.clamp(0.0, 1.0) * n as f32;
            let i = (f as usize).min(n - 1);
            (i, f - i as f32)
        };
        let (row, wr) = cell((1.0 - cos_theta).max(0.0).sqrt(), ROWS);
        let (column, wc) = cell((1.0 - u1).max(0.0).sqrt(), COLUMNS);
        let at = |row: usize, column: usize| self.fraction[row * (COLUMNS + 1) + column];
        let near = at(row, column) + (at(row, column + 1) - at(row, column)) * wc;
        let far = at(row + 1, column) + (at(row + 1, column + 1) - at(row + 1, column)) * wc;
        (near + (far - near) * wr) * (erf_max + 1.0) - 1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::special::erf_and_gaussian_fast;

    /// Elevations from grazing to just short of normal, and numbers reaching both clamps.
    fn grid() -> impl Iterator<Item = (f32, f32)> {
        let cosines = [1e-6, 1e-4, 0.01, 0.05, 0.2, 0.37, 0.5, 0.71, 0.9, 0.99, 0.999, 0.99998];
        cosines.into_iter().flat_map(|c| {
            (0..=400).map(|i| i as f32 / 400.0).chain([1e-12, 1e-9, 1e-6, 1.0 - 1e-6, 1.0 - 1e-9]).map(move |u| (c, u))
        })
    }

    #[test]
    fn slopes_invert_the_cdf() {
        for (cos_theta, u) in grid() {
            let (x, _) = visible_slopes_11(cos_theta, u, 0.5);
            let cdf = SlopeCdf::new(F32s([cos_theta]));
            let u = u.clamp(U_MIN, 1.0 - U_MIN);
            let (erf_x, gaussian) = erf_and_gaussian_fast(x);
            let value = (1.0 + erf_x + cdf.k.0[0] * gaussian) / cdf.total.0[0];
            assert!((value - u).abs() < 2.0 * TOLERANCE, "cos θ {cos_theta}, u {u}: C(x)/C(cot θ) = {value}");
            assert!(x <= cdf.x_max.0[0], "cos θ {cos_theta}, u {u}: x {x} beyond cot θ");
        }
    }

    #[test]
    fn slopes_increase_with_the_number() {
        for cos_theta in [0.01, 0.3, 0.8, 0.9999] {
            let xs: Vec<f32> = (1..1000).map(|i| visible_slopes_11(cos_theta, i as f32 / 1000.0, 0.5).0).collect();
            assert!(xs.windows(2).all(|w| w[0] < w[1]), "cos θ {cos_theta}");
        }
    }

    /// The table's start is within 2·10⁻³ of the root in the CDF everywhere on the grid (the
    /// point of the table: one Newton step from there reaches the tolerance).
    #[test]
    fn table_starts_near_the_root() {
        let table = start_table();
        for (cos_theta, u) in grid() {
            if cos_theta > NORMAL_INCIDENCE {
                continue;
            }
            let cdf = SlopeCdf::new(F32s([cos_theta]));
            let u = u.clamp(U_MIN, 1.0 - U_MIN);
            let x = erfinv_fast(table.erf_of_root(cos_theta, u, cdf.erf_max.0[0]));
            let (erf_x, gaussian) = erf_and_gaussian_fast(x);
            let value = (1.0 + erf_x + cdf.k.0[0] * gaussian) / cdf.total.0[0];
            assert!((value - u).abs() < 2e-3, "cos θ {cos_theta}, u {u}: start at C = {value}");
        }
    }
}
