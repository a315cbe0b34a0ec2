//! The integration tests of this crate, one module per subject, in one binary (one link per
//! change instead of one per file).

mod tet_mesh_delaunay;
mod tet_mesh_lines;
mod tet_mesh_peers;
mod tet_mesh_progress;
mod tet_mesh_quality;
mod tet_mesh_simple;
mod tet_mesh_stuck;
