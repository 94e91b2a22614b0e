//! Helpers shared by the engine's integration tests.

use sightline_dsl::Scenario;
use sightline_engine::{Run, simulate};

/// Simulates `scenario` on a rayon pool of `threads` threads.
pub fn in_pool(threads: usize, scenario: &Scenario) -> Run {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(|| simulate(scenario))
}
