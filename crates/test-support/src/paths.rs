//! Where the repository's test data and the shared folder beside the repository are.

use std::path::{Path, PathBuf};

/// The repository's root (the workspace), whichever crate's test asks.
pub fn repo() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// A file or folder under the repository's `tests/data`.
pub fn data(rel: &str) -> PathBuf {
    repo().join("tests/data").join(rel)
}

/// A file or folder under `../shared` (beside the repository), or `None` after printing a note
/// naming what is missing, so that the caller skips.
pub fn shared(rel: &str) -> Option<PathBuf> {
    let p = repo().join("../shared").join(rel);
    if p.exists() {
        Some(p)
    } else {
        eprintln!("skipping: ../shared/{rel} is absent");
        None
    }
}
