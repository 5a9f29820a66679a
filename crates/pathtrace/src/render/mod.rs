//! Rendering: settings, the tile worker, and the background [`RenderSession`].

mod adaptive;
mod sample_range;
mod session;
mod settings;
pub(crate) mod tile;

pub use adaptive::{allocate, AdaptiveSettings};
pub use sample_range::SampleRange;
pub use session::{render, EndSignal, Progress, RenderError, RenderOutcome, RenderSession};
pub use settings::RenderSettings;
