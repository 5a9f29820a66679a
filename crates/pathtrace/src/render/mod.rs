//! Rendering: settings, the tile worker, and the background [`RenderSession`].

mod session;
mod settings;
mod tile;

pub use session::{render, Progress, RenderError, RenderOutcome, RenderSession};
pub use settings::RenderSettings;
