//! The build graph: named nodes (source files and operations) and their input edges, held in a
//! petgraph `StableDiGraph`, plus `Expander`s that grow the graph while it builds.
//!
//! A node can only name inputs that already exist, so the graph is acyclic by construction,
//! including after expansion. Names are unique: they are how reports, reasons and lock files
//! refer to nodes, and the only identity that is the same across builds and thread counts.

use crate::artifact::Artifact;
use crate::op::{OpError, Operation};
use petgraph::stable_graph::{NodeIndex, StableDiGraph};
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;

/// A node of one `BuildGraph` (meaningless in another graph).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct NodeId(pub(crate) usize);

#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum GraphError {
    #[error("a node named `{0}` already exists")]
    DuplicateName(String),
    #[error("node names must not be empty")]
    EmptyName,
    #[error("node `{node}` names an input that is not in this graph")]
    UnknownInput { node: String },
    #[error("an expander can only be set on a node added by the same expansion")]
    NotNew,
}

/// Grows the graph once a node's output is known.
pub trait Expander: Send + Sync {
    /// Called once the node's output is known (ran or cached), before any node added here runs.
    fn expand(&self, output: &Artifact, x: &mut Expansion) -> Result<(), OpError>;
}

#[derive(Clone)]
pub(crate) enum Work {
    File(PathBuf),
    Op(Arc<dyn Operation>),
}

#[derive(Clone)]
pub(crate) struct NodeData {
    pub name: String,
    pub work: Work,
    pub inputs: Vec<NodeId>,
    pub expander: Option<Arc<dyn Expander>>,
}

impl NodeData {
    pub fn kind(&self) -> &'static str {
        match &self.work {
            Work::File(_) => "file",
            Work::Op(op) => op.kind(),
        }
    }
}

/// The DAG of operations. Node `NodeId(i)` is `nodes[i]` and petgraph node `pix[i]`.
#[derive(Default)]
pub struct BuildGraph {
    pub(crate) nodes: Vec<NodeData>,
    by_name: BTreeMap<String, NodeId>,
    dag: StableDiGraph<usize, ()>,
    pix: Vec<NodeIndex>,
}

impl BuildGraph {
    pub fn new() -> Self {
        BuildGraph::default()
    }

    /// A source node whose output is the file's content (read at build time; key = content hash).
    pub fn add_file(&mut self, name: &str, path: PathBuf) -> Result<NodeId, GraphError> {
        self.check_name(name)?;
        Ok(self.push(NodeData {
            name: name.to_string(),
            work: Work::File(path),
            inputs: vec![],
            expander: None,
        }))
    }

    /// An operation node over `inputs` (passed to `run` in this order).
    pub fn add_op(
        &mut self,
        name: &str,
        op: Arc<dyn Operation>,
        inputs: &[NodeId],
    ) -> Result<NodeId, GraphError> {
        self.check_name(name)?;
        if inputs.iter().any(|i| i.0 >= self.nodes.len()) {
            return Err(GraphError::UnknownInput {
                node: name.to_string(),
            });
        }
        Ok(self.push(NodeData {
            name: name.to_string(),
            work: Work::Op(op),
            inputs: inputs.to_vec(),
            expander: None,
        }))
    }

    /// Attach an expander to `node` (an id from another graph is ignored).
    pub fn set_expander(&mut self, node: NodeId, exp: Arc<dyn Expander>) {
        if let Some(n) = self.nodes.get_mut(node.0) {
            n.expander = Some(exp);
        }
    }

    pub fn node(&self, name: &str) -> Option<NodeId> {
        self.by_name.get(name).copied()
    }

    pub fn name(&self, id: NodeId) -> Option<&str> {
        self.nodes.get(id.0).map(|n| n.name.as_str())
    }

    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    fn check_name(&self, name: &str) -> Result<(), GraphError> {
        if name.is_empty() {
            return Err(GraphError::EmptyName);
        }
        if self.by_name.contains_key(name) {
            return Err(GraphError::DuplicateName(name.to_string()));
        }
        Ok(())
    }

