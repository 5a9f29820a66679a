//! Multiple importance sampling weights (Veach & Guibas, "Optimally Combining Sampling
//! Techniques for Monte Carlo Rendering", SIGGRAPH 1995), for one sample from each technique.

use crate::wide::simd::F32s;

/// Balance heuristic: w_f = p_f / (p_f + p_g). Infinite `pdf_f` (a delta technique) takes all
/// the weight.
#[inline]
pub fn balance_heuristic(pdf_f: f32, pdf_g: f32) -> f32 {
    balance_heuristic_lanes(F32s([pdf_f]), F32s([pdf_g])).0[0]
}

/// Power heuristic with β = 2: w_f = p_f² / (p_f² + p_g²). Infinite `pdf_f` (a delta
/// technique) takes all the weight.
#[inline]
pub fn power_heuristic(pdf_f: f32, pdf_g: f32) -> f32 {
    power_heuristic_lanes(F32s([pdf_f]), F32s([pdf_g])).0[0]
}

/// [`balance_heuristic`] in every lane.
#[inline(always)]
pub fn balance_heuristic_lanes<const N: usize>(pdf_f: F32s<N>, pdf_g: F32s<N>) -> F32s<N> {
    heuristic(pdf_f, pdf_g, |r| r)
}

/// [`power_heuristic`] in every lane.
#[inline(always)]
pub fn power_heuristic_lanes<const N: usize>(pdf_f: F32s<N>, pdf_g: F32s<N>) -> F32s<N> {
    heuristic(pdf_f, pdf_g, |r| r * r)
}

/// w_f = 1 / (1 + (p_g / p_f)^β), the heuristics' common form, which cannot overflow (squares of
/// large densities would); 0 where `pdf_f` ≤ 0, 1 where it is infinite.
#[inline(always)]
fn heuristic<const N: usize>(pdf_f: F32s<N>, pdf_g: F32s<N>, power: impl Fn(F32s<N>) -> F32s<N>) -> F32s<N> {
    let w = 1.0 / (1.0 + power(pdf_g / pdf_f));
    let w = F32s::select(pdf_f.is_finite(), w, F32s::ONE);
    F32s::select(pdf_f.gt(F32s::ZERO), w, F32s::ZERO)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_sum_to_one() {
        for (a, b) in [(1.0, 1.0), (0.3, 7.0), (1e20, 3e19), (5.0, 0.0)] {
            assert!((power_heuristic(a, b) + power_heuristic(b, a) - 1.0).abs() < 1e-6);
            assert!((balance_heuristic(a, b) + balance_heuristic(b, a) - 1.0).abs() < 1e-6);
        }
        assert_eq!(power_heuristic(0.0, 1.0), 0.0);
        assert_eq!(power_heuristic(f32::INFINITY, 1.0), 1.0);
        assert_eq!(balance_heuristic(f32::INFINITY, 1.0), 1.0);
        assert_eq!(power_heuristic(f32::INFINITY, f32::INFINITY), 1.0);
        assert_eq!(power_heuristic(0.0, 0.0), 0.0);
        // Squares of these overflow f32; the ratio form does not.
        assert!((power_heuristic(3e30, 4e30) - 0.36).abs() < 1e-6);
    }
}
