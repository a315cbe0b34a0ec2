//! The coordinating side of a build: tracks every node's state, dispatches ready nodes to the
//! workers in a deterministic priority (by name), computes keys as soon as inputs are known,
//! classifies each finished node (ran / cached / cut off / failed / skipped) with its rebuild
//! reason, runs expanders, and skips the dependents of failures while independent nodes go on.
//!
//! Everything that reaches the report is decided here from node names, keys and hashes alone,
//! so the outcome does not depend on how many workers there are or in which order they finish.

const QUEUE_DEPTH: usize = 4;

use crate::artifact::{Artifact, Hash};
use crate::build::Event;
use crate::emitted::{Emitted, NodeFiles};
use crate::focus::Focus;
use crate::graph::{BuildGraph, Expansion, NodeData, NodeId, Work};
use crate::key::{file_key, op_key};
use crate::manifest::{Manifest, ManifestEntry};
use crate::params::Params;
use crate::reason::RebuildReason;
use crate::report::{NodeReport, NodeState};
use crate::worker::{Done, Job, JobWork, panic_text};
use std::collections::{BTreeMap, BTreeSet};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::mpsc::Receiver;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    Waiting(usize),
    Ready,
    Running,
    Done,
}

struct Slot {
    phase: Phase,
    key: Hash,
    version: u32,
    params: Params,
    artifact: Option<Artifact>,
    report: Option<NodeReport>,
    /// This node ran, or something upstream of it ran, in this build.
    ran_upstream: bool,
}

impl Slot {
    fn new() -> Self {
        Slot {
            phase: Phase::Waiting(0),
            key: Hash::ZERO,
            version: 0,
            params: Params::new(),
            artifact: None,
            report: None,
            ran_upstream: false,
        }
    }
    fn ok(&self) -> bool {
        self.phase == Phase::Done && self.artifact.is_some()
    }
}

pub(crate) struct Coordinator<'a> {
    prev: &'a Manifest,
    /// The files each emitting node emitted in the record's last build.
    prev_emitted: &'a Emitted,
    /// The same for this build.
    pub emitted: Emitted,
    keep_going: bool,
    stopped: bool,
    slots: Vec<Slot>,
    ready: BTreeSet<(String, usize)>,
    pub output_files: BTreeMap<String, Hash>,
    file_owner: BTreeMap<String, String>,
    /// Keys being computed by a worker, with the nodes of the same key parked behind them.
    inflight_keys: BTreeMap<Hash, Vec<usize>>,
    /// Keys already resolved in this build: nodes sharing a key share the first resolution, so
    /// whether they ran or were cached depends on the cache at build start, not on timing.
    resolved: BTreeMap<Hash, Done>,
    /// Keys that failed in a build of this process just before (an op is a pure function of
    /// its key): they fail again with the same error, without running.
    pub failed_before: BTreeMap<Hash, String>,
    /// The nodes a focused build runs (all, unless the caller focuses it).
    pub focus: Focus,
    /// Ready nodes the focus does not need (yet: an expansion may add a node that needs them).
    held: BTreeSet<(String, usize)>,
    /// The graph's size when the held nodes were last looked at.
    held_at: usize,
}

fn distinct_inputs(n: &NodeData) -> BTreeSet<usize> {
    n.inputs.iter().map(|i| i.0).collect()
}

impl<'a> Coordinator<'a> {
    pub fn new(prev: &'a Manifest, prev_emitted: &'a Emitted, keep_going: bool) -> Self {
        Coordinator {
            prev,
            prev_emitted,
            emitted: Emitted::new(),
            keep_going,
            stopped: false,
            slots: Vec::new(),
            ready: BTreeSet::new(),
            output_files: BTreeMap::new(),
            file_owner: BTreeMap::new(),
            inflight_keys: BTreeMap::new(),
            resolved: BTreeMap::new(),
            failed_before: BTreeMap::new(),
            focus: Focus::default(),
            held: BTreeSet::new(),
            held_at: 0,
        }
    }

