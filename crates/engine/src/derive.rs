//! Derived artifacts: what a caller computes from a build's outputs after the build (the
//! figures of a report), cached like the output of a node.
//!
//! A derivation is an [`Operation`] the caller runs on outputs of the build, outside the graph:
//! it is not a node, so it is neither in the build's report nor in the lock file (it says
//! nothing about the build's reproducibility), yet it is computed once per distinct input. It is
//! keyed exactly like a node (kind, version, canonical parameters, the hashes of its inputs) and
//! stored the same way (an action record and an object, verified when read), so its inputs are
//! read only when it has to run: a lazy input stays in the store on a hit. What a record's last
//! build derived is listed in the record (`derived.bin`), and `gc` keeps it as it keeps the
//! record's last build.

use crate::artifact::{Artifact, Hash};
use crate::build::BuildOptions;
use crate::checked;
use crate::error::EngineError;
use crate::key::op_key;
use crate::lockfile::LockedNode;
use crate::op::{OpError, Operation, Quiet};
use crate::store::{ActionRecord, Load, Store};
use crate::worker::panic_text;
use std::collections::BTreeMap;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The derived entries of a record, by the caller's name for each.
type Entries = BTreeMap<String, LockedNode>;

fn list_path(record_dir: &Path) -> PathBuf {
    record_dir.join("derived.bin")
}

/// What the last build of the record in `record_dir` derived (none when unreadable).
pub(crate) fn recorded(record_dir: &Path) -> Entries {
    checked::load(&list_path(record_dir)).unwrap_or_default()
}

/// The derivations of one build of one record.
pub struct Derivations {
    store: Store,
    record_dir: PathBuf,
    before: Entries,
    used: Mutex<Entries>,
}

impl Derivations {
    /// The derivations of a build with options `opts` (its cache and record); take them under
    /// the cache's lock, as the build.
    pub fn open(opts: &BuildOptions) -> Result<Derivations, EngineError> {
        let record_dir = opts.record_dir();
        Ok(Derivations {
            store: Store::open_for(&opts.cache_dir, opts.read_only)?,
            before: recorded(&record_dir),
            record_dir,
            used: Mutex::new(Entries::new()),
        })
    }

    /// The output of `op` on `inputs`: from the cache, else run (on this thread) and stored.
    /// `name` names the derivation in the record.
    pub fn derive(
        &self,
        name: &str,
        op: &dyn Operation,
        inputs: &[Artifact],
    ) -> Result<Artifact, OpError> {
        let hashes: Vec<Hash> = inputs.iter().map(Artifact::hash).collect();
        let key = op_key(op.kind(), op.version(), &op.params(), &hashes);
        let artifact = match self.cached(key) {
            Some(a) => a,
            None => self.run(key, op, inputs)?,
        };
        let entry = LockedNode {
            key,
            output: artifact.hash(),
        };
        let mut used = self.used.lock().unwrap_or_else(|p| p.into_inner());
        used.insert(name.to_string(), entry);
        Ok(artifact)
    }

    fn cached(&self, key: Hash) -> Option<Artifact> {
        let Load::Hit(rec) = self.store.load_action(key) else {
            return None;
        };
        match self.store.load_object(rec.output, rec.output_len) {
            Load::Hit(a) => Some(a),
            _ => None,
        }
    }

    fn run(&self, key: Hash, op: &dyn Operation, inputs: &[Artifact]) -> Result<Artifact, OpError> {
        let out = catch_unwind(AssertUnwindSafe(|| op.run(&Quiet, inputs)))
            .map_err(|p| format!("operation panicked: {}", panic_text(p.as_ref())))??;
        let rec = ActionRecord::of(&out.artifact, out.counts, out.notes);
        // Not cached is only slower next time.
        let _ = self
            .store
            .put_object(&out.artifact)
            .and_then(|()| self.store.put_action(key, &rec));
        Ok(out.artifact)
    }

    /// Lists what this build derived in the record (for `gc`), unless the record lists it
    /// already.
    pub fn save(&self) -> Result<(), EngineError> {
        let used = self.used.lock().unwrap_or_else(|p| p.into_inner());
        if *used == self.before || self.store.read_only() {
            return Ok(());
        }
        let path = list_path(&self.record_dir);
        checked::save(&path, &*used).map_err(|e| EngineError::io(&path, e))
    }
}
