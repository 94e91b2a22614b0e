//! The proptest runner of the engine's unit tests, pinned so that the cases a
//! run checks do not depend on the environment.
//!
//! The `proptest!` macro passes its `#![proptest_config(..)]` through
//! `contextualize_config`, which re-reads `PROPTEST_CASES`,
//! `PROPTEST_RNG_SEED`, `PROPTEST_RNG_ALGORITHM` and the other `PROPTEST_*`
//! variables and lets them override the fields set in the test (proptest 1.12,
//! `src/sugar.rs`); `TestRunner::new` uses the config as given, and
//! `ProptestConfig::default()` reads the variables too, so every field that
//! could change which cases run or whether a run passes is set here. (`fork`
//! and `timeout` exist only with proptest features this workspace does not
//! enable; `..default()` fills the hidden `_non_exhaustive` field.)

use proptest::prelude::ProptestConfig;
use proptest::test_runner::{RngAlgorithm, RngSeed, TestRunner, noop_result_cache};

/// A runner of `cases` cases drawn from the fixed `seed`.
pub(crate) fn runner(cases: u32, seed: u64) -> TestRunner {
    TestRunner::new(ProptestConfig {
        cases,
        // The strategies never reject, so these limits are never approached.
        max_local_rejects: 65_536,
        max_global_rejects: 1_024,
        max_flat_map_regens: 1_000_000,
        failure_persistence: None,
        source_file: None,
        test_name: None,
        max_shrink_time: 0,
        max_shrink_iters: 10_000,
        max_default_size_range: 100,
        result_cache: noop_result_cache,
        verbose: 0,
        rng_algorithm: RngAlgorithm::ChaCha,
        rng_seed: RngSeed::Fixed(seed),
        ..ProptestConfig::default()
    })
}
