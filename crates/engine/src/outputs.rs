//! Writing the files an exporting node emits under the build's output directory.
//!
//! Paths come from operation output, so they are validated (relative, `/`-separated, no `..`,
//! no empty or `.` components) before anything is written. A file whose bytes on disk already
//! equal the emitted bytes is left alone; any other is replaced atomically (temp + rename), so
//! no reader ever sees a partial output file. "Already equal" is decided from the file's length
//! and then chunk by chunk, so a big output is never read whole into memory. A build with a
//! staging directory writes every file that differs there instead, under the same relative path,
//! and leaves the output directory as it was: the caller publishes or discards the staged files.
//! A cached node whose files a previous build recorded (`emitted`) is first checked by hashing
//! the files on disk against that record, so its output is read only when one differs.

use crate::artifact::Hash;
use crate::store::write_atomic;
use std::collections::BTreeMap;
use std::io::Read;
use std::path::{Path, PathBuf};

/// How much of an existing output file is read at a time to compare it.
const COMPARE_CHUNK: usize = 1 << 20;

/// Check an emitted relative path and turn it into a path under `root`.
pub(crate) fn resolve(root: &Path, rel: &str) -> Result<PathBuf, String> {
    if rel.is_empty() || rel.starts_with('/') || rel.contains('\\') || rel.contains(':') {
        return Err(format!(
            "emitted file path `{rel}` must be relative and use `/`"
        ));
    }
    let mut out = root.to_path_buf();
    for part in rel.split('/') {
        if part.is_empty() || part == "." || part == ".." {
            return Err(format!(
                "emitted file path `{rel}` has an empty, `.` or `..` component"
            ));
        }
        out.push(part);
    }
    Ok(out)
}

/// Write (or leave in place when identical) every file of `files` (as read in place from a
/// `FileSet` artifact) under `root`, or, with `staging`, write the files that differ from their
/// copy under `root` under `staging` instead; returns path -> content hash and the paths that
/// had to be (re)written.
pub(crate) fn write_fileset(
    root: &Path,
    staging: Option<&Path>,
    files: &[(&str, &[u8])],
) -> Result<(BTreeMap<String, Hash>, Vec<String>), String> {
    let mut hashes = BTreeMap::new();
    let mut written = Vec::new();
    for &(rel, bytes) in files {
        let path = resolve(root, rel)?;
        if !same_on_disk(&path, bytes) {
            let path = match staging {
                Some(dir) => resolve(dir, rel)?,
                None => path,
            };
            write_atomic(&path, bytes, true)
                .map_err(|e| format!("cannot write output file {}: {e}", path.display()))?;
            written.push(rel.to_string());
        }
        hashes.insert(rel.to_string(), Hash::of(bytes));
    }
    Ok((hashes, written))
}

/// Whether every file of `files` (relative path → content hash, as a previous build emitted
/// them) is under `root` with that content: read and hashed, the files in parallel, without the
/// node's output. Anything missing, unreadable or different is `false`.
pub(crate) fn unchanged_on_disk(root: &Path, files: &BTreeMap<String, Hash>) -> bool {
    use rayon::prelude::*;
    files.par_iter().all(|(rel, want)| {
        resolve(root, rel)
            .ok()
            .and_then(|p| hash_file(&p).ok())
            .is_some_and(|h| h == *want)
    })
}

