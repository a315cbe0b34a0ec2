//! The previous build's manifest, from which rebuild reasons are explained: per node name, what
//! it was (kind, version, parameters, inputs and their output hashes, source file) and what it
//! produced (key, output hash).
//!
//! Several graphs (a command line's recipes) may share one cache: each keeps its manifest in a
//! record of its own, `<cache>/records/<name>/manifest.bin`, named by the caller
//! (`BuildOptions::record`), so one graph's build never becomes another's baseline and `gc` keeps
//! what the last build of every record references. The caller may keep files of its own in its
//! record's directory. A `manifest.bin` at the cache root is what builds wrote before records:
//! builds ignore it and `gc` removes it.
//!
//! It is written atomically at the end of each build with a blake3 checksum in front; an
//! unreadable or corrupt manifest only costs explanations (every node reads as new), never a
//! wrong result, because caching itself is decided by keys alone.

use crate::artifact::Hash;
use crate::checked;
use crate::params::Params;
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

/// The manifest file in a record's directory (see [`record_dir`]).
pub fn manifest_path(record_dir: &Path) -> PathBuf {
    record_dir.join("manifest.bin")
}

/// The directory holding every record of a cache.
pub const RECORDS: &str = "records";

/// Whether `name` can name a record: 1 to 128 ASCII letters, digits, `.`, `_` or `-`, not
/// starting with `.` (one path component, never a temporary's name).
pub fn is_record_name(name: &str) -> bool {
    !name.is_empty()
        && name.len() <= 128
        && !name.starts_with('.')
        && name
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || matches!(b, b'.' | b'_' | b'-'))
}

/// The directory of record `name` in `cache_dir`.
pub fn record_dir(cache_dir: &Path, name: &str) -> PathBuf {
    cache_dir.join(RECORDS).join(name)
}

/// The names of the records in `cache_dir`, sorted (none when it has no `records/`).
pub fn records(cache_dir: &Path) -> std::io::Result<Vec<String>> {
    let dir = cache_dir.join(RECORDS);
    let entries = match std::fs::read_dir(&dir) {
        Ok(e) => e,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(e),
    };
    let mut names = Vec::new();
    for entry in entries {
        let entry = entry?;
        let name = entry.file_name().to_string_lossy().into_owned();
        if entry.file_type()?.is_dir() && is_record_name(&name) {
            names.push(name);
        }
    }
    names.sort();
    Ok(names)
}

impl Manifest {
    pub fn new() -> Self {
        Manifest {
            format: FORMAT,
            nodes: BTreeMap::new(),
        }
    }

    /// The manifest in `record_dir`, or `None` when absent, unreadable or corrupt.
    pub fn load(record_dir: &Path) -> Option<Manifest> {
        let m: Manifest = checked::load(&manifest_path(record_dir))?;
        (m.format == FORMAT).then_some(m)
    }

    /// Writes the manifest into `record_dir` (created if needed), atomically.
    pub fn save(&self, record_dir: &Path) -> std::io::Result<()> {
        checked::save(&manifest_path(record_dir), self)
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

    #[test]
    fn a_record_name_is_one_plain_path_component() {
        for ok in ["default", "didactic.toml-0123abcd", "a_b-c.d"] {
            assert!(is_record_name(ok), "{ok}");
        }
        let long = "x".repeat(129);
        for bad in [
            "",
            ".",
            "..",
            ".tmp-x",
            "a/b",
            "a\\b",
            "a b",
            "é",
            long.as_str(),
        ] {
            assert!(!is_record_name(bad), "{bad}");
        }
    }

    #[test]
    fn records_lists_the_record_directories_by_name() {
        let dir = tempfile::tempdir().unwrap();
        assert_eq!(records(dir.path()).unwrap(), Vec::<String>::new());
        Manifest::new().save(&record_dir(dir.path(), "b")).unwrap();
        Manifest::new().save(&record_dir(dir.path(), "a")).unwrap();
        std::fs::write(dir.path().join(RECORDS).join("stray"), b"x").unwrap();
        std::fs::create_dir(dir.path().join(RECORDS).join(".tmp-x")).unwrap();
        assert_eq!(records(dir.path()).unwrap(), ["a", "b"]);
    }
}
