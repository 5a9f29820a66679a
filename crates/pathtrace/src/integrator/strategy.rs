//! How the path tracer picks directions at each non-specular vertex.

use crate::sampling::{balance_heuristic_lanes, power_heuristic_lanes};
use crate::wide::simd::F32s;

/// Direction-sampling strategy. All but `Light` converge to the same (correct) image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Strategy {
    /// Scatter by the material's own sampling routine; light is found only by hitting it.
    Bsdf,
    /// Send every bounce towards a light (pdf r²/(|cos θ|·A)). **Biased**: paths only ever
    /// continue towards lights, so indirect light that arrives from other surfaces is lost.
    /// Kept as the teaching step it is in the design document.
    Light,
    /// One-sample mixture: with probability ½ towards a light, else by the material; the
    /// direction's pdf is the average of both densities (0.5·p_light + 0.5·p_bsdf).
    Mixture,
    /// Next-event estimation plus material sampling, combined by multiple importance sampling
    /// with the power heuristic. The default.
    #[default]
    Mis,
    /// As `Mis`, weighted by the balance heuristic instead (to measure the difference).
    MisBalance,
}

impl Strategy {
    pub const NAMES: [&'static str; 5] = ["bsdf", "light", "mixture", "mis", "mis-balance"];

    pub fn name(self) -> &'static str {
        match self {
            Strategy::Bsdf => "bsdf",
            Strategy::Light => "light",
            Strategy::Mixture => "mixture",
            Strategy::Mis => "mis",
            Strategy::MisBalance => "mis-balance",
        }
    }

    /// True for the strategies that combine light and material samples by MIS.
    pub fn is_mis(self) -> bool {
        matches!(self, Strategy::Mis | Strategy::MisBalance)
    }

    /// The MIS weight of a sample drawn with density `pdf_f` when the other technique has
    /// density `pdf_g` at the same direction: the power heuristic (β = 2) for `Mis`, the
    /// balance heuristic for `MisBalance` (Veach & Guibas 1995).
    #[inline]
    pub fn mis_weight(self, pdf_f: f32, pdf_g: f32) -> f32 {
        self.mis_weight_lanes(F32s([pdf_f]), F32s([pdf_g])).0[0]
    }

    /// [`Strategy::mis_weight`] in every lane.
    #[inline(always)]
    pub fn mis_weight_lanes<const N: usize>(self, pdf_f: F32s<N>, pdf_g: F32s<N>) -> F32s<N> {
        if self == Strategy::MisBalance {
            balance_heuristic_lanes(pdf_f, pdf_g)
        } else {
            power_heuristic_lanes(pdf_f, pdf_g)
        }
    }

    /// True if the strategy converges to the correct image.
    pub fn is_unbiased(self) -> bool {
        self != Strategy::Light
    }
}

impl std::str::FromStr for Strategy {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "bsdf" | "naive" => Ok(Strategy::Bsdf),
            "light" => Ok(Strategy::Light),
            "mixture" | "mix" => Ok(Strategy::Mixture),
            "mis" | "mis-power" => Ok(Strategy::Mis),
            "mis-balance" => Ok(Strategy::MisBalance),
            _ => Err(format!("unknown strategy '{s}' (expected one of: {})", Self::NAMES.join(", "))),
        }
    }
}

impl std::fmt::Display for Strategy {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
