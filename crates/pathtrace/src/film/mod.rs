//! The film: accumulation buffer, variance, tone mapping.

pub mod tonemap;
