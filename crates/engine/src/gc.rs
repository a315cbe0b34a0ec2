//! Cache maintenance: `gc` keeps only the entries that the given lock files or the last build of
//! any record (`manifest`, and what the caller derived from it: `derive`) reference (node keys
//! and output objects) and removes everything else, including stray temporary files and the
//! root `manifest.bin` that builds wrote before records; `forget` removes a record, so what only
//! its last build referenced goes at the next `gc`; `clean` removes the cache. Each removes only
//! the cache's own entries (`marker` says which): a file of the user's left inside stays.
//! All touch only a directory marked as a cache (`marker`), and take the directory lock so they
//! never race a build.

use crate::artifact::Hash;
use crate::dirlock::DirLock;
use crate::error::EngineError;
use crate::lockfile::{LockFile, LockedNode};
use crate::manifest::{self, Manifest};
use crate::marker;
use std::collections::BTreeSet;
use std::path::Path;

#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct GcStats {
    pub kept: usize,
    pub removed: usize,
    pub bytes_freed: u64,
}

fn lock_now(cache_dir: &Path) -> Result<DirLock, EngineError> {
    let lock = DirLock::try_acquire(cache_dir)?.ok_or_else(|| EngineError::Locked {
        path: cache_dir.to_path_buf(),
    })?;
    if lock.read_only() {
        return Err(EngineError::Invalid {
            path: cache_dir.to_path_buf(),
            message: "the cache cannot be written (a read-only disk or no permission): nothing was removed".into(),
        });
    }
    Ok(lock)
}

/// Remove every object and action referenced neither by a lock file of `keep` nor by the last
/// build of any record in the cache (nothing to do when the cache does not exist; an error,
/// touching nothing, when the directory is not a cache). The records' last builds are read under
/// the cache lock, so a build that finished just before is kept whole.
pub fn gc(cache_dir: &Path, keep: &[LockFile]) -> Result<GcStats, EngineError> {
    gc_and(cache_dir, keep, &|| {})
}

/// [`gc`], also running `tidy` while the cache lock is held: the caller's sweep of what killed
/// builds left outside the cache (beside outputs and recipes), which no build can be writing
/// while the lock is held.
pub fn gc_and(
    cache_dir: &Path,
    keep: &[LockFile],
    tidy: &dyn Fn(),
) -> Result<GcStats, EngineError> {
    if !cache_dir.exists() {
        return Ok(GcStats::default());
    }
    marker::require(cache_dir)?;
    let _lock = lock_now(cache_dir)?;
    tidy();
    let records = manifest::records(cache_dir).map_err(|e| EngineError::io(cache_dir, e))?;
    let last: Vec<LockFile> = records
        .iter()
        .filter_map(|r| last_build(cache_dir, r))
        .collect();
    let nodes = || keep.iter().chain(&last).flat_map(|l| l.nodes.values());
    let objects: BTreeSet<Hash> = nodes().map(|n| n.output).collect();
    let actions: BTreeSet<Hash> = nodes().map(|n| n.key).collect();
    let mut stats = GcStats::default();
    sweep(&cache_dir.join("objects"), &objects, &mut stats)?;
    sweep(&cache_dir.join("actions"), &actions, &mut stats)?;
    // The manifest of the builds before records: no build reads it any more.
    let legacy = manifest::manifest_path(cache_dir);
    if let Ok(m) = std::fs::metadata(&legacy) {
        std::fs::remove_file(&legacy).map_err(|e| EngineError::io(&legacy, e))?;
        stats.removed += 1;
        stats.bytes_freed += m.len();
    }
    Ok(stats)
}

/// Removes record `name` from the cache (its manifest and whatever its caller kept beside it),
/// so that the next [`gc`] no longer keeps what only its last build referenced; `false` when
/// there was no such record. Takes the cache lock; an error, touching nothing, when the directory
/// is not a cache or the name cannot be a record's.
pub fn forget(cache_dir: &Path, name: &str) -> Result<bool, EngineError> {
    if !manifest::is_record_name(name) {
        return Err(EngineError::Invalid {
            path: cache_dir.to_path_buf(),
            message: format!("`{name}` cannot name a build record"),
        });
    }
    let dir = manifest::record_dir(cache_dir, name);
    if !dir.exists() {
        return Ok(false);
    }
    marker::require(cache_dir)?;
    let _lock = lock_now(cache_dir)?;
    marker::remove_record(&dir)?;
    Ok(true)
}

fn sweep(dir: &Path, keep: &BTreeSet<Hash>, stats: &mut GcStats) -> Result<(), EngineError> {
    let entries = match std::fs::read_dir(dir) {
        Ok(e) => e,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(EngineError::io(dir, e)),
    };
    let mut paths = Vec::new();
    for entry in entries {
        let entry = entry.map_err(|e| EngineError::io(dir, e))?;
        let kind = entry.file_type().map_err(|e| EngineError::io(dir, e))?;
        // Only the store's own files: entries named by hashes and temporaries of their writes.
        let name = entry.file_name();
        let name = name.to_string_lossy();
        if kind.is_file() && (Hash::from_hex(&name).is_ok() || name.starts_with(".tmp")) {
            paths.push(entry.path());
        }
    }
    paths.sort();
    for path in paths {
        let referenced = path
            .file_name()
            .and_then(|n| n.to_str())
            .and_then(|n| Hash::from_hex(n).ok())
            .is_some_and(|h| keep.contains(&h));
        if referenced {
            stats.kept += 1;
            continue;
        }
        let size = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
        std::fs::remove_file(&path).map_err(|e| EngineError::io(&path, e))?;
        stats.removed += 1;
        stats.bytes_freed += size;
    }
    Ok(())
}

/// What the last build of record `record` in `cache_dir` referenced, as a lock file: its nodes
/// and what the caller derived from them (named `derived:<name>`); `None` when the record has no
/// readable manifest.
pub fn last_build(cache_dir: &Path, record: &str) -> Option<LockFile> {
    let dir = manifest::record_dir(cache_dir, record);
    let m = Manifest::load(&dir)?;
    let derived = crate::derive::recorded(&dir)
        .into_iter()
        .map(|(n, e)| (format!("derived:{n}"), e));
    let nodes = m
        .nodes
        .into_iter()
        .map(|(n, e)| {
            (
                n,
                LockedNode {
                    key: e.key,
                    output: e.output,
                },
            )
        })
        .chain(derived)
        .collect();
    Some(LockFile {
        nodes,
        outputs: Default::default(),
    })
}

/// What [`clean`] did.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Cleaned {
    /// There was no such directory.
    Absent,
    /// The cache and its directory are gone.
    Removed,
    /// The cache's entries are gone; the directory stays, holding these paths (relative to it)
    /// that were never the cache's.
    Kept(Vec<String>),
}

/// Removes the cache: its own entries, then its directory unless it holds anything else. A
/// directory that is not marked as a cache is an error and is not touched (not even by the lock
/// file).
pub fn clean(cache_dir: &Path) -> Result<Cleaned, EngineError> {
    if !cache_dir.exists() {
        return Ok(Cleaned::Absent);
    }
    marker::require(cache_dir)?;
    let lock = lock_now(cache_dir)?;
    let left = marker::remove_own(cache_dir);
    drop(lock);
    Ok(match left? {
        left if left.is_empty() => Cleaned::Removed,
        left => Cleaned::Kept(left),
    })
}
