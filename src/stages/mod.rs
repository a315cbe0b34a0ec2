//! The pipeline stages, one module per stage (ARCHITECTURE.md gives their order). Each is a pure
//! function of typed inputs: no filesystem, no clock, no global RNG, no output that depends on the
//! thread count.

pub mod discretize;
pub mod export;
pub mod import;
pub mod intersect;
pub mod model;
pub mod patches;
pub mod quality;
pub mod regions;
pub mod report;
pub mod surface_mesh;
pub mod tet_mesh;
pub mod topology;
pub mod trims;
pub mod validate;
