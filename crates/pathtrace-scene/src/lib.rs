//! Scene formats and image IO.

pub mod image_io;
