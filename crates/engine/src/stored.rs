//! Outputs a cache hit leaves in the store until something reads them.
//!
//! A node's key needs only its inputs' hashes, which a cache hit knows from the action record,
//! so a node whose operation says its output may stay unread (`Operation::lazy_output`) hands
//! its dependents a [`Stored`] artifact: the object is read and verified the first time its
//! bytes are asked for (by a dependent that runs, the files to write, the caller after the
//! build) and never when nobody asks, which is every time in a build where nothing changed.
//!
//! Reading late must not make a damaged cache entry fatal where reading early would have
//! repaired it: a stored artifact keeps the operation and inputs that made it, and when the
//! object is missing or does not match its hash it runs the operation again, checks that the
//! output has the same hash (the operation is pure), and puts it back into the store.

use crate::artifact::{Artifact, Hash};
use crate::op::{Operation, Quiet};
use crate::store::{Load, Store};
use crate::worker::panic_text;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};

/// An output in the store, read on first use.
pub(crate) struct Stored {
    store: Store,
    hash: Hash,
    /// Its size in bytes, when its record gives it.
    len: Option<u64>,
    /// The node that made it, for messages.
    node: String,
    /// How to make it again.
    op: Arc<dyn Operation>,
    inputs: Vec<Artifact>,
    /// The bytes once read (an artifact in memory), or why they cannot be had.
    read: OnceLock<Result<Artifact, String>>,
    /// What was wrong with the stored object, when it had to be made again.
    repaired: OnceLock<String>,
    /// The repair was told (once, by the first dependent that read it).
    told: AtomicBool,
}

impl Stored {
    /// The output `hash` (of `len` bytes, when known) of node `node`, made by `op` from
    /// `inputs`.
    pub(crate) fn new(
        store: &Store,
        (hash, len): (Hash, Option<u64>),
        node: &str,
        op: Arc<dyn Operation>,
        inputs: Vec<Artifact>,
    ) -> Stored {
        Stored {
            store: store.clone(),
            hash,
            len,
            node: node.to_string(),
            op,
            inputs,
            read: OnceLock::new(),
            repaired: OnceLock::new(),
            told: AtomicBool::new(false),
        }
    }

    pub(crate) fn hash(&self) -> Hash {
        self.hash
    }

    pub(crate) fn is_read(&self) -> bool {
        matches!(self.read.get(), Some(Ok(_)))
    }

    /// The node that made it and what was wrong with its stored object, if it was made again
    /// and nobody asked before.
    pub(crate) fn take_repair(&self) -> Option<(String, String)> {
        let d = self.repaired.get()?;
        (!self.told.swap(true, Ordering::SeqCst)).then(|| (self.node.clone(), d.clone()))
    }

    /// The verified bytes: from the store, or made again when the stored object is damaged.
    pub(crate) fn read(&self) -> Result<&[u8], String> {
        match self.read.get_or_init(|| self.fetch()) {
            Ok(a) => a.bytes().map_err(|e| e.message),
            Err(e) => Err(e.clone()),
        }
    }

    fn fetch(&self) -> Result<Artifact, String> {
        let damage = match self.store.load_object(self.hash, self.len) {
            Load::Hit(a) => return Ok(a),
            Load::Missing => format!("object {} is missing", self.hash.short()),
            Load::Corrupt(d) => d,
            Load::Unreadable(e) => {
                return Err(format!(
                    "the cached output of `{}` could not be read: {e}",
                    self.node
                ));
            }
        };
        let made = self.remake().map_err(|e| {
            format!(
                "the cached output of `{}` is damaged ({damage}) and could not be made again: {e}",
                self.node
            )
        })?;
        // A failed write only costs the next build the same repair.
        let _ = self.store.put_object(&made);
        let _ = self.repaired.set(damage);
        Ok(made)
    }

    fn remake(&self) -> Result<Artifact, String> {
        let out = catch_unwind(AssertUnwindSafe(|| self.op.run(&Quiet, &self.inputs)))
            .map_err(|p| format!("operation panicked: {}", panic_text(p.as_ref())))?
            .map_err(|e| e.message)?;
        if out.artifact.hash() != self.hash {
            return Err(format!(
                "it ran to {} instead of {}: the operation is not deterministic",
                out.artifact.hash().short(),
                self.hash.short()
            ));
        }
        Ok(out.artifact)
    }
}
