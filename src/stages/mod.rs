//! The pipeline stages, one module per stage in pipeline order. Each is a pure function of typed
//! inputs: no filesystem, no clock, no global RNG, no output that depends on the thread count.

pub mod import;
pub mod validate;
pub mod topology;
pub mod intersect;
<<<<<<< HEAD
pub mod quality;
pub mod regions;
=======
pub mod discretize;
>>>>>>> wip/tetmesh
pub mod surface_mesh;
pub mod tet_mesh;
pub mod quality;
pub mod export;
