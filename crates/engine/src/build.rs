//! `build`: run a `BuildGraph` against a cache directory and produce a `BuildReport`.
//!
//! The entry point takes the cache lock (telling the caller when it has to wait), loads the
//! previous manifest of its record for explanations and the files its emitting nodes wrote
//! (`emitted`), runs the coordinator over a pool of `jobs` threads, writes the next manifest and
//! emitted files into the record (when they changed), and orders the report topologically with
//! ties broken by name, so the report, outputs and lock file are identical for any number of
//! jobs.
//!
//! One pool bounds all the work: every node runs as a task of a rayon pool of `jobs` threads
//! built for this build, and a stage's own parallel loops (rayon, inside a node) run in that same
//! pool, so `-j 1` computes on one thread and `-j N` never runs more than N at once. The
//! coordinator (dispatch, expansion, bookkeeping) waits on the calling thread.

use crate::artifact::Hash;
use crate::dirlock::{Access, DirLock};
use crate::emitted::Emitted;
use crate::error::EngineError;
use crate::executor::Coordinator;
use crate::graph::{BuildGraph, Work};
use crate::manifest::Manifest;
use crate::store::Store;
use crate::worker::{Done, Job, panic_text, run_job};
use std::collections::{BTreeMap, BTreeSet};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::PathBuf;
use std::sync::mpsc;
use std::time::Instant;

pub use crate::reason::RebuildReason;
pub use crate::report::{BuildReport, NodeReport, NodeState};

#[derive(Debug, Clone)]
pub struct BuildOptions {
    pub cache_dir: PathBuf,
    /// Where emitted files are written (relative paths from `FileSet`s are joined to it).
    pub output_dir: PathBuf,
    /// When set, `output_dir` is only read: an emitted file that differs from its copy there is
    /// written under this directory instead (same relative path), for the caller to move into
    /// `output_dir` once it accepts the build, or to discard.
    pub staging_dir: Option<PathBuf>,
    /// Worker threads; 0 means one per available core.
    pub jobs: usize,
    /// Keep building independent nodes after a failure (otherwise stop dispatching).
    pub keep_going: bool,
    /// The record this build reads its previous manifest from and writes its manifest to
    /// (`<cache>/records/<record>/`, see `manifest`): one per graph that shares the cache, so
    /// builds of other graphs never become this one's baseline. A plain path component
    /// ([`crate::manifest::is_record_name`]); `BuildOptions::new` says `default`.
    pub record: String,
    /// Use the cache for reading only: nothing is written into it (no entries, no manifest).
    /// [`lock_cache`] then takes a shared lock; a build whose lock came back read-only (a
    /// cache that cannot be written) is read-only too, whatever this says.
    pub read_only: bool,
}

impl BuildOptions {
    pub fn new(cache_dir: impl Into<PathBuf>, output_dir: impl Into<PathBuf>) -> Self {
        BuildOptions {
            cache_dir: cache_dir.into(),
            output_dir: output_dir.into(),
            staging_dir: None,
            jobs: 1,
            keep_going: true,
            record: DEFAULT_RECORD.to_string(),
            read_only: false,
        }
    }

    /// The directory of this build's record in the cache.
    pub fn record_dir(&self) -> PathBuf {
        crate::manifest::record_dir(&self.cache_dir, &self.record)
    }
}

/// The record of a build that does not name one.
pub const DEFAULT_RECORD: &str = "default";

/// Status for the CLI to render (Cargo-style lines, progress bars). Events from worker threads
/// arrive in timing order; only the final `BuildReport` is thread-count independent (a skipped
/// node's `Finished` reason may name fewer failed inputs than its final report does).
#[allow(clippy::large_enum_variant)] // `Finished` carries the report by value, as the CLI wants it.
#[derive(Debug, Clone, PartialEq)]
pub enum Event {
    /// Another build holds the cache lock; this one waits for it.
    WaitingForLock {
        path: PathBuf,
    },
    /// A node started running (not emitted for cache hits).
    Started {
        name: String,
        kind: String,
    },
    Progress {
        name: String,
        done: u64,
        total: u64,
    },
    Finished(NodeReport),
    /// A cache entry for this node was unreadable or did not match its hash; it is rebuilt.
    CacheCorrupt {
        name: String,
        detail: String,
    },
    /// Node `by`'s expander added `added` nodes.
    Expanded {
        by: String,
        added: usize,
    },
}

