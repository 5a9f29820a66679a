//! Statistical test helpers for pathtrace (dev-only): a deterministic RNG, the
//! chi-square goodness-of-fit test for direction samplers, pdf integration over the
//! sphere, and z-tests between Monte Carlo estimates.

mod chi2;
mod chi2_outcome;
#[cfg(test)]
mod chi2_tests;
mod mean;
mod p_value;
mod quadrature;
mod rng;

pub use chi2::ChiSquareTest;
pub use chi2_outcome::ChiSquareOutcome;
pub use mean::{assert_agree, z_score, MeanEstimate};
pub use p_value::chi_square_p_value;
pub use quadrature::integrate_over_sphere;
pub use rng::TestRng;
