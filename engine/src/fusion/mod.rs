//! Fusion of per-sensor evidence into one estimate per cell.

mod batch;
mod bayes;
mod decision;
mod dempster;
mod mass;
mod rule;
mod weighted;

#[cfg(test)]
mod properties;

pub use batch::{BatchScratch, Weights, fuse_cells};
pub use bayes::pignistic;
pub use decision::decide;
pub use dempster::combine;
pub use mass::{Mass, State};
pub use rule::{Estimate, Source, fuse};

pub(crate) use rule::method_idealisations;
