//! A piecewise-constant density over the unit square `[0,1)²`, proportional to a grid of
//! non-negative weights: a marginal distribution picks the row (v), a conditional one per row
//! the column (u) (pbrt-v4 §A.4.4 `PiecewiseConstant2D`). Used to importance-sample an
//! environment map.

use super::guide::{find_interleaved, CdfGuide};
use super::Distribution1D;
use crate::math::Vec2;
use crate::wide::simd::{F32s, Ms};

/// Density over `[0,1)²` constant on each of `nu × nv` cells.
#[derive(Clone, Debug)]
pub struct Distribution2D {
    nu: usize,
    nv: usize,
    /// One per row; `None` for a row of zero weight (the marginal never picks it).
    rows: Vec<Option<Distribution1D>>,
    /// The first row of positive weight, which lanes outside the active mask search.
    first_row: usize,
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
        // The marginal has positive total weight, so some row has weight.
        let first_row = rows.iter().position(Option::is_some)?;
        Some(Self { nu, nv, rows, first_row, marginal })
    }

    /// A point of the square and its density (with respect to area in `[0,1)²`): the one-lane
    /// instance of [`Distribution2D::sample_lanes`].
    pub fn sample(&self, u: Vec2) -> (Vec2, f32) {
        let (x, y, pdf) = self.sample_lanes(&F32s::<1>::splat(u.x), &F32s::splat(u.y), Ms::ALL);
        (Vec2::new(x.0[0], y.0[0]), pdf.0[0])
    }

    /// A point of the square per lane of `active` from the numbers `(u1, u2)`, as coordinates
    /// (x, y) and density (zeros in the other lanes). The marginal (small, and cached) is
    /// searched lane by lane; the rows, each likely a cache miss, in lockstep.
    #[inline(always)]
    pub fn sample_lanes<const N: usize>(
        &self,
        u1: &F32s<N>,
        u2: &F32s<N>,
        active: Ms<N>,
    ) -> (F32s<N>, F32s<N>, F32s<N>) {
        let (mut x, mut y, mut pdf) = (F32s::<N>::ZERO, F32s::<N>::ZERO, F32s::<N>::ZERO);
        // Inactive lanes skip the marginal and keep row 0.
        let mut row_of = [0usize; N];
        for i in active.lanes() {
            let (j, pv, tv) = self.marginal.sample_remapped(u2.0[i]);
            row_of[i] = j;
            y.0[i] = (j as f32 + tv) / self.nv as f32;
            pdf.0[i] = pv;
        }
        // The marginal never picks a row of zero weight; an inactive lane keeps row 0, which
        // may have none, and then searches the first row that has weight.
        let fallback = self.rows[self.first_row].as_ref().map(Distribution1D::search_table);
        let Some(fallback) = fallback else { return (x, y, F32s::ZERO) };
        // A loop, not `array::from_fn`: that was compiled out of the SIMD kernels.
        let mut searches: [(&CdfGuide, &[f32], f32); N] = [(fallback.0, fallback.1, 0.0); N];
        for (i, search) in searches.iter_mut().enumerate() {
            let row = self.rows[row_of[i]].as_ref().map_or(fallback, Distribution1D::search_table);
            *search = (row.0, row.1, u1.0[i]);
        }
        let columns = find_interleaved(&searches);
        for i in active.lanes() {
            let Some(row) = &self.rows[row_of[i]] else {
                pdf.0[i] = 0.0;
                continue;
            };
            let (pu, tu) = row.remap(columns[i], u1.0[i]);
            x.0[i] = (columns[i] as f32 + tu) / self.nu as f32;
            // Cell probability pv·pu spread over a cell of area 1/(nu·nv).
            pdf.0[i] *= pu * (self.nu * self.nv) as f32;
        }
        (x, y, pdf)
    }

    /// Density of [`Distribution2D::sample`] at `p ∈ [0,1)²` (0 outside).
    // Always inlined: an environment map asks it lane by lane inside the SIMD kernels, where,
    // compiled out of line for baseline x86-64, it was 3–4% of the bunny's and matpreview
    // plastic's profiles as its own symbol.
    #[inline(always)]
    pub fn pdf(&self, p: Vec2) -> f32 {
        self.cell(p).map_or(0.0, |(i, j)| self.cell_pdf(i, j))
    }

    /// [`Distribution2D::pdf`] at `(x, y)` per lane of `active` (0 in the others). The rows'
    /// entries are asked of the caches lane by lane before any is read: an environment map's
    /// rows are as large as the L2 cache, and read lane by lane their misses waited one after
    /// another.
    #[inline(always)]
    pub fn pdf_lanes<const N: usize>(&self, x: &F32s<N>, y: &F32s<N>, active: Ms<N>) -> F32s<N> {
        let mut cells = [None; N];
        for i in active.lanes() {
            cells[i] = self.cell(Vec2::new(x.0[i], y.0[i]));
            if let Some((u, v)) = cells[i] {
                if let Some(row) = &self.rows[v] {
                    row.prefetch(u);
                }
            }
        }
        let mut pdf = F32s::ZERO;
        for i in active.lanes() {
            if let Some((u, v)) = cells[i] {
                pdf.0[i] = self.cell_pdf(u, v);
            }
        }
        pdf
    }

    /// The cell (column, row) of `p ∈ [0,1]²`; `None` outside.
    #[inline(always)]
    fn cell(&self, p: Vec2) -> Option<(usize, usize)> {
        if !(0.0..=1.0).contains(&p.x) || !(0.0..=1.0).contains(&p.y) {
            return None;
        }
        let i = ((p.x * self.nu as f32) as usize).min(self.nu - 1);
        let j = ((p.y * self.nv as f32) as usize).min(self.nv - 1);
        Some((i, j))
    }

    /// The density on cell `(i, j)`.
    #[inline(always)]
    fn cell_pdf(&self, i: usize, j: usize) -> f32 {
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

    /// 37 × 9 cells of uneven weights, row 4 of zero weight: rows long enough to be searched
    /// through their guide tables.
    fn uneven_grid() -> Distribution2D {
        let (nu, nv) = (37, 9);
        let w: Vec<f32> =
            (0..nu * nv).map(|k| if k / nu == 4 { 0.0 } else { ((k * 7919) % 31) as f32 + 0.5 }).collect();
        Distribution2D::new(&w, nu, nv).unwrap()
    }

    /// Sixteen lanes, each active with probability ¾.
    fn three_in_four_active(rng: &mut crate::sampling::Pcg32) -> Ms<16> {
        Ms::<16>(std::array::from_fn(|_| if rng.next_u32().is_multiple_of(4) { 0 } else { u32::MAX }))
    }

    /// The density in lanes is the density of each lane's point alone (0 in inactive lanes),
    /// bit for bit, including points outside the square, on the edges and in a row of zero
    /// weight.
    #[test]
    fn lane_densities_are_each_points_density() {
        let d = uneven_grid();
        let mut rng = crate::sampling::Pcg32::new(7, 3);
        let coordinate = |r: &mut crate::sampling::Pcg32| match r.next_u32() % 8 {
            0 => -0.25,
            1 => 1.0,
            2 => 1.5,
            _ => r.next_f32(),
        };
        for _ in 0..2000 {
            let x = F32s::<16>::from_fn(|_| coordinate(&mut rng));
            let y = F32s::<16>::from_fn(|_| coordinate(&mut rng));
            let active = three_in_four_active(&mut rng);
            let pdf = d.pdf_lanes(&x, &y, active);
            for i in 0..16 {
                let alone = if active.0[i] != 0 { d.pdf(Vec2::new(x.0[i], y.0[i])) } else { 0.0 };
                assert_eq!(pdf.0[i].to_bits(), alone.to_bits(), "lane {i}");
            }
        }
    }

    /// Sixteen lanes at once give what each lane's numbers give alone, including a row of zero
    /// weight, inactive lanes and a grid whose rows are long enough to be searched through
    /// their guide tables.
    #[test]
    fn lanes_sample_what_each_lane_samples_alone() {
        let d = uneven_grid();
        let mut rng = crate::sampling::Pcg32::new(5, 9);
        for _ in 0..2000 {
            let u1 = F32s::<16>::from_fn(|_| rng.next_f32());
            let u2 = F32s::<16>::from_fn(|_| rng.next_f32());
            let active = three_in_four_active(&mut rng);
            let (x, y, pdf) = d.sample_lanes(&u1, &u2, active);
            for i in 0..16 {
                let alone = d.sample(Vec2::new(u1.0[i], u2.0[i]));
                let expected = if active.0[i] != 0 { alone } else { (Vec2::ZERO, 0.0) };
                assert_eq!((Vec2::new(x.0[i], y.0[i]), pdf.0[i]), expected, "lane {i}");
            }
        }
    }
}
