//! The on-disk, content-addressed cache.
//!
//! Layout: `<cache>/objects/<hash>` holds artifact bytes, named by their blake3;
//! `<cache>/actions/<key>` holds a small record (output hash and size, counts, notes) prefixed by
//! the blake3 of its payload; the recorded size bounds the object's read, so a file of any other
//! size in its place is corrupt before a byte of it is read. Every read re-hashes what it read,
//! so a truncated, altered or half-written entry is reported as corrupt and never used (and
//! anything but a regular file is not even read: see `entry`); every write goes to a temporary
//! file in the same directory and is renamed into place, so readers see either the old entry or
//! the whole new one.

use crate::artifact::{Artifact, Hash};
use crate::entry;
use crate::error::EngineError;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};

/// What a cache read found.
#[derive(Debug)]
pub enum Load<T> {
    Hit(T),
    Missing,
    /// The entry exists but cannot be trusted; the text says why.
    Corrupt(String),
    /// The entry could not be read (an I/O error, e.g. too many open files): nothing is known
    /// about it, so it is neither used nor replaced.
    Unreadable(String),
}

/// The cached record of one action (node key).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ActionRecord {
    pub output: Hash,
    pub counts: BTreeMap<String, u64>,
    pub notes: Vec<String>,
    /// The output's size in bytes, which bounds its read (unknown in records written before
    /// sizes were recorded).
    pub output_len: Option<u64>,
}

impl ActionRecord {
    /// The record of an action that produced `output`.
    pub fn of(output: &Artifact, counts: BTreeMap<String, u64>, notes: Vec<String>) -> Self {
        ActionRecord {
            output: output.hash(),
            counts,
            notes,
            output_len: output.bytes().ok().map(|b| b.len() as u64),
        }
    }
}

#[derive(Serialize, Deserialize)]
struct ActionFile {
    key: Hash,
    record: ActionRecord,
}

/// An action file as written before outputs' sizes were recorded: still read, so that a cache
/// outlives the change.
#[derive(Deserialize)]
struct ActionFileWithoutSize {
    key: Hash,
    output: Hash,
    counts: BTreeMap<String, u64>,
    notes: Vec<String>,
}

impl ActionFileWithoutSize {
    fn upgraded(self) -> ActionFile {
        ActionFile {
            key: self.key,
            record: ActionRecord {
                output: self.output,
                counts: self.counts,
                notes: self.notes,
                output_len: None,
            },
        }
    }
}

/// The most bytes an action file may hold (its record is an output's hash, counts and notes).
const MAX_ACTION_BYTES: u64 = 64 << 20;

/// A handle on a cache directory.
#[derive(Debug, Clone)]
pub struct Store {
    root: PathBuf,
    /// Entries are read, never written nor removed (a cache the build may only read).
    read_only: bool,
}

impl Store {
    /// Open (creating if needed) the cache at `root`.
    pub fn open(root: &Path) -> Result<Store, EngineError> {
        for sub in ["objects", "actions"] {
            let d = root.join(sub);
            std::fs::create_dir_all(&d).map_err(|e| EngineError::io(&d, e))?;
        }
        Ok(Store {
            root: root.to_path_buf(),
            read_only: false,
        })
    }

    /// Open the cache at `root` for reading only: what is missing stays missing, and the puts
    /// store nothing (what a build makes then lives as long as the build).
    pub fn open_read_only(root: &Path) -> Store {
        Store {
            root: root.to_path_buf(),
            read_only: true,
        }
    }

    /// [`Store::open`], or [`Store::open_read_only`] when `read_only`.
    pub fn open_for(root: &Path, read_only: bool) -> Result<Store, EngineError> {
        if read_only {
            Ok(Store::open_read_only(root))
        } else {
            Store::open(root)
        }
    }

    pub fn read_only(&self) -> bool {
        self.read_only
    }

