//! The build report: for every node its state, reason, key, output and counts, in a
//! deterministic order (topological, ties broken by name), with JSON and DOT renderings.
//!
//! Nothing in a report depends on the number of worker threads except the durations, which
//! `BuildReport::without_timings` zeroes for comparisons.

use crate::artifact::{Artifact, Hash};
use crate::reason::RebuildReason;
use serde_json::{Value, json};
use std::collections::BTreeMap;
use std::fmt;

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum NodeState {
    Ran,
    Cached,
    /// Cached although at least one (transitive) upstream node ran in this build.
    CutOff,
    Failed,
    /// An input failed (or the build stopped).
    Skipped,
}

impl NodeState {
    pub fn as_str(&self) -> &'static str {
        match self {
            NodeState::Ran => "ran",
            NodeState::Cached => "cached",
            NodeState::CutOff => "cut off",
            NodeState::Failed => "failed",
            NodeState::Skipped => "skipped",
        }
    }

    /// Whether the node has a usable output.
    pub fn is_ok(&self) -> bool {
        matches!(self, NodeState::Ran | NodeState::Cached | NodeState::CutOff)
    }
}

impl fmt::Display for NodeState {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct NodeReport {
    pub name: String,
    pub kind: String,
    pub state: NodeState,
    pub reason: RebuildReason,
    pub duration_ms: f64,
    /// `Hash::ZERO` when the node was skipped before its key could be computed.
    pub key: Hash,
    pub output: Option<Hash>,
    pub counts: BTreeMap<String, u64>,
    pub notes: Vec<String>,
    pub error: Option<String>,
    /// Input node names, in input order.
    pub inputs: Vec<String>,
}

impl NodeReport {
    pub fn to_json(&self) -> Value {
        json!({
            "name": self.name,
            "kind": self.kind,
            "state": self.state.as_str(),
            "reason": self.reason.to_string(),
            "reason_kind": self.reason.tag(),
            "duration_ms": self.duration_ms,
            "key": self.key.to_hex(),
            "output": self.output.map(|h| h.to_hex()),
            "counts": self.counts,
            "notes": self.notes,
            "error": self.error,
            "inputs": self.inputs,
        })
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct BuildReport {
    /// Topological order, ties broken by name.
    pub nodes: Vec<NodeReport>,
    /// Every emitted file (relative path under the output directory) and its content hash.
    pub output_files: BTreeMap<String, Hash>,
    /// False when any node failed or was skipped.
    pub ok: bool,
    pub duration_ms: f64,
    /// Final artifact of every node that has one, by node name; not of nodes that emit files
    /// (their bytes are in `output_files` on disk).
    pub artifacts: BTreeMap<String, Artifact>,
}

impl BuildReport {
    pub fn node(&self, name: &str) -> Option<&NodeReport> {
        self.nodes.iter().find(|n| n.name == name)
    }

    /// The final artifact of node `name` (ran or cached), if it has one.
    pub fn artifact(&self, name: &str) -> Option<&Artifact> {
        self.artifacts.get(name)
    }

    /// Count of nodes in each state.
    pub fn count(&self, state: NodeState) -> usize {
        self.nodes.iter().filter(|n| n.state == state).count()
    }

    /// The same report with every duration set to zero, for comparing builds.
    pub fn without_timings(&self) -> BuildReport {
        let mut r = self.clone();
        r.duration_ms = 0.0;
        for n in &mut r.nodes {
            n.duration_ms = 0.0;
        }
        r
    }

    pub fn to_json(&self) -> Value {
        json!({
            "ok": self.ok,
            "duration_ms": self.duration_ms,
            "nodes": self.nodes.iter().map(NodeReport::to_json).collect::<Vec<_>>(),
            "output_files": self.output_files.iter().map(|(k, v)| (k.clone(), Value::from(v.to_hex()))).collect::<serde_json::Map<_, _>>(),
        })
    }

    /// Graphviz DOT of the whole (expanded) graph, each node labelled with kind and state.
    pub fn to_dot(&self) -> String {
        let mut s = String::from(
            "digraph build {\n  rankdir=LR;\n  node [shape=box, style=filled, fontname=\"Helvetica\"];\n",
        );
        let mut sorted: Vec<&NodeReport> = self.nodes.iter().collect();
        sorted.sort_by(|a, b| a.name.cmp(&b.name));
        for n in &sorted {
            let colour = match n.state {
                NodeState::Ran => "#f6c85f",
                NodeState::Cached => "#d9ead3",
                NodeState::CutOff => "#9fc5e8",
                NodeState::Failed => "#ea9999",
                NodeState::Skipped => "#cccccc",
            };
            s.push_str(&format!(
                "  \"{}\" [label=\"{}\\n{} · {}\", fillcolor=\"{}\"];\n",
                esc(&n.name),
                esc(&n.name),
                esc(&n.kind),
                n.state,
                colour
            ));
        }
        let mut edges: Vec<(&str, &str)> = sorted
            .iter()
            .flat_map(|n| n.inputs.iter().map(move |i| (i.as_str(), n.name.as_str())))
            .collect();
        edges.sort();
        edges.dedup();
        for (a, b) in edges {
            s.push_str(&format!("  \"{}\" -> \"{}\";\n", esc(a), esc(b)));
        }
        s.push_str("}\n");
        s
    }
}

fn esc(s: &str) -> String {
    s.replace('\\', "\\\\")
        .replace('"', "\\\"")
        .replace('\n', "\\n")
}