    /// Register nodes `range` of `graph` (all inputs of each are already registered).
    pub fn add_nodes(
        &mut self,
        graph: &BuildGraph,
        range: std::ops::Range<usize>,
        on_event: &(dyn Fn(&Event) + Sync),
    ) {
        for id in range {
            self.slots.push(Slot::new());
            let Some(n) = graph.nodes.get(id) else {
                continue;
            };
            let inputs = distinct_inputs(n);
            let failed: Vec<String> = n
                .inputs
                .iter()
                .filter(|i| {
                    self.slots
                        .get(i.0)
                        .is_some_and(|s| s.phase == Phase::Done && !s.ok())
                })
                .map(|i| graph.nodes[i.0].name.clone())
                .collect();
            if !failed.is_empty() {
                self.finish_skipped(
                    graph,
                    id,
                    RebuildReason::InputFailed {
                        inputs: dedup(failed),
                    },
                    on_event,
                );
                continue;
            }
            let waiting = inputs
                .iter()
                .filter(|&&i| self.slots.get(i).is_some_and(|s| s.phase != Phase::Done))
                .count();
            if waiting == 0 {
                self.make_ready(graph, id);
            } else {
                self.slots[id].phase = Phase::Waiting(waiting);
            }
        }
    }

    fn make_ready(&mut self, graph: &BuildGraph, id: usize) {
        self.slots[id].phase = Phase::Ready;
        self.ready.insert((graph.nodes[id].name.clone(), id));
    }

    /// Run the build to completion with `jobs` dispatch slots.
    pub fn drive(
        &mut self,
        graph: &mut BuildGraph,
        jobs: usize,
        dispatch: &dyn Fn(Job),
        rx: &Receiver<Done>,
        on_event: &(dyn Fn(&Event) + Sync),
    ) {
        let mut in_flight = 0usize;
        loop {
            // Keep a few jobs queued per worker so a worker never waits for the coordinator to
            // wake up between two nodes (each node is pure: the order of completion never
            // changes a result). Without keep-going, dispatch one at a time so that a failure
            // stops everything not yet started.
            let depth = if self.keep_going { QUEUE_DEPTH } else { 1 };
            while in_flight < jobs * depth && !self.stopped {
                if self.held_at != graph.len() {
                    // An expansion grew the graph: what was held back may be needed now.
                    self.held_at = graph.len();
                    self.ready.append(&mut self.held);
                }
                let Some((name, id)) = self.ready.pop_first() else {
                    break;
                };
                if !self.focus.needs(graph, id) {
                    self.held.insert((name, id));
                    continue;
                }
                match self.job_for(graph, id) {
                    Ok(job) => {
                        self.slots[id].phase = Phase::Running;
                        if let JobWork::Op { key, .. } = &job.work {
                            let key = *key;
                            if let Some(e) = self.failed_before.get(&key) {
                                self.finish(graph, Done::failed(id, e.clone()), on_event);
                                continue;
                            }
                            if let Some(res) = self.resolved.get(&key) {
                                let done = Done {
                                    id,
                                    duration_ms: 0.0,
                                    ..res.clone()
                                };
                                self.finish(graph, done, on_event);
                                continue;
                            }
                            if let Some(parked) = self.inflight_keys.get_mut(&key) {
                                parked.push(id);
                                continue;
                            }
                            self.inflight_keys.insert(key, Vec::new());
                        }
                        dispatch(job);
                        in_flight += 1;
                    }
                    Err(e) => self.fail_now(graph, id, e, on_event),
                }
            }
            if in_flight == 0 {
                break;
            }
            let Ok(done) = rx.recv() else { break };
            in_flight -= 1;
            let id = done.id;
            let key = self.slots.get(id).map(|s| s.key);
            let parked = match (key, graph.nodes.get(id).map(|n| &n.work)) {
                (Some(k), Some(Work::Op(_))) => self.inflight_keys.remove(&k).map(|p| (k, p)),
                _ => None,
            };
            match parked {
                Some((k, parked)) => {
                    self.resolved.insert(k, done.clone());
                    self.finish(graph, done.clone(), on_event);
                    for twin in parked {
                        self.finish(
                            graph,
                            Done {
                                id: twin,
                                duration_ms: 0.0,
                                ..done.clone()
                            },
                            on_event,
                        );
                    }
                }
                None => self.finish(graph, done, on_event),
            }
        }
        if self.focus.is_on() && !self.stopped {
            self.finish_unfocused(graph, on_event);
        }
        let reason = if self.stopped {
            RebuildReason::BuildStopped
        } else {
            RebuildReason::InputFailed { inputs: vec![] }
        };
        for id in 0..self.slots.len() {
            if self.slots[id].phase != Phase::Done {
                self.finish_skipped(graph, id, reason.clone(), on_event);
            }
        }
    }

