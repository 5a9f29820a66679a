//! Participating media: phase functions and homogeneous media (transmittance and free-flight
//! distance sampling). The maths is in docs/cameras-and-media.md.
//!
//! Not yet used by the estimator: volumetric path tracing (media attached to shapes and to the
//! camera, Mitsuba's `volpath`) is the next step of issue #19; these are its building blocks,
//! each tested on its own (tests/media.rs).

mod homogeneous;
mod phase;

pub use homogeneous::{FreeFlight, HomogeneousMedium};
pub use phase::{PhaseFunction, PhaseSample};
