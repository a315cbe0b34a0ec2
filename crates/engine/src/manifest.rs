//! The previous build's manifest, kept in `<cache>/manifest.bin`, from which rebuild reasons
//! are explained: per node name, what it was (kind, version, parameters, inputs and their
//! output hashes, source file) and what it produced (key, output hash).
//!
//! It is written atomically at the end of each build with a blake3 checksum in front; an
//! unreadable or corrupt manifest only costs explanations (every node reads as new), never a
//! wrong result, because caching itself is decided by keys alone.

use crate::artifact::Hash;
use crate::params::Params;
use crate::store::write_atomic;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

const FORMAT: u32 = 1;

/// What one node was in the previous build.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ManifestEntry {
    pub kind: String,
    pub version: u32,
    pub params: Params,
    /// Input node names with the output hashes they had.
    pub inputs: Vec<(String, Hash)>,
    pub key: Hash,
    pub output: Hash,
    /// The source path, for file nodes.
    pub file: Option<String>,
}

#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    pub format: u32,
    pub nodes: BTreeMap<String, ManifestEntry>,
}

pub fn manifest_path(cache_dir: &Path) -> PathBuf {
    cache_dir.join("manifest.bin")
}

impl Manifest {
    pub fn new() -> Self {
        Manifest {
            format: FORMAT,
            nodes: BTreeMap::new(),
        }
    }

    /// The previous manifest, or `None` when absent, unreadable or corrupt.
    pub fn load(cache_dir: &Path) -> Option<Manifest> {
        let bytes = std::fs::read(manifest_path(cache_dir)).ok()?;
        let (sum, payload) = bytes.split_first_chunk::<32>()?;
        if Hash::of(payload).0 != *sum {
            return None;
        }
        let m: Manifest = postcard::from_bytes(payload).ok()?;
        (m.format == FORMAT).then_some(m)
    }

    pub fn save(&self, cache_dir: &Path) -> std::io::Result<()> {
        let payload =
            postcard::to_stdvec(self).map_err(|e| std::io::Error::other(e.to_string()))?;
        let mut bytes = Hash::of(&payload).0.to_vec();
        bytes.extend_from_slice(&payload);
        write_atomic(&manifest_path(cache_dir), &bytes, false)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_saved_manifest_loads_back_and_a_damaged_one_reads_as_absent() {
        let dir = tempfile::tempdir().unwrap();
        let mut m = Manifest::new();
        m.nodes.insert(
            "a".into(),
            ManifestEntry {
                kind: "k".into(),
                version: 3,
                params: Params::new().with("x", 1.5).unwrap(),
                inputs: vec![("b".into(), Hash::of(b"b"))],
                key: Hash::of(b"key"),
                output: Hash::of(b"out"),
                file: None,
            },
        );
        m.save(dir.path()).unwrap();
        assert_eq!(Manifest::load(dir.path()), Some(m));
        let p = manifest_path(dir.path());
        let mut bytes = std::fs::read(&p).unwrap();
        let last = bytes.len() - 1;
        bytes[last] ^= 1;
        std::fs::write(&p, bytes).unwrap();
        assert_eq!(Manifest::load(dir.path()), None);
    }
}