    fn job_for(&mut self, graph: &BuildGraph, id: usize) -> Result<Job, String> {
        let n = &graph.nodes[id];
        let inputs: Vec<Artifact> = n
            .inputs
            .iter()
            .filter_map(|i| self.slots[i.0].artifact.clone())
            .collect();
        if inputs.len() != n.inputs.len() {
            return Err("an input has no output".into());
        }
        let work = match &n.work {
            Work::File(p) => JobWork::File(p.clone()),
            Work::Op(op) => {
                let (kind, version, params) =
                    catch_unwind(AssertUnwindSafe(|| (op.kind(), op.version(), op.params())))
                        .map_err(|p| {
                            format!(
                                "operation panicked while describing itself: {}",
                                panic_text(p.as_ref())
                            )
                        })?;
                let hashes: Vec<Hash> = inputs.iter().map(Artifact::hash).collect();
                let key = op_key(kind, version, &params, &hashes);
                let slot = &mut self.slots[id];
                slot.key = key;
                slot.version = version;
                slot.params = params;
                let emitted = op
                    .emits_files()
                    .then(|| self.prev_emitted.nodes.get(&n.name).cloned())
                    .flatten();
                JobWork::Op {
                    op: op.clone(),
                    key,
                    lazy: op.lazy_output() && n.expander.is_none(),
                    emitted,
                }
            }
        };
        Ok(Job {
            id,
            name: n.name.clone(),
            work,
            inputs,
        })
    }

    fn base_report(
        &self,
        graph: &BuildGraph,
        id: usize,
        state: NodeState,
        reason: RebuildReason,
    ) -> NodeReport {
        let n = &graph.nodes[id];
        NodeReport {
            name: n.name.clone(),
            kind: n.kind().to_string(),
            state,
            reason,
            duration_ms: 0.0,
            key: self.slots[id].key,
            output: None,
            counts: BTreeMap::new(),
            notes: vec![],
            error: None,
            inputs: n
                .inputs
                .iter()
                .map(|i| graph.nodes[i.0].name.clone())
                .collect(),
        }
    }

    fn fail_now(
        &mut self,
        graph: &BuildGraph,
        id: usize,
        error: String,
        on_event: &(dyn Fn(&Event) + Sync),
    ) {
        let mut r = self.base_report(graph, id, NodeState::Failed, RebuildReason::NewNode);
        r.error = Some(error);
        self.settle(graph, id, r, None, on_event);
    }

    fn finish_skipped(
        &mut self,
        graph: &BuildGraph,
        id: usize,
        reason: RebuildReason,
        on_event: &(dyn Fn(&Event) + Sync),
    ) {
        self.ready.retain(|(_, i)| *i != id);
        let r = self.base_report(graph, id, NodeState::Skipped, reason);
        self.settle(graph, id, r, None, on_event);
    }

    /// Every node a focused build left out (held back, or waiting on one that was), skipped as
    /// such: none of them failed.
    fn finish_unfocused(&mut self, graph: &BuildGraph, on_event: &(dyn Fn(&Event) + Sync)) {
        self.ready.clear();
        self.held.clear();
        for id in 0..self.slots.len() {
            if self.slots[id].phase != Phase::Done {
                let r = self.base_report(graph, id, NodeState::Skipped, RebuildReason::Unfocused);
                on_event(&Event::Finished(r.clone()));
                let slot = &mut self.slots[id];
                slot.phase = Phase::Done;
                slot.report = Some(r);
            }
        }
    }

    /// Why a node that had to run ran, from the previous build's manifest.
    fn run_reason(&self, graph: &BuildGraph, id: usize, corrupt: &Option<String>) -> RebuildReason {
        let n = &graph.nodes[id];
        let slot = &self.slots[id];
        let Some(p) = self.prev.nodes.get(&n.name) else {
            return RebuildReason::NewNode;
        };
        if p.kind != n.kind() {
            return RebuildReason::NewNode;
        }
        if p.key != slot.key {
            if p.version != slot.version {
                return RebuildReason::VersionChanged {
                    old: p.version,
                    new: slot.version,
                };
            }
            let d = slot.params.diff(&p.params);
            if !d.is_empty() {
                return RebuildReason::ParamsChanged(d);
            }
            let now = self.input_hashes(graph, id);
            let before: BTreeMap<&String, &Hash> = p.inputs.iter().map(|(n, h)| (n, h)).collect();
            let changed: Vec<String> = now
                .iter()
                .filter(|(n, h)| before.get(n) != Some(&h))
                .map(|(n, _)| n.clone())
                .collect();
            if !changed.is_empty() {
                return RebuildReason::UpstreamChanged {
                    inputs: dedup(changed),
                };
            }
            if p.inputs != now {
                return RebuildReason::UpstreamChanged {
                    inputs: dedup(now.into_iter().map(|(n, _)| n).collect()),
                };
            }
        }
        match corrupt {
            Some(d) => RebuildReason::CacheCorrupt(d.clone()),
            None => RebuildReason::CacheMissing,
        }
    }