/// Build every node of `graph` (and every node its expanders add), holding the cache's lock for
/// the build only.
pub fn build(
    graph: BuildGraph,
    opts: &BuildOptions,
    on_event: &(dyn Fn(&Event) + Sync),
) -> Result<BuildReport, EngineError> {
    let lock = lock_cache(opts, on_event)?;
    build_holding(graph, opts, &lock, on_event)
}

/// Claims `opts.cache_dir` as a cache (see `marker`) and takes its lock, telling `on_event` when
/// another build holds it first. A caller that writes files of its own after the build (a lock
/// file, a report) holds the guard until they are written, so that a build racing it cannot
/// interleave its outputs with them. A read-only build (or a cache that cannot be written) gets
/// a shared lock on an existing cache ([`DirLock::read_only`]).
pub fn lock_cache(
    opts: &BuildOptions,
    on_event: &(dyn Fn(&Event) + Sync),
) -> Result<DirLock, EngineError> {
    if !crate::manifest::is_record_name(&opts.record) {
        return Err(EngineError::Invalid {
            path: opts.cache_dir.clone(),
            message: format!(
                "`{}` cannot name a build record (letters, digits, `.`, `_`, `-`)",
                opts.record
            ),
        });
    }
    let access = if opts.read_only {
        if !opts.cache_dir.is_dir() {
            return Err(EngineError::Invalid {
                path: opts.cache_dir.clone(),
                message: "there is no cache to read here: a read-only build reads a cache that \
                          a writing build made"
                    .into(),
            });
        }
        crate::marker::require(&opts.cache_dir)?;
        Access::Read
    } else {
        crate::marker::claim(&opts.cache_dir)?;
        Access::Write
    };
    DirLock::acquire_for(&opts.cache_dir, access, |p| {
        on_event(&Event::WaitingForLock {
            path: p.to_path_buf(),
        })
    })
}

/// [`build`] under a lock the caller took with [`lock_cache`] on the same options.
pub fn build_holding(
    graph: BuildGraph,
    opts: &BuildOptions,
    lock: &DirLock,
    on_event: &(dyn Fn(&Event) + Sync),
) -> Result<BuildReport, EngineError> {
    build_again(graph, opts, lock, &Retry::default(), on_event)
}

/// What a build again knows from a failed build of this process before it.
#[derive(Debug, Clone, Default)]
pub struct Retry {
    /// The failed nodes' keys and errors: a node of the same key fails again with the same
    /// error without running (failures are not cached, and an op is a pure function of its key).
    pub failed_before: BTreeMap<Hash, String>,
    /// When not empty, the build runs only what the nodes of these names need (see `focus`);
    /// every other node is skipped as [`RebuildReason::Unfocused`].
    pub focus: BTreeSet<String>,
}

