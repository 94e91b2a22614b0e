//! Helpers shared by the engine's integration tests (each test binary uses
//! some of them).
#![allow(dead_code)]

use sightline_dsl::{Scenario, compile};
use sightline_engine::outcome::{ObjectRecord, SemanticMetrics};

/// Runs `f` on a rayon pool of `threads` threads.
pub fn in_pool<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}

/// A scenario of `tests/fixtures/valid`, compiled from its `text`.
pub fn fixture(name: &str, text: &str) -> Scenario {
    compile(name, text, &Default::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// The record of the relevant road user `id`.
pub fn by_id<'a>(metrics: &'a SemanticMetrics, id: &str) -> &'a ObjectRecord {
    metrics
        .objects
        .iter()
        .find(|o| o.id == id)
        .unwrap_or_else(|| panic!("{id} is relevant"))
}
