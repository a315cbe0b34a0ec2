//! What makes a directory a cache: the marker file `CACHEDIR.TAG` (the Cache Directory Tagging
//! convention, which backup tools honour), written when a build first uses the directory. `clean`
//! and `gc` touch only a marked directory, and a build claims only a new or empty directory, or
//! one that holds nothing but cache entries (a cache made before the marker existed), so a
//! mistyped `--cache-dir` can never make the engine delete a user's files.

use crate::error::EngineError;
use std::path::Path;

/// The marker's file name.
pub const MARKER: &str = "CACHEDIR.TAG";

const SIGNATURE: &str = "Signature: 8a477f597d28d172789f06886806bc55";

/// What the marker says, beyond the signature the convention requires.
const TEXT: &str = "Signature: 8a477f597d28d172789f06886806bc55\n\
    # This directory is a georecipe build cache; `recipe clean` may delete it whole.\n\
    # For information about cache directory tags see https://bford.info/cachedir/\n";

/// Entries a cache holds: the engine's (`records` holds each graph's last build, and whatever
/// the command line keeps beside it), those that builds kept at the root before records
/// (`manifest.bin`, the command line's `last-report.json` and `last-graph.dot`), and
/// temporaries of atomic writes.
fn is_cache_entry(name: &str) -> bool {
    matches!(
        name,
        MARKER
            | "objects"
            | "actions"
            | "records"
            | "lock"
            | "manifest.bin"
            | "last-report.json"
            | "last-graph.dot"
    ) || name.starts_with(".tmp")
}

/// Whether `dir` carries the marker.
pub fn is_cache(dir: &Path) -> bool {
    std::fs::read(dir.join(MARKER)).is_ok_and(|b| b.starts_with(SIGNATURE.as_bytes()))
}

/// Makes `dir` a cache for a build: creates it if needed and marks it, unless it is an unmarked
/// directory holding anything a cache does not hold, which is refused with the entries found.
pub fn claim(dir: &Path) -> Result<(), EngineError> {
    if is_cache(dir) {
        return Ok(());
    }
    std::fs::create_dir_all(dir).map_err(|e| EngineError::io(dir, e))?;
    refuse_foreign(dir)?;
    match crate::store::write_atomic(&dir.join(MARKER), TEXT.as_bytes(), true) {
        // A build that claimed it at the same moment, and swept this write's temporary as a
        // killed write's under its lock, marked it.
        Err(_) if is_cache(dir) => Ok(()),
        done => done.map_err(|e| EngineError::io(dir.join(MARKER), e)),
    }
}

/// An error naming the first entries of `dir` that are not cache entries, if there are any.
fn refuse_foreign(dir: &Path) -> Result<(), EngineError> {
    let mut foreign: Vec<String> = std::fs::read_dir(dir)
        .map_err(|e| EngineError::io(dir, e))?
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| !is_cache_entry(n))
        .collect();
    if foreign.is_empty() {
        return Ok(());
    }
    foreign.sort();
    let more = foreign.len().saturating_sub(3);
    foreign.truncate(3);
    let mut found = foreign
        .iter()
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>()
        .join(", ");
    if more > 0 {
        found.push_str(&format!(" and {more} more"));
    }
    Err(EngineError::NotACache {
        path: dir.to_path_buf(),
        found,
    })
}

/// For `clean` and `gc`: an error unless `dir` is marked as a cache (the entries it holds say
/// what it is instead).
pub fn require(dir: &Path) -> Result<(), EngineError> {
    if is_cache(dir) {
        return Ok(());
    }
    refuse_foreign(dir)?;
    Err(EngineError::NotACache {
        path: dir.to_path_buf(),
        found: format!("no `{MARKER}`; a cache an older version made is marked by its next build"),
    })
}
