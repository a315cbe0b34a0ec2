//! What makes a directory a cache: the marker file `CACHEDIR.TAG` (the Cache Directory Tagging
//! convention, which backup tools honour) with this program's line in it, written when a build
//! first uses the directory. `clean` and `gc` touch only a marked directory, and in it only the
//! cache's own entries, by their names and kinds; a build claims only a new or empty directory,
//! or one that holds nothing but cache entries, down to the names of its files (a cache made
//! before the marker existed). So a mistyped `--cache-dir`, another program's tagged cache, or
//! a file a user left inside a cache never makes the engine delete a user's files.

use crate::error::EngineError;
use std::path::{Path, PathBuf};

/// The marker's file name.
pub const MARKER: &str = "CACHEDIR.TAG";

const SIGNATURE: &str = "Signature: 8a477f597d28d172789f06886806bc55";

/// The marker's line that makes a tagged directory this program's cache.
const OWNER: &str = "# This directory is a georecipe build cache;";

/// How much of a marker is read: a little more than [`TEXT`].
const MARKER_READ: u64 = 1024;

/// What the marker says, beyond the signature the convention requires.
const TEXT: &str = "Signature: 8a477f597d28d172789f06886806bc55\n\
    # This directory is a georecipe build cache; `recipe clean` may delete its entries.\n\
    # For information about cache directory tags see https://bford.info/cachedir/\n";

/// Files a cache holds at its root: its lock, and those that builds kept there before records
/// (`manifest.bin`, the command line's `last-report.json` and `last-graph.dot`).
const ROOT_FILES: [&str; 5] = [
    MARKER,
    "lock",
    "manifest.bin",
    "last-report.json",
    "last-graph.dot",
];

/// Files a record holds: the engine's (manifest, emitted files, derivations) and the command
/// line's (the recipe's path, the last report and graph, the report's state).
const RECORD_FILES: [&str; 7] = [
    "manifest.bin",
    "emitted.bin",
    "derived.bin",
    "recipe",
    "report-state.json",
    "last-report.json",
    "last-graph.dot",
];

/// A temporary of an atomic write.
fn is_temporary(name: &str) -> bool {
    name.starts_with(".tmp")
}

/// A store entry's name: a hash in hexadecimal.
fn is_hash_name(name: &str) -> bool {
    name.len() == 64
        && name
            .bytes()
            .all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(&b))
}

/// The entries of `dir`, as (name, is a directory), without following links; a link is neither
/// a file nor a directory of a cache, so it is given as a file whose name no rule accepts.
fn entries(dir: &Path) -> std::io::Result<Vec<(String, bool)>> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir)? {
        let e = e?;
        let kind = e.file_type()?;
        let name = e.file_name().to_string_lossy().into_owned();
        if kind.is_symlink() {
            out.push((format!("{name} (a link)"), false));
        } else {
            out.push((name, kind.is_dir()));
        }
    }
    out.sort();
    Ok(out)
}

/// What a directory holds, sorted into a cache's own entries and the rest.
#[derive(Default)]
struct Survey {
    /// The cache's own files: its root files, store entries, record files and temporaries.
    files: Vec<PathBuf>,
    /// The cache's own folders (`objects`, `actions`, `records` and each record), deepest first.
    folders: Vec<PathBuf>,
    /// The paths (relative to the directory) of anything else: never the cache's to delete.
    foreign: Vec<String>,
}

/// Sorts `dir`'s entries: a cache holds its root files, `objects/` and `actions/` of files named
/// by hashes, and `records/<name>/` of the record files, temporaries anywhere. Looked at whole,
/// so a folder of the user's whose top names happen to be a cache's is never taken for one.
fn survey(dir: &Path) -> std::io::Result<Survey> {
    let mut s = Survey::default();
    for (name, is_dir) in entries(dir)? {
        let path = dir.join(&name);
        match (name.as_str(), is_dir) {
            ("objects" | "actions", true) => s.take(&path, &name, &|n, d| {
                !d && (is_hash_name(n) || is_temporary(n))
            })?,
            ("records", true) => {
                for (record, d) in entries(&path)? {
                    if !d {
                        s.foreign.push(format!("records/{record}"));
                        continue;
                    }
                    s.take(
                        &path.join(&record),
                        &format!("records/{record}"),
                        &|n, d| !d && (is_temporary(n) || RECORD_FILES.contains(&n)),
                    )?;
                }
                s.folders.push(path);
            }
            // Another program's tag: that program's directory, whatever else it holds.
            (MARKER, false) if !is_cache(dir) => s.foreign.push(format!("{MARKER} (not ours)")),
            (n, false) if ROOT_FILES.contains(&n) || is_temporary(n) => s.files.push(path),
            _ => s.foreign.push(name),
        }
    }
    Ok(s)
}

