//! pathtrace: a physically based Monte Carlo path tracer — the engine.
//!
//! The engine never prints, exits or opens a window; file formats live in `pathtrace-scene`.

pub mod film;
pub mod math;
