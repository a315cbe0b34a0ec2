//! What the engine executes: an `Operation` is a pure function from input artifacts to one
//! output artifact, identified by its kind, implementation version and canonical parameters.
//!
//! The engine never looks inside artifacts; it only needs these to build cache keys, to run the
//! operation and to record the counts and notes the report shows.

use crate::artifact::Artifact;
use crate::params::Params;
use std::collections::BTreeMap;

/// A node failure, reported in the build report (never a panic).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{message}")]
pub struct OpError {
    pub message: String,
}

impl From<String> for OpError {
    fn from(message: String) -> Self {
        OpError { message }
    }
}

impl From<&str> for OpError {
    fn from(message: &str) -> Self {
        OpError {
            message: message.to_string(),
        }
    }
}

/// The result of one run: the artifact plus counts (triangles, tets…) and notes for the report.
#[derive(Debug, Clone)]
pub struct Output {
    pub artifact: Artifact,
    pub counts: BTreeMap<String, u64>,
    pub notes: Vec<String>,
}

impl Output {
    pub fn new(artifact: Artifact) -> Self {
        Output {
            artifact,
            counts: BTreeMap::new(),
            notes: Vec::new(),
        }
    }

    pub fn count(mut self, k: &str, v: u64) -> Self {
        self.counts.insert(k.to_string(), v);
        self
    }

    pub fn note(mut self, n: impl Into<String>) -> Self {
        self.notes.push(n.into());
        self
    }
}

/// What a running operation may tell the engine.
pub trait RunContext {
    fn progress(&self, done: u64, total: u64);
}

/// The context of a run nobody watches (a repair of the store, a derivation).
pub(crate) struct Quiet;

impl RunContext for Quiet {
    fn progress(&self, _: u64, _: u64) {}
}

/// One kind of build step.
pub trait Operation: Send + Sync {
    /// e.g. "import", "discretize".
    fn kind(&self) -> &'static str;
    /// Bump when the implementation's output changes.
    fn version(&self) -> u32;
    fn params(&self) -> Params;
    fn run(&self, ctx: &dyn RunContext, inputs: &[Artifact]) -> Result<Output, OpError>;
    /// When true, the artifact decodes as a `FileSet` that the engine writes (atomically, temp +
    /// rename) under `BuildOptions::output_dir` (or its `staging_dir`), and whose files' hashes
    /// enter the report and lock file. A cached node re-writes a file that is missing or differs
    /// on disk.
    fn emits_files(&self) -> bool {
        false
    }
    /// When true, a cache hit does not read this node's output until something needs its bytes
    /// (a dependent that runs, the files it emits, the caller): for large outputs that a build
    /// where nothing changed never looks at. The output is verified when it is read, and made
    /// again then if the cache entry is damaged. Ignored for a node with an expander, which
    /// always reads its output.
    fn lazy_output(&self) -> bool {
        false
    }
}
