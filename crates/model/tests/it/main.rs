//! The integration tests of this crate, one module per subject, in one binary (one link per
//! change instead of one per file).

mod intersect_cases;
mod intersect_cfm;
mod intersect_corpus;
mod intersect_proptest;
mod intersect_shared;
mod intersect_split;
mod intersect_support;
mod model_topology;
mod regions_cases;
mod regions_ringmesh;
mod remesh_shapes;
mod split_cfm;
mod split_corpus;
mod split_crossing;
mod split_degenerate;
mod split_didactic;
mod split_ringmesh;
mod topology_cases;
mod trims_didactic;
mod wells_cases;
