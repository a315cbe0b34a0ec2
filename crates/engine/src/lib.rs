//! The build engine: a generic, content-hashed, cached, parallel executor of a DAG of
//! operations that can grow while it builds. It knows nothing about meshes, recipes or geometry.
//!
//! A node's key is blake3 of its operation kind, version, canonical parameters and its inputs'
//! output hashes (`key`); outputs are cached content-addressed on disk (`store`), verified on
//! every read, under a directory lock (`dirlock`). `build` runs ready nodes in parallel,
//! re-runs only what changed, cuts off dependents when a re-run reproduces the same output,
//! explains every re-run (`reason`, from the previous `manifest`), and reports every node
//! (`report`); `lockfile` pins the outputs and `gc` trims the cache. Graphs sharing a cache each
//! name a record (`BuildOptions::record`) that keeps their own previous manifest.
//!
//! Typical use by the planner and the CLI:
//!
//! ```ignore
//! let mut g = BuildGraph::new();
//! let top = g.add_file("file:top", "data/top.ts".into())?;
//! let imp = g.add_op("import:top", Arc::new(ImportOp { .. }), &[top])?;
//! let model = g.add_op("model", Arc::new(ModelOp { .. }), &[imp])?;
//! g.set_expander(model, Arc::new(PerEntityExpander { .. })); // adds curve:/patch:/region: nodes
//! let report = build(g, &BuildOptions::new(".recipe-cache", "out"), &|e| cli.render(e))?;
//! let lock = LockFile::from_report(&report);            // write as recipe.lock, or diff for --locked
//! let model: Model = report.artifact("model").unwrap().decode()?;
//! ```
//!
//! Nodes with identical keys in one build are computed once and share their resolution, so
//! states never depend on scheduling. Events arrive in timing order; the report does not.

pub mod artifact;
pub mod build;
pub mod checked;
pub mod crash;
pub mod derive;
pub mod dirlock;
mod emitted;
mod entry;
pub mod error;
mod executor;
mod focus;
pub mod gc;
pub mod graph;
pub mod key;
pub mod lockfile;
pub mod manifest;
pub mod marker;
pub mod op;
mod outputs;
pub mod params;
pub mod reason;
pub mod report;
pub mod store;
mod stored;
mod worker;

pub use artifact::{Artifact, FileSet, Hash};
pub use build::{
    BuildOptions, DEFAULT_RECORD, Event, Retry, build, build_again, build_holding, lock_cache,
};
pub use derive::Derivations;
pub use dirlock::DirLock;
pub use error::EngineError;
pub use gc::{Cleaned, GcStats, clean, forget, gc, gc_and};
pub use graph::{BuildGraph, Expander, Expansion, GraphError, NodeId};
pub use lockfile::{LockFile, LockedNode};
pub use op::{OpError, Operation, Output, RunContext};
pub use params::{Param, ParamChange, ParamError, Params};
pub use reason::RebuildReason;
pub use report::{BuildReport, NodeReport, NodeState};
pub use store::write_atomic;
