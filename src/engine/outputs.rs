//! Writing the files an exporting node emits under the build's output directory.
//!
//! Paths come from operation output, so they are validated (relative, `/`-separated, no `..`,
//! no empty or `.` components) before anything is written. A file whose bytes on disk already
//! equal the emitted bytes is left alone; any other is replaced atomically (temp + rename), so
//! no reader ever sees a partial output file.

use crate::engine::artifact::{FileSet, Hash};
use crate::engine::store::write_atomic;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

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

/// Write (or leave in place when identical) every file of `set`; returns path -> content hash
/// and the paths that had to be (re)written.
pub(crate) fn write_fileset(
    root: &Path,
    set: &FileSet,
) -> Result<(BTreeMap<String, Hash>, Vec<String>), String> {
    let mut hashes = BTreeMap::new();
    let mut written = Vec::new();
    for (rel, bytes) in &set.files {
        let path = resolve(root, rel)?;
        let same = std::fs::read(&path).map(|b| b == *bytes).unwrap_or(false);
        if !same {
            write_atomic(&path, bytes, true)
                .map_err(|e| format!("cannot write output file {}: {e}", path.display()))?;
            written.push(rel.clone());
        }
        hashes.insert(rel.clone(), Hash::of(bytes));
    }
    Ok((hashes, written))
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
}
