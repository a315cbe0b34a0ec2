//! What each file-emitting node of a record's last build put into the output directory: the
//! node's output hash and the content hash of every file, kept beside the manifest
//! (`<record>/emitted.bin`).
//!
//! It lets a cached emitting node leave its files alone without reading its output: when the
//! node's output is the one it had then, the files it emits are the ones recorded, and a file
//! whose bytes on disk hash to the recorded hash needs no write. Only the disk is trusted, never
//! the record alone (a file edited, removed or staged and discarded since is read, found
//! different, and the node's output is read and written as usual). A missing or damaged record
//! only costs that reading.

use crate::artifact::Hash;
use crate::checked;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

const FORMAT: u32 = 1;

/// The files one node emitted: relative path → content hash, for the node's output `output`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(crate) struct NodeFiles {
    pub output: Hash,
    pub files: BTreeMap<String, Hash>,
}

/// Every emitting node's files, by node name.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub(crate) struct Emitted {
    format: u32,
    pub nodes: BTreeMap<String, NodeFiles>,
}

fn path(record_dir: &Path) -> PathBuf {
    record_dir.join("emitted.bin")
}

impl Emitted {
    pub(crate) fn new() -> Emitted {
        Emitted {
            format: FORMAT,
            nodes: BTreeMap::new(),
        }
    }

    /// The record's emitted files, or none when absent or unreadable.
    pub(crate) fn load(record_dir: &Path) -> Emitted {
        checked::load::<Emitted>(&path(record_dir))
            .filter(|e| e.format == FORMAT)
            .unwrap_or_default()
    }

    /// Writes them into `record_dir` unless they are what `before` (the loaded record) holds.
    pub(crate) fn save_over(&self, before: &Emitted, record_dir: &Path) -> std::io::Result<()> {
        if self == before {
            return Ok(());
        }
        checked::save(&path(record_dir), self)
    }
}
