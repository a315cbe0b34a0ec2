//! Reading one file of the cache without trusting what is at its path.
//!
//! A cache entry is only ever a regular file that the engine wrote. Anything else at its path (a
//! directory, a FIFO, a device, a symlink to `/dev/zero`) is damage: reading it could fail on
//! every build, block forever while the cache lock is held, or never end. So the path is looked
//! at without following links, only a regular file is opened, and the read is bounded by the
//! size the open file has, and by the size its record gives ([`Size`]): a file of another size
//! is damage found without reading it, however large it is. A wrong kind of file is removed,
//! so that the entry can be written again (left in place when the cache is only read). An I/O
//! error (too many open files, a failing disk) says nothing about the entry: it is told as such,
//! never as damage, and the entry is left alone.
//!
//! Between the look and the open nobody else writes: only builds holding the cache's lock write
//! entries.

use std::io::{ErrorKind, Read as _};
use std::path::Path;

/// What reading an entry found.
#[derive(Debug)]
pub(crate) enum Read {
    Bytes(Vec<u8>),
    Missing,
    /// Not a regular file, or it changed while read; the text says what it was. A wrong kind of
    /// file has been removed, unless it was to be kept.
    Damaged(String),
    /// The entry could not be read; the text is the I/O error.
    Failed(String),
}

/// What to do with a wrong kind of file in place of an entry.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Wrong {
    /// Remove it, so that the entry can be written again.
    Remove,
    /// Leave it (a cache only read): it is still damage.
    Keep,
    /// Leave it for the next write to replace, and say only what it is (a build's record).
    Leave,
}

/// How large an entry may be.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Size {
    /// Exactly this many bytes, as its record says.
    Recorded(u64),
    /// At most this many bytes (a record whose size nothing records).
    AtMost(u64),
    /// Whatever size the file has.
    Any,
}

/// Reads the entry at `path` (see the module docs), removing a wrong kind of file.
#[cfg(test)]
pub(crate) fn read(path: &Path) -> Read {
    read_as(path, Wrong::Remove, Size::Any)
}

/// Reads the entry at `path` (see the module docs); `wrong` says what becomes of a wrong kind
/// of file, `size` how large it may be.
pub(crate) fn read_as(path: &Path, wrong: Wrong, size: Size) -> Read {
    let remove_wrong = |path: &Path, kind| handle_wrong(path, kind, wrong);
    let meta = match std::fs::symlink_metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == ErrorKind::NotFound => return Read::Missing,
        Err(e) => return Read::Failed(e.to_string()),
    };
    if !meta.file_type().is_file() {
        return remove_wrong(path, kind_of(&meta.file_type()));
    }
    let file = match std::fs::File::open(path) {
        Ok(f) => f,
        Err(e) if e.kind() == ErrorKind::NotFound => return Read::Missing,
        Err(e) => return Read::Failed(e.to_string()),
    };
    let len = match file.metadata() {
        Ok(m) if m.is_file() => m.len(),
        Ok(m) => return remove_wrong(path, kind_of(&m.file_type())),
        Err(e) => return Read::Failed(e.to_string()),
    };
    match size {
        Size::Recorded(n) if len != n => {
            return Read::Damaged(format!("it is {len} bytes, its record says {n}"));
        }
        Size::AtMost(n) if len > n => {
            return Read::Damaged(format!(
                "it is {len} bytes, more than the {n} an entry can be"
            ));
        }
        _ => {}
    }
    let mut bytes = Vec::with_capacity(usize::try_from(len).unwrap_or(0));
    match file.take(len.saturating_add(1)).read_to_end(&mut bytes) {
        Ok(n) if n as u64 > len => {
            Read::Damaged(format!("it grew past its {len} bytes while read"))
        }
        Ok(_) => Read::Bytes(bytes),
        Err(e) => Read::Failed(e.to_string()),
    }
}

