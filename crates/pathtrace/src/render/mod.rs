//! Rendering: settings, the tile worker, and the background [`RenderSession`].

mod adaptive;
mod session;
mod settings;
pub(crate) mod tile;

pub use adaptive::{allocate, AdaptiveSettings};
pub use session::{render, EndSignal, Progress, RenderError, RenderOutcome, RenderSession};
pub use settings::RenderSettings;
