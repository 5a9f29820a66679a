//! Tone mapping (placeholder, being written).
