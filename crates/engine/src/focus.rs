//! A focused build: only what the named nodes need. A build again after a failure runs its
//! failed nodes first, and the rest of the graph only once they succeed, so that a remedy which
//! does not reach the failure costs the failed nodes' part of the graph, not the whole graph
//! again.
//!
//! Decisions and why:
//! - A node is needed when it is named, when it has an expander (the named nodes may exist only
//!   once an expansion added them), or when a needed node takes it as an input. So the set is a
//!   function of the graph alone, never of which node finished first: the nodes a focused build
//!   runs are the same for any number of jobs.
//! - The set is computed again whenever an expansion grows the graph: a node held back earlier
//!   may be an input of a named node added since.
//! - A node a focused build does not need is skipped with [`crate::RebuildReason::Unfocused`],
//!   not failed: the caller decides whether to build the rest.

use crate::graph::BuildGraph;
use std::collections::BTreeSet;

/// The names a build is focused on (none: an ordinary build), and which nodes of the graph as
/// it was last seen they need.
#[derive(Debug, Default)]
pub(crate) struct Focus {
    names: BTreeSet<String>,
    needed: Vec<bool>,
}

impl Focus {
    pub fn new(names: BTreeSet<String>) -> Self {
        Focus {
            names,
            needed: Vec::new(),
        }
    }

    /// Whether the build is focused at all.
    pub fn is_on(&self) -> bool {
        !self.names.is_empty()
    }

    /// Whether node `id` of `graph` is needed (always, for an ordinary build).
    pub fn needs(&mut self, graph: &BuildGraph, id: usize) -> bool {
        if !self.is_on() {
            return true;
        }
        if self.needed.len() != graph.len() {
            self.needed = needed(graph, &self.names);
        }
        self.needed.get(id).copied().unwrap_or(true)
    }
}

/// Per node of `graph`: named in `names`, an expander, or an input (transitively) of one.
fn needed(graph: &BuildGraph, names: &BTreeSet<String>) -> Vec<bool> {
    let mut out = vec![false; graph.len()];
    let mut stack: Vec<usize> = (graph.nodes.iter().enumerate())
        .filter(|(_, n)| n.expander.is_some() || names.contains(&n.name))
        .map(|(k, _)| k)
        .collect();
    while let Some(k) = stack.pop() {
        if std::mem::replace(&mut out[k], true) {
            continue;
        }
        stack.extend(graph.nodes[k].inputs.iter().map(|i| i.0));
    }
    out
}
