//! Participating media: phase functions, homogeneous media (transmittance and free-flight
//! distance sampling) and the boundaries surfaces put between them. The maths is in
//! docs/cameras-and-media.md; the estimator's use of them is `integrator::media`.

mod boundary;
mod homogeneous;
mod phase;

pub use boundary::{MediumBoundary, MediumId};
pub use homogeneous::{FreeFlight, HomogeneousMedium};
pub use phase::{PhaseFunction, PhaseSample};
