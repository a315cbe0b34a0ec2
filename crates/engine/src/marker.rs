//! What makes a directory a cache: the marker file `CACHEDIR.TAG` (the Cache Directory Tagging
//! convention, which backup tools honour), written when a build first uses the directory. `clean`
//! and `gc` touch only a marked directory, and a build claims only a new or empty directory, or
//! one that holds nothing but cache entries, down to the names of its files (a cache made
//! before the marker existed), so a mistyped `--cache-dir` can never make the engine delete a
//! user's files.

use crate::error::EngineError;
use std::path::Path;

/// The marker's file name.
pub const MARKER: &str = "CACHEDIR.TAG";

const SIGNATURE: &str = "Signature: 8a477f597d28d172789f06886806bc55";

/// What the marker says, beyond the signature the convention requires.
const TEXT: &str = "Signature: 8a477f597d28d172789f06886806bc55\n\
    # This directory is a georecipe build cache; `recipe clean` may delete it whole.\n\
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
/// line's (the last report and graph, the report's state).
const RECORD_FILES: [&str; 6] = [
    "manifest.bin",
    "emitted.bin",
    "derived.bin",
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

/// The paths under `dir` (relative to it) that a cache does not hold: anything but its root
/// files, `objects/` and `actions/` of files named by hashes, and `records/<name>/` of the
/// record files, temporaries anywhere. Looked at whole, so a folder of the user's whose top
/// names happen to be a cache's is never taken for one.
fn foreign_entries(dir: &Path) -> std::io::Result<Vec<String>> {
    let mut foreign = Vec::new();
    for (name, is_dir) in entries(dir)? {
        let within = |rule: &dyn Fn(&str, bool) -> bool| -> std::io::Result<Vec<String>> {
            Ok(entries(&dir.join(&name))?
                .into_iter()
                .filter(|(n, d)| (*d || !is_temporary(n)) && !rule(n, *d))
                .map(|(n, _)| format!("{name}/{n}"))
                .collect())
        };
        match (name.as_str(), is_dir) {
            ("objects" | "actions", true) => foreign.extend(within(&|n, d| !d && is_hash_name(n))?),
            ("records", true) => {
                for (record, d) in entries(&dir.join(&name))? {
                    if !d {
                        foreign.push(format!("records/{record}"));
                        continue;
                    }
                    let files = entries(&dir.join("records").join(&record))?;
                    foreign.extend(
                        (files.into_iter())
                            .filter(|(n, d)| {
                                *d || !(is_temporary(n) || RECORD_FILES.contains(&n.as_str()))
                            })
                            .map(|(n, _)| format!("records/{record}/{n}")),
                    );
                }
            }
            (n, false) if ROOT_FILES.contains(&n) || is_temporary(n) => {}
            _ => foreign.push(name),
        }
    }
    Ok(foreign)
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
    let mut foreign = foreign_entries(dir).map_err(|e| EngineError::io(dir, e))?;
    if foreign.is_empty() {
        return Ok(());
    }
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
