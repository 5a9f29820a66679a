//! Statistical test helpers.