    fn input_hashes(&self, graph: &BuildGraph, id: usize) -> Vec<(String, Hash)> {
        graph.nodes[id]
            .inputs
            .iter()
            .map(|i| {
                (
                    graph.nodes[i.0].name.clone(),
                    self.slots[i.0]
                        .artifact
                        .as_ref()
                        .map(Artifact::hash)
                        .unwrap_or(Hash::ZERO),
                )
            })
            .collect()
    }

    fn finish(&mut self, graph: &mut BuildGraph, done: Done, on_event: &(dyn Fn(&Event) + Sync)) {
        let id = done.id;
        if id >= self.slots.len() {
            return;
        }
        let ran_upstream = graph.nodes[id]
            .inputs
            .iter()
            .any(|i| self.slots[i.0].ran_upstream);
        let is_file = matches!(graph.nodes[id].work, Work::File(_));
        let mut report;
        let mut artifact = None;
        match done.result {
            Err(e) => {
                let reason = if is_file {
                    RebuildReason::NewNode
                } else {
                    self.run_reason(graph, id, &done.corrupt)
                };
                report = self.base_report(graph, id, NodeState::Failed, reason);
                report.error = Some(e);
            }
            Ok(p) => {
                let (state, reason) = if let Work::File(path) = &graph.nodes[id].work {
                    self.slots[id].key = file_key(p.artifact.hash());
                    match self.prev.nodes.get(&graph.nodes[id].name) {
                        Some(e) if e.kind == "file" && e.output == p.artifact.hash() => {
                            (NodeState::Cached, RebuildReason::UpToDate)
                        }
                        Some(e) if e.kind == "file" => (
                            NodeState::Ran,
                            RebuildReason::InputFileChanged {
                                path: path.display().to_string(),
                            },
                        ),
                        _ => (NodeState::Ran, RebuildReason::NewNode),
                    }
                } else if done.ran {
                    (NodeState::Ran, self.run_reason(graph, id, &done.corrupt))
                } else if ran_upstream {
                    (NodeState::CutOff, RebuildReason::UpToDate)
                } else {
                    (NodeState::Cached, RebuildReason::UpToDate)
                };
                report = self.base_report(graph, id, state, reason);
                report.output = Some(p.artifact.hash());
                report.counts = p.counts;
                report.notes = p.notes;
                artifact = Some(p.artifact);
            }
        }
        report.duration_ms = done.duration_ms;
        // Emitted files: one owner per path.
        if report.state.is_ok() {
            let name = report.name.clone();
            if let Some((path, other)) = done.files.keys().find_map(|p| {
                self.file_owner
                    .get(p)
                    .filter(|o| **o != name)
                    .map(|o| (p.clone(), o.clone()))
            }) {
                report.state = NodeState::Failed;
                report.error = Some(format!(
                    "output file `{path}` is also emitted by node `{other}`"
                ));
                artifact = None;
            } else {
                for (p, h) in &done.files {
                    self.file_owner.insert(p.clone(), name.clone());
                    self.output_files.insert(p.clone(), *h);
                }
                let emits = matches!(&graph.nodes[id].work, Work::Op(op) if op.emits_files());
                if let (true, Some(a)) = (emits, &artifact) {
                    let files = NodeFiles {
                        output: a.hash(),
                        files: done.files.clone(),
                    };
                    self.emitted.nodes.insert(name.clone(), files);
                }
            }
        }
        let ran = report.state == NodeState::Ran;
        self.slots[id].ran_upstream = ran || ran_upstream;
        // Expansion, on this thread, before anything it adds can run.
        let mut staged = Vec::new();
        if let (Some(a), Some(exp)) = (&artifact, graph.nodes[id].expander.clone()) {
            let mut x = Expansion::new(graph);
            match catch_unwind(AssertUnwindSafe(|| exp.expand(a, &mut x))) {
                Ok(Ok(())) => staged = x.into_staged(),
                Ok(Err(e)) => {
                    report.state = NodeState::Failed;
                    report.error = Some(format!("expansion failed: {e}"));
                    artifact = None;
                }
                Err(p) => {
                    report.state = NodeState::Failed;
                    report.error = Some(format!("expander panicked: {}", panic_text(p.as_ref())));
                    artifact = None;
                }
            }
        }
        let name = report.name.clone();
        self.settle(graph, id, report, artifact, on_event);
        if !staged.is_empty() {
            let added = staged.len();
            let range = graph.commit(staged);
            self.add_nodes(graph, range, on_event);
            on_event(&Event::Expanded { by: name, added });
        }
    }

