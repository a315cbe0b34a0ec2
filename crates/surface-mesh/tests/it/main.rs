//! The integration tests of this crate, one module per subject, in one binary (one link per
//! change instead of one per file).

mod surface_mesh_curved;
mod surface_mesh_flat;
mod surface_mesh_points;
mod surface_mesh_progress;
mod surface_mesh_quality;
mod surface_mesh_random;
mod surface_mesh_retriangulate;
