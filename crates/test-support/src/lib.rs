//! Fixtures and helpers shared by the crates' integration tests, benches and examples. A test
//! that needs `../shared` (the public data, the peers' meshes, `check_mesh.py`) asks
//! [`paths::shared`], which prints a note and returns `None` when it is absent, so the test skips.

#![allow(dead_code)]

pub mod big_recipe;
pub mod didactic;
pub mod didactic_wells;
pub mod export_support;
pub mod geology;
pub mod grid;
pub mod netcdf_reader;
pub mod paths;
pub mod peer_support;
pub mod peers;
pub mod progress;
pub mod shapes;
pub mod surface_mesh_common;

use proptest::test_runner::{Config as ProptestConfig, RngSeed};

/// The seed of every property test unless `PROPTEST_RNG_SEED` names another.
pub const PROPTEST_SEED: u64 = 0x6765_6f72_6563_6970;

/// A property test's configuration: `cases` cases drawn from a fixed seed, so every run (and
/// CI) tries the same cases and a failure is reproducible; `PROPTEST_RNG_SEED` explores others.
pub fn proptest_config(cases: u32) -> ProptestConfig {
    let default = ProptestConfig::default();
    let rng_seed = match default.rng_seed {
        RngSeed::Random => RngSeed::Fixed(PROPTEST_SEED),
        chosen => chosen,
    };
    ProptestConfig {
        cases,
        rng_seed,
        ..default
    }
}

/// How many cases a fuzz test (a bounded proptest hunt) runs: `FUZZ_CASES` when set (`.ci/run`
/// sets 20,000 for a longer hunt after the tests), else the test's own `default`.
pub fn fuzz_cases(default: u32) -> u32 {
    std::env::var("FUZZ_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}
