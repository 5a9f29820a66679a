//! Scene formats and image IO.
