//! The cache directory lock: one build (or gc / clean) at a time per cache directory.
//!
//! An exclusive OS file lock on `<cache>/lock`; it is released when the guard is dropped or the
//! process dies, so a crashed build never leaves a stale lock. A second build first tries the
//! lock, tells the caller it is waiting (so the CLI can print a clear message), then blocks.
//!
//! A cache that cannot be written (a read-only disk, a shared cache the user may only read, or
//! one the caller asks to use read-only) is still usable for reading: its lock is then a shared
//! lock on the lock file opened for reading, which waits for a writing build to finish, and no
//! lock at all when the file is missing (nothing can write such a cache). The guard says which
//! ([`DirLock::read_only`]); the holder then writes nothing into the cache.

use crate::error::EngineError;
use std::fs::{File, OpenOptions, TryLockError};
use std::io::ErrorKind;
use std::path::{Path, PathBuf};

/// Holds the lock until dropped.
#[derive(Debug)]
pub struct DirLock {
    file: Option<File>,
    path: PathBuf,
    read_only: bool,
}

/// How a cache is to be locked.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Access {
    /// Exclusively, for writing; read-only when the directory is a cache that cannot be
    /// written.
    Write,
    /// Shared, for reading only.
    Read,
}

/// Errors that say the cache cannot be written, rather than that something is wrong with it.
pub fn is_read_only_error(e: &std::io::Error) -> bool {
    matches!(
        e.kind(),
        ErrorKind::ReadOnlyFilesystem | ErrorKind::PermissionDenied
    )
}

/// The lock file, opened for the access asked (or for reading, when a marked cache cannot be
/// written), and whether it was opened read-only.
fn open(dir: &Path, access: Access) -> Result<(Option<File>, PathBuf, bool), EngineError> {
    let path = dir.join("lock");
    if access == Access::Write {
        std::fs::create_dir_all(dir).map_err(|e| EngineError::io(dir, e))?;
        let opened = OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&path);
        match opened {
            Ok(file) => return Ok((Some(file), path, false)),
            Err(e) if !(is_read_only_error(&e) && crate::marker::is_cache(dir)) => {
                return Err(EngineError::io(&path, e));
            }
            Err(_) => {}
        }
    }
    match File::open(&path) {
        Ok(file) => Ok((Some(file), path, true)),
        Err(e) if e.kind() == ErrorKind::NotFound => Ok((None, path, true)),
        Err(e) => Err(EngineError::io(&path, e)),
    }
}

/// Tries the lock the access calls for (exclusive to write, shared to read).
fn try_lock(file: &File, read_only: bool) -> Result<(), TryLockError> {
    if read_only {
        file.try_lock_shared()
    } else {
        file.try_lock()
    }
}

impl DirLock {
    /// Take the lock without waiting; `Ok(None)` when another holder has it.
    pub fn try_acquire(dir: &Path) -> Result<Option<DirLock>, EngineError> {
        let (file, path, read_only) = open(dir, Access::Write)?;
        if let Some(f) = &file {
            match try_lock(f, read_only) {
                Ok(()) => {}
                Err(TryLockError::WouldBlock) => return Ok(None),
                Err(TryLockError::Error(e)) => return Err(EngineError::io(&path, e)),
            }
        }
        Ok(Some(DirLock {
            file,
            path,
            read_only,
        }))
    }

    /// Take the lock, calling `on_wait` once with the lock path if another holder has it first.
    pub fn acquire(dir: &Path, on_wait: impl FnOnce(&Path)) -> Result<DirLock, EngineError> {
        Self::acquire_for(dir, Access::Write, on_wait)
    }

    /// [`DirLock::acquire`] for the access asked.
    pub fn acquire_for(
        dir: &Path,
        access: Access,
        on_wait: impl FnOnce(&Path),
    ) -> Result<DirLock, EngineError> {
        let (file, path, read_only) = open(dir, access)?;
        if let Some(f) = &file {
            match try_lock(f, read_only) {
                Ok(()) => {}
                Err(TryLockError::WouldBlock) => {
                    on_wait(&path);
                    let waited = if read_only { f.lock_shared() } else { f.lock() };
                    waited.map_err(|e| EngineError::io(&path, e))?;
                }
                Err(TryLockError::Error(e)) => return Err(EngineError::io(&path, e)),
            }
        }
        Ok(DirLock {
            file,
            path,
            read_only,
        })
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Whether the cache is held for reading only: its holder writes nothing into it.
    pub fn read_only(&self) -> bool {
        self.read_only
    }
}

impl Drop for DirLock {
    fn drop(&mut self) {
        if let Some(f) = &self.file {
            let _ = f.unlock();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_held_lock_refuses_a_second_holder_until_dropped() {
        let dir = tempfile::tempdir().unwrap();
        let first = DirLock::try_acquire(dir.path()).unwrap().expect("free");
        assert!(!first.read_only());
        assert!(DirLock::try_acquire(dir.path()).unwrap().is_none());
        drop(first);
        assert!(DirLock::try_acquire(dir.path()).unwrap().is_some());
    }

    #[test]
    fn readers_share_the_lock_and_a_writer_waits_for_them() {
        let dir = tempfile::tempdir().unwrap();
        drop(DirLock::try_acquire(dir.path()).unwrap());
        let a = DirLock::acquire_for(dir.path(), Access::Read, |_| panic!("free")).unwrap();
        let b = DirLock::acquire_for(dir.path(), Access::Read, |_| panic!("shared")).unwrap();
        assert!(a.read_only() && b.read_only());
        assert!(DirLock::try_acquire(dir.path()).unwrap().is_none());
        drop((a, b));
        assert!(DirLock::try_acquire(dir.path()).unwrap().is_some());
    }

    #[test]
    fn a_cache_without_a_lock_file_is_read_without_a_lock_and_left_as_it_was() {
        let dir = tempfile::tempdir().unwrap();
        let lock = DirLock::acquire_for(dir.path(), Access::Read, |_| panic!("free")).unwrap();
        assert!(lock.read_only());
        assert!(!dir.path().join("lock").exists());
    }

    #[test]
    fn only_errors_that_forbid_writing_make_a_cache_read_only() {
        let e = |k| std::io::Error::from(k);
        assert!(is_read_only_error(&e(ErrorKind::ReadOnlyFilesystem)));
        assert!(is_read_only_error(&e(ErrorKind::PermissionDenied)));
        assert!(!is_read_only_error(&e(ErrorKind::NotFound)));
        assert!(!is_read_only_error(&e(ErrorKind::StorageFull)));
    }
}
