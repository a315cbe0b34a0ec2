//! The cache directory lock: one build (or gc / clean) at a time per cache directory.
//!
//! An exclusive OS file lock on `<cache>/lock`; it is released when the guard is dropped or the
//! process dies, so a crashed build never leaves a stale lock. A second build first tries the
//! lock, tells the caller it is waiting (so the CLI can print a clear message), then blocks.

use crate::error::EngineError;
use std::fs::{File, OpenOptions, TryLockError};
use std::path::{Path, PathBuf};

/// Holds the lock until dropped.
#[derive(Debug)]
pub struct DirLock {
    file: File,
    path: PathBuf,
}

fn open(dir: &Path) -> Result<(File, PathBuf), EngineError> {
    std::fs::create_dir_all(dir).map_err(|e| EngineError::io(dir, e))?;
    let path = dir.join("lock");
    let file = OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&path)
        .map_err(|e| EngineError::io(&path, e))?;
    Ok((file, path))
}

impl DirLock {
    /// Take the lock without waiting; `Ok(None)` when another holder has it.
    pub fn try_acquire(dir: &Path) -> Result<Option<DirLock>, EngineError> {
        let (file, path) = open(dir)?;
        match file.try_lock() {
            Ok(()) => Ok(Some(DirLock { file, path })),
            Err(TryLockError::WouldBlock) => Ok(None),
            Err(TryLockError::Error(e)) => Err(EngineError::io(&path, e)),
        }
    }

    /// Take the lock, calling `on_wait` once with the lock path if another holder has it first.
    pub fn acquire(dir: &Path, on_wait: impl FnOnce(&Path)) -> Result<DirLock, EngineError> {
        let (file, path) = open(dir)?;
        match file.try_lock() {
            Ok(()) => return Ok(DirLock { file, path }),
            Err(TryLockError::WouldBlock) => on_wait(&path),
            Err(TryLockError::Error(e)) => return Err(EngineError::io(&path, e)),
        }
        file.lock().map_err(|e| EngineError::io(&path, e))?;
        Ok(DirLock { file, path })
    }

    pub fn path(&self) -> &Path {
        &self.path
    }
}

impl Drop for DirLock {
    fn drop(&mut self) {
        let _ = self.file.unlock();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_held_lock_refuses_a_second_holder_until_dropped() {
        let dir = tempfile::tempdir().unwrap();
        let first = DirLock::try_acquire(dir.path()).unwrap().expect("free");
        assert!(DirLock::try_acquire(dir.path()).unwrap().is_none());
        drop(first);
        assert!(DirLock::try_acquire(dir.path()).unwrap().is_some());
    }
}
