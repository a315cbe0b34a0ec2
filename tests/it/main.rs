//! The integration tests of this crate, one module per subject, in one binary (one link per
//! change instead of one per file).

mod cli_build;
mod cli_cache;
mod cli_errors;
mod cli_exodus;
mod cli_geology;
mod cli_groups;
mod cli_incremental;
mod cli_mesh;
mod cli_msh_groups;
mod cli_noop;
mod cli_output;
mod cli_perturbed;
mod cli_progress;
mod cli_proximity;
mod cli_real_data;
mod cli_ringmesh;
mod cli_sizes;
mod cli_tetmesh;
mod cli_validation;
mod cli_watch;
mod cli_wells;
mod common_cli;
mod export_op_files;
mod ops_progress;
mod recipe_errors;
mod recipe_fuzz;
mod recipe_roundtrip;
mod recipe_samples;
mod recipe_scale;
mod recipe_sealed;
mod recipe_selectors;
mod report_documents;
mod report_peers;
mod report_size;
mod tet_mesh_thin_layers;
