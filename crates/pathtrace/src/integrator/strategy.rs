//! How the path tracer picks directions at each non-specular vertex.

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
}

impl Strategy {
    pub const NAMES: [&'static str; 4] = ["bsdf", "light", "mixture", "mis"];

    pub fn name(self) -> &'static str {
        match self {
            Strategy::Bsdf => "bsdf",
            Strategy::Light => "light",
            Strategy::Mixture => "mixture",
            Strategy::Mis => "mis",
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
            "mis" => Ok(Strategy::Mis),
            _ => Err(format!("unknown strategy '{s}' (expected one of: {})", Self::NAMES.join(", "))),
        }
    }
}

impl std::fmt::Display for Strategy {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
