//! The integration tests of this crate, one module per subject, in one binary (one link per
//! change instead of one per file).

mod import_fuzz;
mod import_lines;
mod import_quirks;
mod import_real_files;
mod import_wells;
mod validate_cases;