    /// Record a node's final report and release (or skip) its dependents.
    fn settle(
        &mut self,
        graph: &BuildGraph,
        id: usize,
        report: NodeReport,
        artifact: Option<Artifact>,
        on_event: &(dyn Fn(&Event) + Sync),
    ) {
        let ok = artifact.is_some();
        if !ok && report.state == NodeState::Failed && !self.keep_going {
            self.stopped = true;
        }
        let slot = &mut self.slots[id];
        slot.phase = Phase::Done;
        slot.artifact = artifact;
        on_event(&Event::Finished(report.clone()));
        slot.report = Some(report);
        let deps = graph.dependents(NodeId(id));
        if ok {
            for d in deps {
                if let Some(Phase::Waiting(k)) = self.slots.get(d.0).map(|s| s.phase) {
                    if k <= 1 {
                        self.make_ready(graph, d.0);
                    } else {
                        self.slots[d.0].phase = Phase::Waiting(k - 1);
                    }
                }
            }
        } else {
            // Skip every waiting node downstream, iteratively.
            let mut stack: Vec<usize> = deps.iter().map(|d| d.0).collect();
            while let Some(d) = stack.pop() {
                if !matches!(self.slots.get(d).map(|s| s.phase), Some(Phase::Waiting(_))) {
                    continue;
                }
                let failed: Vec<String> = graph.nodes[d]
                    .inputs
                    .iter()
                    .filter(|i| self.slots[i.0].phase == Phase::Done && !self.slots[i.0].ok())
                    .map(|i| graph.nodes[i.0].name.clone())
                    .collect();
                let r = self.base_report(
                    graph,
                    d,
                    NodeState::Skipped,
                    RebuildReason::InputFailed {
                        inputs: dedup(failed),
                    },
                );
                let s = &mut self.slots[d];
                s.phase = Phase::Done;
                on_event(&Event::Finished(r.clone()));
                s.report = Some(r);
                stack.extend(graph.dependents(NodeId(d)).into_iter().map(|n| n.0));
            }
        }
    }

    /// Final per-node reports (by id) and artifacts. A skipped node's reason names every input
    /// that ended failed or skipped (known only once all are done, whatever the finishing order).
    pub fn into_results(
        mut self,
        graph: &BuildGraph,
    ) -> Vec<(Option<NodeReport>, Option<Artifact>)> {
        for id in 0..self.slots.len() {
            let Some(RebuildReason::InputFailed { .. }) =
                self.slots[id].report.as_ref().map(|r| &r.reason)
            else {
                continue;
            };
            let bad: Vec<String> = graph.nodes[id]
                .inputs
                .iter()
                .filter(|i| !self.slots[i.0].ok())
                .map(|i| graph.nodes[i.0].name.clone())
                .collect();
            if let Some(r) = self.slots[id].report.as_mut() {
                r.reason = RebuildReason::InputFailed { inputs: dedup(bad) };
            }
        }
        self.slots
            .into_iter()
            .map(|s| (s.report, s.artifact))
            .collect()
    }

    /// The manifest for the next build: this build's successful nodes, and the previous entry
    /// of nodes that failed or were skipped (so their next run is still explained).
    pub fn manifest(&self, graph: &BuildGraph) -> Manifest {
        let mut m = Manifest::new();
        for (id, n) in graph.nodes.iter().enumerate() {
            let Some(slot) = self.slots.get(id) else {
                continue;
            };
            match &slot.artifact {
                Some(a) if slot.ok() => {
                    let file = match &n.work {
                        Work::File(p) => Some(p.display().to_string()),
                        Work::Op(_) => None,
                    };
                    m.nodes.insert(
                        n.name.clone(),
                        ManifestEntry {
                            kind: n.kind().to_string(),
                            version: slot.version,
                            params: slot.params.clone(),
                            inputs: self.input_hashes(graph, id),
                            key: slot.key,
                            output: a.hash(),
                            file,
                        },
                    );
                }
                _ => {
                    if let Some(e) = self.prev.nodes.get(&n.name) {
                        m.nodes.insert(n.name.clone(), e.clone());
                    }
                }
            }
        }
        m
    }
}

fn dedup(mut v: Vec<String>) -> Vec<String> {
    v.sort();
    v.dedup();
    v
}
