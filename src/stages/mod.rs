//! The pipeline stages, one module per stage in pipeline order. Each is a pure function of typed
//! inputs: no filesystem, no clock, no global RNG, no output that depends on the thread count.

<<<<<<< HEAD
=======
pub mod import;
pub mod validate;
pub mod topology;
pub mod regions;
pub mod intersect;
>>>>>>> wip/regions
pub mod discretize;
pub mod export;
pub mod import;
pub mod intersect;
pub mod quality;
pub mod surface_mesh;
pub mod tet_mesh;
pub mod topology;
pub mod validate;
