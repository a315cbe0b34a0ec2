//! The build engine: a generic, content-hashed, cached, parallel executor of a DAG of
//! operations that can grow while it builds. It knows nothing about meshes, recipes or geometry.
//!
//! A node's key is blake3 of its operation kind, version, canonical parameters and its inputs'
//! output hashes (`key`); outputs are cached content-addressed on disk (`store`), verified on
//! every read, under a directory lock (`dirlock`). `build` runs ready nodes in parallel,
//! re-runs only what changed, cuts off dependents when a re-run reproduces the same output,
//! explains every re-run (`reason`, from the previous `manifest`), and reports every node
//! (`report`); `lockfile` pins the outputs and `gc` trims the cache.

pub mod artifact;
pub mod build;
pub mod dirlock;
pub mod error;
mod executor;
pub mod gc;
pub mod graph;
pub mod key;
pub mod lockfile;
pub mod manifest;
pub mod op;
mod outputs;
pub mod params;
pub mod reason;
pub mod report;
pub mod store;
mod worker;

pub use artifact::{Artifact, FileSet, Hash};
pub use build::{BuildOptions, Event, build};
pub use error::EngineError;
pub use gc::{GcStats, clean, gc};
pub use graph::{BuildGraph, Expander, Expansion, GraphError, NodeId};
pub use lockfile::{LockFile, LockedNode};
pub use op::{OpError, Operation, Output, RunContext};
pub use params::{Param, ParamChange, ParamError, Params};
pub use reason::RebuildReason;
pub use report::{BuildReport, NodeReport, NodeState};