    /// What a read does with a wrong kind of file in place of an entry: a cache only read keeps it.
    fn wrong(&self) -> entry::Wrong {
        if self.read_only {
            entry::Wrong::Keep
        } else {
            entry::Wrong::Remove
        }
    }

    /// Removes the temporaries of atomic writes (`.tmp-*`) left in `objects/` and `actions/`, and
    /// beside the cache's marker, by a process killed mid-write; returns how many. Only the
    /// engine writes there, and only under the cache lock (the marker before it, by a build that
    /// finds it written if its own write fails), so with the lock held every such file is debris
    /// (`gc` removes them too, as unreferenced entries). The records are the command line's to
    /// sweep, each for its own recipe.
    pub fn sweep_temporaries(&self) -> Result<usize, EngineError> {
        let mut removed = 0;
        if self.read_only {
            return Ok(0);
        }
        for sub in ["objects", "actions"] {
            let d = self.root.join(sub);
            let entries = std::fs::read_dir(&d).map_err(|e| EngineError::io(&d, e))?;
            for entry in entries {
                let entry = entry.map_err(|e| EngineError::io(&d, e))?;
                let is_file = entry.file_type().is_ok_and(|t| t.is_file());
                if is_file && entry.file_name().to_string_lossy().starts_with(TEMP_PREFIX) {
                    let path = entry.path();
                    std::fs::remove_file(&path).map_err(|e| EngineError::io(&path, e))?;
                    removed += 1;
                }
            }
        }
        let marker = self.root.join(crate::marker::MARKER);
        removed += sweep_temporaries_of(&marker).map_err(|e| EngineError::io(&self.root, e))?;
        Ok(removed)
    }

    pub fn root(&self) -> &Path {
        &self.root
    }

    pub fn object_path(&self, h: Hash) -> PathBuf {
        self.root.join("objects").join(h.to_hex())
    }

    pub fn action_path(&self, key: Hash) -> PathBuf {
        self.root.join("actions").join(key.to_hex())
    }

    /// Read and verify the object named `h`, of `len` bytes when its record says so (a file of
    /// another size is corrupt, and is not read).
    pub fn load_object(&self, h: Hash, len: Option<u64>) -> Load<Artifact> {
        let size = len.map_or(entry::Size::Any, entry::Size::Recorded);
        let bytes = match entry::read_as(&self.object_path(h), self.wrong(), size) {
            entry::Read::Bytes(b) => b,
            entry::Read::Missing => return Load::Missing,
            entry::Read::Damaged(d) => return Load::Corrupt(format!("object {}: {d}", h.short())),
            entry::Read::Failed(e) => {
                return Load::Unreadable(format!("object {} unreadable: {e}", h.short()));
            }
        };
        let len = bytes.len();
        let a = Artifact::from_bytes(bytes);
        if a.hash() == h {
            Load::Hit(a)
        } else {
            Load::Corrupt(format!(
                "object {} has hash mismatch ({len} bytes hash to {})",
                h.short(),
                a.hash().short()
            ))
        }
    }

    /// Whether the object named `h` is in the store, without reading it.
    /// Something other than a regular file at its path is removed, as a read would.
    pub fn has_object(&self, h: Hash) -> bool {
        entry::present(&self.object_path(h), self.wrong())
    }

    pub fn put_object(&self, a: &Artifact) -> std::io::Result<()> {
        if self.read_only {
            return Ok(());
        }
        let bytes = a.bytes().map_err(|e| std::io::Error::other(e.message))?;
        write_atomic(&self.object_path(a.hash()), bytes, false)
    }

