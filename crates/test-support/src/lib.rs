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

/// How many cases a fuzz test (a bounded proptest hunt) runs: `FUZZ_CASES` when set (`.ci/run`
/// sets 20,000 for a longer hunt after the tests), else the test's own `default`.
pub fn fuzz_cases(default: u32) -> u32 {
    std::env::var("FUZZ_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}