/// Whether a regular file is at `path`, without reading it; `wrong` says what becomes of a
/// wrong kind of file.
pub(crate) fn present(path: &Path, wrong: Wrong) -> bool {
    match std::fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_file() => true,
        Ok(m) => {
            handle_wrong(path, kind_of(&m.file_type()), wrong);
            false
        }
        Err(_) => false,
    }
}

/// Removes what is at `path` in place of an entry (unless told to keep it), and says what it
/// was.
fn handle_wrong(path: &Path, kind: &str, wrong: Wrong) -> Read {
    match wrong {
        Wrong::Keep => {
            return Read::Damaged(format!(
                "{kind}, not a file: left in place (the cache is only read)"
            ));
        }
        Wrong::Leave => return Read::Damaged(format!("{kind}, not a file")),
        Wrong::Remove => {}
    }
    let removed = if kind == "a directory" {
        std::fs::remove_dir_all(path)
    } else {
        std::fs::remove_file(path)
    };
    match removed {
        Ok(()) => Read::Damaged(format!("{kind}, not a file: removed")),
        Err(e) => Read::Damaged(format!(
            "{kind}, not a file, that could not be removed: {e}"
        )),
    }
}

/// A file type in words.
fn kind_of(t: &std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_block_device() || t.is_char_device() {
            return "a device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if t.is_symlink() {
        "a symbolic link"
    } else if t.is_dir() {
        "a directory"
    } else {
        "not a regular file"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_regular_file_reads_whole_and_a_missing_one_is_missing() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("e");
        assert!(matches!(read(&p), Read::Missing));
        std::fs::write(&p, b"bytes").unwrap();
        assert!(matches!(read(&p), Read::Bytes(b) if b == b"bytes"));
    }

    #[test]
    fn a_directory_or_a_link_in_place_of_an_entry_is_damage_and_is_removed() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path().join("d");
        std::fs::create_dir_all(d.join("inner")).unwrap();
        std::fs::write(d.join("inner/f"), b"x").unwrap();
        assert!(matches!(read(&d), Read::Damaged(w) if w.contains("a directory")));
        assert!(!d.exists());
        #[cfg(unix)]
        {
            let target = dir.path().join("target");
            std::fs::write(&target, b"kept").unwrap();
            let l = dir.path().join("l");
            std::os::unix::fs::symlink(&target, &l).unwrap();
            assert!(matches!(read(&l), Read::Damaged(w) if w.contains("symbolic link")));
            assert!(std::fs::symlink_metadata(&l).is_err(), "the link is gone");
            assert_eq!(
                std::fs::read(&target).unwrap(),
                b"kept",
                "not what it pointed at"
            );
        }
    }

    #[test]
    fn an_io_error_is_told_as_a_failure_not_as_damage_and_removes_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("file");
        std::fs::write(&file, b"kept").unwrap();
        // A path through a regular file fails with "not a directory", as EMFILE or EIO would.
        assert!(matches!(read(&file.join("entry")), Read::Failed(_)));
        assert!(!present(&file.join("entry"), Wrong::Remove));
        assert_eq!(std::fs::read(&file).unwrap(), b"kept");
    }

    #[test]
    fn a_cache_only_read_keeps_a_wrong_kind_of_file_and_still_calls_it_damage() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path().join("d");
        std::fs::create_dir_all(&d).unwrap();
        assert!(
            matches!(read_as(&d, Wrong::Keep, Size::Any), Read::Damaged(w) if w.contains("left in place"))
        );
        assert!(!present(&d, Wrong::Keep));
        assert!(d.is_dir());
    }

    #[cfg(unix)]
    #[test]
    fn a_fifo_in_place_of_an_entry_is_damage_without_blocking() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("fifo");
        let made = std::process::Command::new("mkfifo").arg(&p).status();
        if !made.is_ok_and(|s| s.success()) {
            eprintln!("skipped: mkfifo is not available");
            return;
        }
        assert!(matches!(read(&p), Read::Damaged(w) if w.contains("FIFO")));
        assert!(std::fs::symlink_metadata(&p).is_err());
    }
}
