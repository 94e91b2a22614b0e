//! One module per family of checks. Each returns (status, value, margin, message).

pub(crate) mod invariant;
pub(crate) mod metric;