/// [`build_holding`] once more after a failed build of this process, with what it knows from
/// that build (`retry`).
pub fn build_again(
    graph: BuildGraph,
    opts: &BuildOptions,
    lock: &DirLock,
    retry: &Retry,
    on_event: &(dyn Fn(&Event) + Sync),
) -> Result<BuildReport, EngineError> {
    if lock.path() != opts.cache_dir.join("lock") {
        return Err(EngineError::Invalid {
            path: opts.cache_dir.clone(),
            message: format!(
                "the build holds the lock of another cache ({})",
                lock.path().display()
            ),
        });
    }
    let mut graph = graph;
    let t0 = Instant::now();
    let read_only = opts.read_only || lock.read_only();
    let store = Store::open_for(&opts.cache_dir, read_only)?;
    store.sweep_temporaries()?;
    let record_dir = opts.record_dir();
    let prev = Manifest::load(&record_dir).unwrap_or_default();
    let prev_emitted = Emitted::load(&record_dir);
    let jobs = if opts.jobs == 0 {
        std::thread::available_parallelism()
            .map(|n| n.get())
            .unwrap_or(1)
    } else {
        opts.jobs
    };

    let mut co = Coordinator::new(&prev, &prev_emitted, opts.keep_going);
    co.failed_before = retry.failed_before.clone();
    co.focus = crate::focus::Focus::new(retry.focus.clone());
    co.add_nodes(&graph, 0..graph.len(), on_event);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .thread_name(|i| format!("recipe-job-{i}"))
        .build()
        .map_err(|e| EngineError::Threads {
            jobs,
            message: e.to_string(),
        })?;
    let (done_tx, done_rx) = mpsc::channel::<Done>();
    pool.in_place_scope(|s| {
        let (store, output_dir) = (&store, &opts.output_dir);
        let staging_dir = opts.staging_dir.as_deref();
        let dispatch = |job: Job| {
            let done_tx = done_tx.clone();
            s.spawn(move |_| {
                let id = job.id;
                let done = catch_unwind(AssertUnwindSafe(|| {
                    run_job(job, store, output_dir, staging_dir, on_event)
                }))
                .unwrap_or_else(|p| {
                    Done::failed(
                        id,
                        format!("engine worker panicked: {}", panic_text(p.as_ref())),
                    )
                });
                // The coordinator only stops listening once nothing is in flight.
                let _ = done_tx.send(done);
            });
        };
        co.drive(&mut graph, jobs, &dispatch, &done_rx, on_event);
    });

    // A build that changed nothing leaves its record as it was.
    let manifest = co.manifest(&graph);
    if manifest != prev && !read_only {
        manifest
            .save(&record_dir)
            .map_err(|e| EngineError::io(crate::manifest::manifest_path(&record_dir), e))?;
    }
    if !read_only {
        co.emitted
            .save_over(&prev_emitted, &record_dir)
            .map_err(|e| EngineError::io(&record_dir, e))?;
    }
    let output_files = co.output_files.clone();
    let results = co.into_results(&graph);

    // Topological order, ties broken by name (Kahn with a name-ordered ready set).
    let n = graph.len();
    let mut indegree: Vec<usize> = graph
        .nodes
        .iter()
        .map(|d| d.inputs.iter().map(|i| i.0).collect::<BTreeSet<_>>().len())
        .collect();
    let mut ready: BTreeSet<(String, usize)> = (0..n)
        .filter(|&i| indegree[i] == 0)
        .map(|i| (graph.nodes[i].name.clone(), i))
        .collect();
    let mut order = Vec::with_capacity(n);
    while let Some((_, i)) = ready.pop_first() {
        order.push(i);
        for d in graph.dependents(crate::graph::NodeId(i)) {
            indegree[d.0] = indegree[d.0].saturating_sub(1);
            if indegree[d.0] == 0 {
                ready.insert((graph.nodes[d.0].name.clone(), d.0));
            }
        }
    }
    let mut results: Vec<_> = results.into_iter().map(Some).collect();
    let mut nodes = Vec::with_capacity(n);
    let mut artifacts = BTreeMap::new();
    for i in order {
        if let Some((Some(report), artifact)) = results.get_mut(i).and_then(Option::take) {
            // A file-emitting node's bytes are on disk by now: not kept (they are the largest
            // artifact of a build, and the caller's report phase would otherwise hold them).
            let emits = matches!(&graph.nodes[i].work, Work::Op(op) if op.emits_files());
            if let Some(a) = artifact.filter(|_| !emits) {
                artifacts.insert(report.name.clone(), a);
            }
            nodes.push(report);
        }
    }
    let ok = nodes.iter().all(|r| r.state.is_ok());
    Ok(BuildReport {
        nodes,
        output_files,
        ok,
        duration_ms: t0.elapsed().as_secs_f64() * 1000.0,
        artifacts,
    })
}

/// Hash of a file's content as the engine keys it (for callers comparing files with a lock).
pub fn file_hash(bytes: &[u8]) -> Hash {
    Hash::of(bytes)
}
