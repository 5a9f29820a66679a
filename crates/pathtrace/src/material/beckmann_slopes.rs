//! Visible slopes of the α = 1 Beckmann distribution seen from elevation cos θ at azimuth 0
//! (Jakob 2014, "An Improved Visible Normal Sampling Routine for the Beckmann Distribution"),
//! drawn by inverting the marginal CDF of the x slope numerically.
//!
//! Up to its normalisation the CDF of the x slope is C(x) = 1 + erf(x) + tanθ/√π · e^(−x²) for
//! x ≤ cot θ, with C'(x) = 2/√π · e^(−x²) · (1 − x tanθ). Jakob solves C = u in the erf domain
//! (b = erf(x)), where each Newton step costs an inverse erf (a logarithm) and an exponential;
//! here the steps are taken on x itself, where erf(x) and e^(−x²) share one exponential
//! ([`erf_and_gaussian_fast`]). The start comes from a table of the inverse (in the erf domain,
//! where it is smooth), so that one step usually reaches the tolerance. The table only chooses
//! where Newton's method starts: every answer is iterated, inside a shrinking bracket, until the
//! CDF matches to [`TOLERANCE`] of its range, as before the table.
//!
//! Everything is single precision (as Mitsuba 3's routine is): the CDF's erf is a
//! single-precision approximation anyway, and f32 is the number type of the SIMD lanes.

use std::sync::OnceLock;

use std::f32::consts::FRAC_2_SQRT_PI;

use crate::math::special::{erf_and_gaussian_fast, erf_fast, erfinv_fast};

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
/// independent and Gaussian: y = erfinv(2u₂ − 1)).
pub(super) fn visible_slopes_11(cos_theta: f32, u1: f32, u2: f32) -> (f32, f32) {
    let u1 = u1.clamp(U_MIN, 1.0 - U_MIN);
    let u2 = u2.clamp(U_MIN, 1.0 - U_MIN);
    let sy = erfinv_fast(2.0 * u2 - 1.0);
    if cos_theta > NORMAL_INCIDENCE {
        return (erfinv_fast(2.0 * u1 - 1.0), sy);
    }
    let cdf = SlopeCdf::new(cos_theta);
    let start = erfinv_fast(start_table().erf_of_root(cos_theta, u1, cdf.erf_max));
    (cdf.invert(u1, start), sy)
}

/// The unnormalised CDF C of the x slope at one elevation.
struct SlopeCdf {
    tan_theta: f32,
    /// tanθ/√π, the weight of the Gaussian term.
    k: f32,
    /// The largest slope, cot θ, and erf of it.
    x_max: f32,
    erf_max: f32,
    /// C(cot θ), the normalisation.
    total: f32,
}

impl SlopeCdf {
    fn new(cos_theta: f32) -> Self {
        let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
        let tan_theta = sin_theta / cos_theta;
        let x_max = cos_theta / sin_theta;
        let k = tan_theta * FRAC_1_SQRT_PI;
        let (erf_max, gaussian) = erf_and_gaussian_fast(x_max);
        Self { tan_theta, k, x_max, erf_max, total: 1.0 + erf_max + k * gaussian }
    }

    /// The slope x with C(x) = u·C(cot θ), from `start`: Newton's method on x, kept inside a
    /// bracket that every evaluation narrows (C increases on (−∞, cot θ]), with a bisection
    /// step whenever Newton would leave it.
    fn invert(&self, u: f32, start: f32) -> f32 {
        let target = u * self.total;
        let tolerance = TOLERANCE * self.total;
        let (mut lo, mut hi) = (LOWEST_SLOPE, self.x_max);
        let mut x = start;
        for _ in 0..64 {
            // Also true for NaN (a step divided by a vanished derivative).
            if !(x > lo && x < hi) {
                x = 0.5 * (lo + hi);
            }
            let (erf_x, gaussian) = erf_and_gaussian_fast(x);
            let value = 1.0 + erf_x + self.k * gaussian - target;
            if value.abs() < tolerance {
                break;
            }
            if value > 0.0 {
                hi = x;
            } else {
                lo = x;
            }
            // No f32 left between the bracket's ends.
            if hi - lo <= f32::EPSILON * lo.abs().max(hi.abs()) {
                break;
            }
            let derivative = FRAC_2_SQRT_PI * gaussian * (1.0 - x * self.tan_theta);
            x -= value / derivative;
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
            let cdf = SlopeCdf::new(cos_theta);
            for column in 0..=COLUMNS {
                let s = column as f32 / COLUMNS as f32;
                let u = (1.0 - s * s).clamp(U_MIN, 1.0 - U_MIN);
                let jakob = cdf.erf_max - (cdf.erf_max + 1.0) * erf_fast((-u.ln()).sqrt());
                let x = cdf.invert(u, erfinv_fast(jakob));
                fraction.push(((erf_fast(x) + 1.0) / (cdf.erf_max + 1.0)).clamp(0.0, 1.0));
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
            let cdf = SlopeCdf::new(cos_theta);
            let u = u.clamp(U_MIN, 1.0 - U_MIN);
            let (erf_x, gaussian) = erf_and_gaussian_fast(x);
            let value = (1.0 + erf_x + cdf.k * gaussian) / cdf.total;
            assert!((value - u).abs() < 2.0 * TOLERANCE, "cos θ {cos_theta}, u {u}: C(x)/C(cot θ) = {value}");
            assert!(x <= cdf.x_max, "cos θ {cos_theta}, u {u}: x {x} beyond cot θ");
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
            let cdf = SlopeCdf::new(cos_theta);
            let u = u.clamp(U_MIN, 1.0 - U_MIN);
            let x = erfinv_fast(table.erf_of_root(cos_theta, u, cdf.erf_max));
            let (erf_x, gaussian) = erf_and_gaussian_fast(x);
            let value = (1.0 + erf_x + cdf.k * gaussian) / cdf.total;
            assert!((value - u).abs() < 2e-3, "cos θ {cos_theta}, u {u}: start at C = {value}");
        }
    }
}
