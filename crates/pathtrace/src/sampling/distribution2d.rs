//! A piecewise-constant density over the unit square `[0,1)²`, proportional to a grid of
//! non-negative weights: a marginal distribution picks the row (v), a conditional one per row
//! the column (u) (pbrt-v4 §A.4.4 `PiecewiseConstant2D`). Used to importance-sample an
//! environment map.

use super::Distribution1D;
use crate::math::Vec2;

/// Density over `[0,1)²` constant on each of `nu × nv` cells.
#[derive(Clone, Debug)]
pub struct Distribution2D {
    nu: usize,
    nv: usize,
    /// One per row; `None` for a row of zero weight (the marginal never picks it).
    rows: Vec<Option<Distribution1D>>,
    marginal: Distribution1D,
}

impl Distribution2D {
    /// `weights` is row-major, `nu` columns by `nv` rows. `None` when the grid is empty, the
    /// sizes disagree, or the weights do not sum to a positive finite value.
    pub fn new(weights: &[f32], nu: usize, nv: usize) -> Option<Self> {
        if nu == 0 || nv == 0 || weights.len() != nu.checked_mul(nv)? {
            return None;
        }
        let rows: Vec<Option<Distribution1D>> = weights.chunks_exact(nu).map(Distribution1D::new).collect();
        let row_sums: Vec<f32> =
            weights.chunks_exact(nu).map(|r| r.iter().map(|&w| w.max(0.0) as f64).sum::<f64>() as f32).collect();
        let marginal = Distribution1D::new(&row_sums)?;
        Some(Self { nu, nv, rows, marginal })
    }

    /// A point of the square and its density (with respect to area in `[0,1)²`).
    pub fn sample(&self, u: Vec2) -> (Vec2, f32) {
        let (j, pv, tv) = self.marginal.sample_remapped(u.y);
        // The marginal never picks a row of zero weight, so the row exists.
        let Some(row) = &self.rows[j] else { return (Vec2::ZERO, 0.0) };
        let (i, pu, tu) = row.sample_remapped(u.x);
        let point = Vec2::new((i as f32 + tu) / self.nu as f32, (j as f32 + tv) / self.nv as f32);
        // Cell probability pv·pu spread over a cell of area 1/(nu·nv).
        (point, pv * pu * (self.nu * self.nv) as f32)
    }

    /// Density of [`Distribution2D::sample`] at `p ∈ [0,1)²` (0 outside).
    pub fn pdf(&self, p: Vec2) -> f32 {
        if !(0.0..=1.0).contains(&p.x) || !(0.0..=1.0).contains(&p.y) {
            return 0.0;
        }
        let i = ((p.x * self.nu as f32) as usize).min(self.nu - 1);
        let j = ((p.y * self.nv as f32) as usize).min(self.nv - 1);
        let pv = self.marginal.pmf(j);
        match &self.rows[j] {
            Some(row) if pv > 0.0 => pv * row.pmf(i) * (self.nu * self.nv) as f32,
            _ => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_land_in_cells_with_their_weight_and_the_pdf_agrees() {
        // 3 columns × 2 rows; total weight 10.
        let w = [1.0, 0.0, 3.0, 0.0, 4.0, 2.0];
        let d = Distribution2D::new(&w, 3, 2).unwrap();
        let n = 200;
        let mut counts = [0usize; 6];
        for a in 0..n {
            for b in 0..n {
                let u = Vec2::new((a as f32 + 0.5) / n as f32, (b as f32 + 0.5) / n as f32);
                let (p, pdf) = d.sample(u);
                let cell = (p.y * 2.0) as usize * 3 + (p.x * 3.0) as usize;
                counts[cell] += 1;
                assert!((pdf - d.pdf(p)).abs() < 1e-4 * pdf, "pdf {pdf} vs {}", d.pdf(p));
            }
        }
        for (c, &wc) in counts.iter().zip(&w) {
            let expected = wc / 10.0;
            assert!((*c as f32 / (n * n) as f32 - expected).abs() < 2e-3, "{counts:?}");
        }
        // Density 6·w/10 on each cell.
        assert!((d.pdf(Vec2::new(0.9, 0.7)) - 6.0 * 0.2).abs() < 1e-5);
        assert_eq!(d.pdf(Vec2::new(0.5, 0.2)), 0.0);
        assert!(Distribution2D::new(&[0.0; 4], 2, 2).is_none());
        assert!(Distribution2D::new(&[1.0; 3], 2, 2).is_none());
    }
}
