//! The integration tests of this crate, one module per subject, in one binary (one link per
//! change instead of one per file).

mod engine_build;
mod engine_cache;
mod engine_derive;
mod engine_lazy;
mod engine_marker;
mod engine_parallel;
mod engine_support;
mod engine_threads;
