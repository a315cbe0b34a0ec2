//! Small files that say when they are damaged: the records of a build (its manifest, emitted
//! files and derivations, and the command line's last report, graph and report state).
//!
//! Each is written atomically as the blake3 of its payload (32 bytes) followed by the payload,
//! and read back only when the two agree. These files are not synced to disk and are not the
//! results: a damaged one costs the next build some work or an explanation, but is never taken
//! for true (a flipped byte in the last report is not printed by `explain` as if it were).
//! They are read as cache entries are (`entry`): a FIFO, a device or a link in place of one is
//! damage, left in place (a cache may be only read) for the next write to replace, never
//! followed, blocked on or read without end.

use crate::artifact::Hash;
use crate::entry::{self, Wrong};
use crate::store::write_atomic;
use serde::Serialize;
use serde::de::DeserializeOwned;
use std::path::Path;

/// Why a checked file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum CheckedError {
    #[error("it does not exist")]
    Missing,
    #[error("it is damaged: {0}")]
    Damaged(String),
    #[error("{0}")]
    Io(#[from] std::io::Error),
}

/// Writes `payload` to `path` with its checksum in front, atomically, unless the file holds it
/// already (a record that did not change is not rewritten).
pub fn write(path: &Path, payload: &[u8]) -> std::io::Result<()> {
    if read(path).is_ok_and(|old| old == payload) {
        return Ok(());
    }
    // The rename replaces a FIFO, a device or a link in its place, but not a directory.
    if std::fs::symlink_metadata(path).is_ok_and(|m| m.is_dir()) {
        std::fs::remove_dir_all(path)?;
    }
    let mut bytes = Hash::of(payload).0.to_vec();
    bytes.extend_from_slice(payload);
    write_atomic(path, &bytes, false)
}

/// The payload [`write()`] wrote to `path`, verified.
pub fn read(path: &Path) -> Result<Vec<u8>, CheckedError> {
    let mut bytes = match entry::read_as(path, Wrong::Leave, entry::Size::Any) {
        entry::Read::Bytes(b) => b,
        entry::Read::Missing => return Err(CheckedError::Missing),
        entry::Read::Damaged(what) => return Err(CheckedError::Damaged(what)),
        entry::Read::Failed(e) => return Err(CheckedError::Io(std::io::Error::other(e))),
    };
    let Some((sum, payload)) = bytes.split_first_chunk::<32>() else {
        return Err(CheckedError::Damaged("shorter than its checksum".into()));
    };
    if Hash::of(payload).0 != *sum {
        return Err(CheckedError::Damaged("its checksum does not match".into()));
    }
    Ok(bytes.split_off(32))
}

/// Writes `value` (postcard) as a checked file.
pub(crate) fn save<T: Serialize>(path: &Path, value: &T) -> std::io::Result<()> {
    let payload = postcard::to_stdvec(value).map_err(|e| std::io::Error::other(e.to_string()))?;
    write(path, &payload)
}

/// What [`save`] wrote to `path`, or `None` when it is absent, damaged or of another type.
pub(crate) fn load<T: DeserializeOwned>(path: &Path) -> Option<T> {
    postcard::from_bytes(&read(path).ok()?).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_checked_file_reads_back_and_any_flipped_or_cut_byte_is_damage() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("r");
        assert!(matches!(read(&p), Err(CheckedError::Missing)));
        write(&p, b"{\"nodes\": []}").unwrap();
        assert_eq!(read(&p).unwrap(), b"{\"nodes\": []}");
        let good = std::fs::read(&p).unwrap();
        for i in 0..good.len() {
            let mut bad = good.clone();
            bad[i] ^= 0x01;
            std::fs::write(&p, &bad).unwrap();
            assert!(
                matches!(read(&p), Err(CheckedError::Damaged(_))),
                "byte {i}"
            );
        }
        std::fs::write(&p, &good[..20]).unwrap();
        assert!(matches!(read(&p), Err(CheckedError::Damaged(_))));
    }

    #[test]
    fn a_fifo_a_device_link_or_a_directory_in_place_of_a_checked_file_is_damage_then_replaced() {
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("fifo");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        let mut wrong = vec![dir.path().join("dir")];
        std::fs::create_dir(&wrong[0]).unwrap();
        std::fs::write(wrong[0].join("x"), b"x").unwrap();
        if made.is_ok_and(|s| s.success()) {
            wrong.push(fifo);
        } else {
            eprintln!("note: mkfifo is not available; no FIFO tried");
        }
        #[cfg(unix)]
        if std::path::Path::new("/dev/zero").exists() {
            let link = dir.path().join("zero");
            std::os::unix::fs::symlink("/dev/zero", &link).unwrap();
            wrong.push(link);
        }
        for p in &wrong {
            // Neither followed, blocked on nor read without end: damage, at once.
            assert!(
                matches!(read(p), Err(CheckedError::Damaged(_))),
                "{}",
                p.display()
            );
            write(p, b"payload").unwrap();
            assert_eq!(read(p).unwrap(), b"payload", "{}", p.display());
        }
    }
}