    /// Read and verify the action record for `key`.
    pub fn load_action(&self, key: Hash) -> Load<ActionRecord> {
        let size = entry::Size::AtMost(MAX_ACTION_BYTES);
        let bytes = match entry::read_as(&self.action_path(key), self.wrong(), size) {
            entry::Read::Bytes(b) => b,
            entry::Read::Missing => return Load::Missing,
            entry::Read::Damaged(d) => {
                return Load::Corrupt(format!("action {}: {d}", key.short()));
            }
            entry::Read::Failed(e) => {
                return Load::Unreadable(format!("action {} unreadable: {e}", key.short()));
            }
        };
        let Some((sum, payload)) = bytes.split_first_chunk::<32>() else {
            return Load::Corrupt(format!(
                "action {} truncated ({} bytes)",
                key.short(),
                bytes.len()
            ));
        };
        if Hash::of(payload).0 != *sum {
            return Load::Corrupt(format!("action {} has hash mismatch", key.short()));
        }
        let decoded = postcard::from_bytes::<ActionFile>(payload).or_else(|e| {
            postcard::from_bytes::<ActionFileWithoutSize>(payload)
                .map(ActionFileWithoutSize::upgraded)
                .map_err(|_| e)
        });
        match decoded {
            Ok(f) if f.key == key => Load::Hit(f.record),
            Ok(f) => Load::Corrupt(format!(
                "action {} records key {}",
                key.short(),
                f.key.short()
            )),
            Err(e) => Load::Corrupt(format!("action {} undecodable: {e}", key.short())),
        }
    }

    pub fn put_action(&self, key: Hash, record: &ActionRecord) -> std::io::Result<()> {
        if self.read_only {
            return Ok(());
        }
        let payload = postcard::to_stdvec(&ActionFile {
            key,
            record: record.clone(),
        })
        .map_err(|e| std::io::Error::other(e.to_string()))?;
        let mut bytes = Hash::of(&payload).0.to_vec();
        bytes.extend_from_slice(&payload);
        write_atomic(&self.action_path(key), &bytes, false)
    }
}

/// The prefix of every temporary file of an atomic write.
pub const TEMP_PREFIX: &str = ".tmp-";

/// The prefix of the temporaries [`write_atomic`] makes for `path`: [`TEMP_PREFIX`], the file's
/// name and a dot (`.tmp-report.json.`), so that debris a killed write left can be told from
/// anyone else's files and swept ([`sweep_temporaries_of`]).
pub fn temp_prefix_of(path: &Path) -> String {
    let name = path
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    format!("{TEMP_PREFIX}{name}.")
}

/// Removes the temporaries [`write_atomic`] left beside `path` (a process killed mid-write);
/// returns how many. Only for a path whose writers the caller's lock excludes.
pub fn sweep_temporaries_of(path: &Path) -> std::io::Result<usize> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let prefix = temp_prefix_of(path);
    let mut removed = 0;
    let entries = match std::fs::read_dir(dir) {
        Ok(e) => e,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(0),
        Err(e) => return Err(e),
    };
    for entry in entries {
        let entry = entry?;
        let is_file = entry.file_type().is_ok_and(|t| t.is_file());
        if is_file && entry.file_name().to_string_lossy().starts_with(&prefix) {
            std::fs::remove_file(entry.path())?;
            removed += 1;
        }
    }
    Ok(removed)
}

