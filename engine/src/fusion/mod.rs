//! Fusion of per-sensor evidence into one estimate per cell.

mod bayes;
mod decision;
mod dempster;
mod mass;
mod rule;
mod weighted;

pub use bayes::{Occupancy, PROBABILITY_CLAMP, pignistic};
pub use decision::decide;
pub use dempster::{Combination, Combiner, combine};
pub use mass::{Mass, State};
pub use rule::{Estimate, Source, fuse};
pub use weighted::{Distances, combine_all, combine_two, discount};

pub(crate) use rule::method_idealisations;
