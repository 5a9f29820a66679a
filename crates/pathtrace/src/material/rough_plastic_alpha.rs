//! A rough plastic whose α varies over the surface (a roughness texture): its coating tables —
//! the transmittance t(μ) and the internal reflectance F_dr, which depend on α — tabulated once
//! per material over α and interpolated at each hit.
//!
//! The rows are the constant-α plastic's own tables ([`RoughPlastic::new`], the one
//! implementation of the integrals) at `ROWS` roughnesses α_k = (k / (ROWS − 1))³, evenly spaced
//! in ∛α, denser near a smooth coating where the tables change fastest (√α spacing with 24 rows
//! left errors of 1e-2 in t at grazing angles for α ≈ 5e-4); a hit's α ∈ [0, 1] blends the two
//! rows around ∛α linearly (α above 1 reads as 1; below the microfacet models' smallest α,
//! 1e-4, as that α). The unit test bounds the interpolation
//! error against the tables computed directly at the same α.

use super::microfacet::Microfacet;
use super::rough_plastic::{RoughPlastic, TABLE_SIZE};
use rayon::prelude::*;

/// Roughnesses tabulated (each costs one constant-α plastic's tables).
const ROWS: usize = 32;

/// Row k's roughness α_k = (k / (ROWS − 1))³ (the distribution raises it to MIN_ALPHA).
fn row_alpha(k: usize) -> f32 {
    let s = k as f32 / (ROWS - 1) as f32;
    s * s * s
}

/// The coating tables of one rough plastic at `ROWS` roughnesses.
#[derive(Clone, Debug, PartialEq)]
pub struct RoughPlasticAlphaTable {
    /// (t(μ) at μ = i/(TABLE_SIZE − 1), F_dr) per row.
    rows: Vec<([f32; TABLE_SIZE], f32)>,
}

impl RoughPlasticAlphaTable {
    /// The tables of `plastic`'s coating (distribution kind, ior) at every row's α.
    pub fn new(plastic: &RoughPlastic) -> Self {
        let rows = (0..ROWS)
            .into_par_iter()
            .map(|k| {
                let d = Microfacet::isotropic(plastic.distribution.kind, row_alpha(k));
                let p = RoughPlastic::new(d, plastic.albedo, plastic.specular, plastic.ior, plastic.nonlinear);
                (*p.transmittance_table(), p.internal_reflectance())
            })
            .collect();
        Self { rows }
    }

    /// The tables at roughness `alpha`, blended from the two rows around ∛α.
    pub fn at(&self, alpha: f32) -> ([f32; TABLE_SIZE], f32) {
        let x = alpha.clamp(0.0, 1.0).cbrt() * (ROWS - 1) as f32;
        let k = (x as usize).min(ROWS - 2);
        let w = x - k as f32;
        let ((t0, f0), (t1, f1)) = (&self.rows[k], &self.rows[k + 1]);
        let t = std::array::from_fn(|i| (1.0 - w) * t0[i] + w * t1[i]);
        (t, (1.0 - w) * f0 + w * f1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::MicrofacetKind;
    use crate::math::Rgb;

    /// Interpolated tables against the tables integrated directly at α between the rows, for
    /// both distributions and coatings of ior 1.5 and 2.
    #[test]
    fn interpolated_tables_match_direct_integration() {
        for kind in [MicrofacetKind::Ggx, MicrofacetKind::Beckmann] {
            for ior in [1.5, 2.0] {
                let base = RoughPlastic::new(Microfacet::isotropic(kind, 0.1), Rgb::splat(0.5), Rgb::WHITE, ior, false);
                let table = RoughPlasticAlphaTable::new(&base);
                let (mut worst_t, mut worst_f) = (0.0f32, 0.0f32);
                for alpha in [0.0005, 0.003, 0.01, 0.027, 0.06, 0.13, 0.21, 0.33, 0.48, 0.61, 0.77, 0.95] {
                    let direct =
                        RoughPlastic::new(Microfacet::isotropic(kind, alpha), base.albedo, base.specular, ior, false);
                    let (t, f) = table.at(alpha);
                    let dt = t.iter().zip(direct.transmittance_table()).map(|(a, b)| (a - b).abs()).fold(0.0, f32::max);
                    worst_t = worst_t.max(dt);
                    worst_f = worst_f.max((f - direct.internal_reflectance()).abs());
                }
                eprintln!("{kind:?} ior {ior}: worst |Δt| {worst_t:.2e}, |ΔF_dr| {worst_f:.2e}");
                assert!(worst_t < 2e-3 && worst_f < 2e-3, "{kind:?} ior {ior}: {worst_t} {worst_f}");
            }
        }
    }

    /// At a row's own α the table returns that row exactly.
    #[test]
    fn rows_are_returned_exactly() {
        let base =
            RoughPlastic::new(Microfacet::isotropic(MicrofacetKind::Ggx, 0.3), Rgb::splat(0.5), Rgb::WHITE, 1.5, false);
        let table = RoughPlasticAlphaTable::new(&base);
        let direct = RoughPlastic::new(
            Microfacet::isotropic(MicrofacetKind::Ggx, row_alpha(5)),
            base.albedo,
            base.specular,
            1.5,
            false,
        );
        let (t, f) = table.at(row_alpha(5));
        let dt = t.iter().zip(direct.transmittance_table()).map(|(a, b)| (a - b).abs()).fold(0.0, f32::max);
        assert!(dt < 1e-5 && (f - direct.internal_reflectance()).abs() < 1e-5, "{dt}");
    }
}