/// Write `bytes` to `path` through a temporary file in the same directory and a rename.
/// `durable` also flushes the data to disk before the rename (used for user-visible outputs).
/// The temporary's name starts with [`temp_prefix_of`] `path`.
pub fn write_atomic(path: &Path, bytes: &[u8], durable: bool) -> std::io::Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    std::fs::create_dir_all(&dir)?;
    let mut b = tempfile::Builder::new();
    let prefix = temp_prefix_of(path);
    b.prefix(&prefix);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        b.permissions(std::fs::Permissions::from_mode(0o644));
    }
    let mut tmp = b.tempfile_in(&dir)?;
    tmp.write_all(bytes)?;
    if durable {
        tmp.as_file().sync_data()?;
    }
    crate::crash::point(path);
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_truncated_object_or_action_reads_as_corrupt() {
        let dir = tempfile::tempdir().unwrap();
        let s = Store::open(dir.path()).unwrap();
        let a = Artifact::from_bytes(b"hello world".to_vec());
        s.put_object(&a).unwrap();
        let key = Hash::of(b"key");
        let rec = ActionRecord::of(&a, BTreeMap::new(), vec![]);
        s.put_action(key, &rec).unwrap();
        assert!(matches!(
            s.load_object(a.hash(), rec.output_len),
            Load::Hit(_)
        ));
        assert!(matches!(s.load_action(key), Load::Hit(r) if r == rec));
        std::fs::write(s.object_path(a.hash()), b"hello").unwrap();
        std::fs::write(s.action_path(key), b"short").unwrap();
        assert!(matches!(
            s.load_object(a.hash(), rec.output_len),
            Load::Corrupt(_)
        ));
        assert!(matches!(s.load_action(key), Load::Corrupt(_)));
        assert!(matches!(
            s.load_object(Hash::of(b"nothing"), None),
            Load::Missing
        ));
    }

    #[test]
    fn an_action_copied_under_another_key_is_corrupt() {
        let dir = tempfile::tempdir().unwrap();
        let s = Store::open(dir.path()).unwrap();
        let rec = ActionRecord::of(
            &Artifact::from_bytes(b"o".to_vec()),
            BTreeMap::new(),
            vec![],
        );
        s.put_action(Hash::of(b"k1"), &rec).unwrap();
        std::fs::copy(
            s.action_path(Hash::of(b"k1")),
            s.action_path(Hash::of(b"k2")),
        )
        .unwrap();
        assert!(matches!(s.load_action(Hash::of(b"k2")), Load::Corrupt(_)));
    }

    #[test]
    fn an_object_of_another_size_than_its_record_is_corrupt_and_not_read() {
        let dir = tempfile::tempdir().unwrap();
        let s = Store::open(dir.path()).unwrap();
        let a = Artifact::from_bytes(b"hello world".to_vec());
        s.put_object(&a).unwrap();
        // A sparse file of 64 GiB in its place: reading it would take minutes and all memory.
        // The size is told before any read (a read would end in a hash mismatch, or not at all).
        sparse(&s.object_path(a.hash()), 64 << 30);
        match s.load_object(a.hash(), Some(11)) {
            Load::Corrupt(d) => assert!(d.contains("its record says 11"), "{d}"),
            other => panic!("{other:?}"),
        }
    }

    /// A sparse file of `len` bytes at `path`.
    fn sparse(path: &Path, len: u64) {
        std::fs::File::create(path).unwrap().set_len(len).unwrap();
    }

    #[test]
    fn an_action_file_larger_than_any_record_is_corrupt_and_not_read() {
        let dir = tempfile::tempdir().unwrap();
        let s = Store::open(dir.path()).unwrap();
        let key = Hash::of(b"k");
        sparse(&s.action_path(key), 64 << 30);
        match s.load_action(key) {
            Load::Corrupt(d) => assert!(d.contains("more than"), "{d}"),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn an_action_written_before_sizes_were_recorded_is_still_a_hit() {
        #[derive(Serialize)]
        struct Before {
            key: Hash,
            output: Hash,
            counts: BTreeMap<String, u64>,
            notes: Vec<String>,
        }
        let dir = tempfile::tempdir().unwrap();
        let s = Store::open(dir.path()).unwrap();
        let (key, output) = (Hash::of(b"k"), Hash::of(b"o"));
        let counts = BTreeMap::from([("nodes".to_string(), 7)]);
        let before = Before {
            key,
            output,
            counts: counts.clone(),
            notes: vec!["a note".into()],
        };
        let payload = postcard::to_stdvec(&before).unwrap();
        let mut bytes = Hash::of(&payload).0.to_vec();
        bytes.extend_from_slice(&payload);
        std::fs::write(s.action_path(key), bytes).unwrap();
        let expected = ActionRecord {
            output,
            counts,
            notes: vec!["a note".into()],
            output_len: None,
        };
        assert!(matches!(s.load_action(key), Load::Hit(r) if r == expected));
    }
}