/// The content hash of the regular file at `path`, read one chunk at a time.
fn hash_file(path: &Path) -> std::io::Result<Hash> {
    let mut file = std::fs::File::open(path)?;
    if !file.metadata()?.is_file() {
        return Err(std::io::Error::other("not a regular file"));
    }
    let mut h = blake3::Hasher::new();
    let mut buf = vec![0u8; COMPARE_CHUNK];
    loop {
        match file.read(&mut buf) {
            Ok(0) => return Ok(Hash(*h.finalize().as_bytes())),
            Ok(n) => {
                h.update(&buf[..n]);
            }
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
}

/// Whether `path` is a regular file holding exactly `bytes`: its length first, then its
/// contents one chunk at a time. Anything unreadable counts as different (it gets rewritten).
fn same_on_disk(path: &Path, bytes: &[u8]) -> bool {
    let Ok(mut file) = std::fs::File::open(path) else {
        return false;
    };
    match file.metadata() {
        Ok(m) if m.is_file() && m.len() == bytes.len() as u64 => {}
        _ => return false,
    }
    let mut buf = vec![0u8; COMPARE_CHUNK.min(bytes.len())];
    for want in bytes.chunks(COMPARE_CHUNK) {
        let got = &mut buf[..want.len()];
        if file.read_exact(got).is_err() || got != want {
            return false;
        }
    }
    // The file may have grown since its metadata was read.
    matches!(file.read(&mut [0u8; 1]), Ok(0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_escaping_the_output_directory_are_refused() {
        let root = Path::new("/tmp/out");
        for bad in ["", "/etc/passwd", "../x", "a/../b", "a//b", "./a", "c:\\x"] {
            assert!(resolve(root, bad).is_err(), "{bad} accepted");
        }
        assert_eq!(
            resolve(root, "mesh/m.msh").unwrap(),
            Path::new("/tmp/out/mesh/m.msh")
        );
    }

    #[test]
    fn an_output_equal_on_disk_is_left_alone_and_any_difference_is_rewritten() {
        let dir = tempfile::tempdir().unwrap();
        let big: Vec<u8> = (0..3 * COMPARE_CHUNK + 17)
            .map(|i| (i % 251) as u8)
            .collect();
        let files: Vec<(&str, &[u8])> = vec![("a/big.bin", &big), ("empty", b"")];
        let (hashes, written) = write_fileset(dir.path(), None, &files).unwrap();
        assert_eq!(written, ["a/big.bin", "empty"]);
        assert_eq!(hashes["a/big.bin"], Hash::of(&big));
        assert_eq!(std::fs::read(dir.path().join("a/big.bin")).unwrap(), big);
        let (_, written) = write_fileset(dir.path(), None, &files).unwrap();
        assert!(written.is_empty(), "{written:?}");
        // One byte changed in the last chunk, then the same length plus one byte.
        let path = dir.path().join("a/big.bin");
        let mut other = big.clone();
        *other.last_mut().unwrap() ^= 1;
        std::fs::write(&path, &other).unwrap();
        assert!(!same_on_disk(&path, &big));
        let (_, written) = write_fileset(dir.path(), None, &files).unwrap();
        assert_eq!(written, ["a/big.bin"]);
        assert_eq!(std::fs::read(&path).unwrap(), big);
        other = big.clone();
        other.push(0);
        std::fs::write(&path, &other).unwrap();
        assert!(!same_on_disk(&path, &big));
        assert!(same_on_disk(&dir.path().join("empty"), b""));
        assert!(!same_on_disk(dir.path(), b""));
        assert!(!same_on_disk(&dir.path().join("missing"), b""));
    }

    #[test]
    fn a_staged_write_leaves_the_output_directory_alone_and_stages_only_what_differs() {
        let out = tempfile::tempdir().unwrap();
        let stage = tempfile::tempdir().unwrap();
        std::fs::write(out.path().join("same"), b"kept").unwrap();
        std::fs::write(out.path().join("old"), b"before").unwrap();
        let files: Vec<(&str, &[u8])> =
            vec![("same", b"kept"), ("old", b"after"), ("sub/new", b"new")];
        let (hashes, written) = write_fileset(out.path(), Some(stage.path()), &files).unwrap();
        assert_eq!(written, ["old", "sub/new"]);
        assert_eq!(hashes.len(), 3);
        assert_eq!(std::fs::read(out.path().join("old")).unwrap(), b"before");
        assert!(!out.path().join("sub").exists());
        let mut staged: Vec<String> = Vec::new();
        for rel in ["same", "old", "sub/new"] {
            if stage.path().join(rel).is_file() {
                staged.push(rel.to_string());
            }
        }
        assert_eq!(staged, ["old", "sub/new"]);
        assert_eq!(std::fs::read(stage.path().join("old")).unwrap(), b"after");
    }
}