impl Survey {
    /// Sorts the entries of the cache's folder `path` (`shown` relative to the cache) by `own`.
    fn take(
        &mut self,
        path: &Path,
        shown: &str,
        own: &dyn Fn(&str, bool) -> bool,
    ) -> std::io::Result<()> {
        for (n, d) in entries(path)? {
            if own(&n, d) {
                self.files.push(path.join(&n));
            } else {
                self.foreign.push(format!("{shown}/{n}"));
            }
        }
        self.folders.push(path.to_path_buf());
        Ok(())
    }
}

/// The paths under `dir` (relative to it) that a cache does not hold.
fn foreign_entries(dir: &Path) -> std::io::Result<Vec<String>> {
    survey(dir).map(|s| s.foreign)
}

/// Removes the record folder `dir`'s own files (the record files and temporaries), and the
/// folder when nothing else is left in it. The caller holds the cache lock.
pub(crate) fn remove_record(dir: &Path) -> Result<(), EngineError> {
    let mut s = Survey::default();
    s.take(dir, "", &|n, d| {
        !d && (is_temporary(n) || RECORD_FILES.contains(&n))
    })
    .map_err(|e| EngineError::io(dir, e))?;
    for f in &s.files {
        remove(f, std::fs::remove_file(f))?;
    }
    let _ = std::fs::remove_dir(dir);
    Ok(())
}

/// Removes the cache's own entries from the marked cache `dir`, its marker last, and `dir`
/// itself when nothing else is left in it; returns the paths (relative to `dir`) of what was not
/// the cache's and was left as it was. The caller holds the cache lock.
pub(crate) fn remove_own(dir: &Path) -> Result<Vec<String>, EngineError> {
    let s = survey(dir).map_err(|e| EngineError::io(dir, e))?;
    let marker = dir.join(MARKER);
    for f in s.files.iter().filter(|f| **f != marker) {
        remove(f, std::fs::remove_file(f))?;
    }
    // A folder still holding something of the user's stays; `foreign` names what.
    for f in &s.folders {
        let _ = std::fs::remove_dir(f);
    }
    remove(&marker, std::fs::remove_file(&marker))?;
    if s.foreign.is_empty() {
        remove(dir, std::fs::remove_dir(dir))?;
    }
    Ok(s.foreign)
}

/// The outcome of removing `path`: done, or already gone.
fn remove(path: &Path, r: std::io::Result<()>) -> Result<(), EngineError> {
    match r {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(EngineError::io(path, e)),
        _ => Ok(()),
    }
}

/// Whether `dir` carries this program's marker: a plain file (never a link, a FIFO or a device,
/// read no further than the marker's own length) with the convention's signature and the line
/// that says whose cache it is. Other tools tag their caches with the same signature (cargo's
/// `target/`, folders a user keeps out of backups): those are not ours to clean.
pub fn is_cache(dir: &Path) -> bool {
    use std::io::Read;
    let path = dir.join(MARKER);
    let plain = std::fs::symlink_metadata(&path).is_ok_and(|m| m.file_type().is_file());
    let mut text = Vec::new();
    plain
        && std::fs::File::open(&path)
            .and_then(|f| f.take(MARKER_READ).read_to_end(&mut text))
            .is_ok()
        && text.starts_with(SIGNATURE.as_bytes())
        && text.windows(OWNER.len()).any(|w| w == OWNER.as_bytes())
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
    let foreign = foreign_entries(dir).map_err(|e| EngineError::io(dir, e))?;
    if foreign.is_empty() {
        return Ok(());
    }
    Err(EngineError::NotACache {
        path: dir.to_path_buf(),
        found: listed(&foreign),
    })
}

/// The first three of `paths` in backquotes, and how many more there are.
pub fn listed(paths: &[String]) -> String {
    let mut found = (paths.iter().take(3))
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>()
        .join(", ");
    if paths.len() > 3 {
        found.push_str(&format!(" and {} more", paths.len() - 3));
    }
    found
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
