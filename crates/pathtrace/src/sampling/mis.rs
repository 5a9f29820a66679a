//! Multiple importance sampling weights (Veach & Guibas, "Optimally Combining Sampling
//! Techniques for Monte Carlo Rendering", SIGGRAPH 1995), for one sample from each technique.

/// Balance heuristic: w_f = p_f / (p_f + p_g). Infinite `pdf_f` (a delta technique) takes all
/// the weight.
#[inline]
pub fn balance_heuristic(pdf_f: f32, pdf_g: f32) -> f32 {
    if pdf_f <= 0.0 {
        return 0.0;
    }
    if pdf_f.is_infinite() {
        return 1.0;
    }
    pdf_f / (pdf_f + pdf_g)
}

/// Power heuristic with β = 2: w_f = p_f² / (p_f² + p_g²). Infinite `pdf_f` (a delta
/// technique) takes all the weight.
#[inline]
pub fn power_heuristic(pdf_f: f32, pdf_g: f32) -> f32 {
    if pdf_f <= 0.0 {
        return 0.0;
    }
    if pdf_f.is_infinite() {
        return 1.0;
    }
    let f2 = pdf_f * pdf_f;
    let g2 = pdf_g * pdf_g;
    if !(f2 + g2).is_finite() {
        // Squares overflowed: compare ratios instead.
        let r = pdf_g / pdf_f;
        return 1.0 / (1.0 + r * r);
    }
    f2 / (f2 + g2)
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
    }
}