    fn push(&mut self, data: NodeData) -> NodeId {
        let id = NodeId(self.nodes.len());
        let ix = self.dag.add_node(id.0);
        for input in &data.inputs {
            if let Some(&from) = self.pix.get(input.0) {
                self.dag.add_edge(from, ix, ());
            }
        }
        self.by_name.insert(data.name.clone(), id);
        self.nodes.push(data);
        self.pix.push(ix);
        id
    }

    /// Nodes that take `id` as an input, in id order.
    pub(crate) fn dependents(&self, id: NodeId) -> Vec<NodeId> {
        let Some(&ix) = self.pix.get(id.0) else {
            return vec![];
        };
        let mut out: Vec<NodeId> = self
            .dag
            .neighbors_directed(ix, petgraph::Direction::Outgoing)
            .filter_map(|n| self.dag.node_weight(n))
            .map(|&i| NodeId(i))
            .collect();
        out.sort();
        out.dedup();
        out
    }

    /// Append staged nodes; returns the range of new ids.
    pub(crate) fn commit(&mut self, staged: Vec<NodeData>) -> std::ops::Range<usize> {
        let start = self.nodes.len();
        for n in staged {
            self.push(n);
        }
        start..self.nodes.len()
    }
}

/// The graph as an expander sees it: lookups over existing and newly added nodes, and additions
/// that take effect only if the expander succeeds.
pub struct Expansion<'g> {
    graph: &'g BuildGraph,
    staged: Vec<NodeData>,
    staged_names: BTreeMap<String, NodeId>,
}

impl<'g> Expansion<'g> {
    pub(crate) fn new(graph: &'g BuildGraph) -> Self {
        Expansion {
            graph,
            staged: Vec::new(),
            staged_names: BTreeMap::new(),
        }
    }

    pub(crate) fn into_staged(self) -> Vec<NodeData> {
        self.staged
    }

    pub fn node(&self, name: &str) -> Option<NodeId> {
        self.graph
            .node(name)
            .or_else(|| self.staged_names.get(name).copied())
    }

    /// Number of nodes added so far.
    pub fn added(&self) -> usize {
        self.staged.len()
    }

    fn check_name(&self, name: &str) -> Result<(), GraphError> {
        self.graph.check_name(name)?;
        if self.staged_names.contains_key(name) {
            return Err(GraphError::DuplicateName(name.to_string()));
        }
        Ok(())
    }

    fn stage(&mut self, data: NodeData) -> NodeId {
        let id = NodeId(self.graph.nodes.len() + self.staged.len());
        self.staged_names.insert(data.name.clone(), id);
        self.staged.push(data);
        id
    }

    pub fn add_op(
        &mut self,
        name: &str,
        op: Arc<dyn Operation>,
        inputs: &[NodeId],
    ) -> Result<NodeId, GraphError> {
        self.check_name(name)?;
        let limit = self.graph.nodes.len() + self.staged.len();
        if inputs.iter().any(|i| i.0 >= limit) {
            return Err(GraphError::UnknownInput {
                node: name.to_string(),
            });
        }
        Ok(self.stage(NodeData {
            name: name.to_string(),
            work: Work::Op(op),
            inputs: inputs.to_vec(),
            expander: None,
        }))
    }

    pub fn add_file(&mut self, name: &str, path: PathBuf) -> Result<NodeId, GraphError> {
        self.check_name(name)?;
        Ok(self.stage(NodeData {
            name: name.to_string(),
            work: Work::File(path),
            inputs: vec![],
            expander: None,
        }))
    }

    /// Attach an expander to a node added by this expansion (expansion may cascade).
    pub fn set_expander(&mut self, node: NodeId, exp: Arc<dyn Expander>) -> Result<(), GraphError> {
        let base = self.graph.nodes.len();
        match node
            .0
            .checked_sub(base)
            .and_then(|i| self.staged.get_mut(i))
        {
            Some(n) => {
                n.expander = Some(exp);
                Ok(())
            }
            None => Err(GraphError::NotNew),
        }
    }
}
