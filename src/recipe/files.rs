//! Missing import files. The library never touches the filesystem: the caller passes a probe
//! (and optionally a directory listing), and this module decides which imports are missing or
//! are not regular files (a directory, a FIFO that would block the build) and what the user most
//! likely meant: the closest name in the same directory, or the same file name in a directory
//! other imports use, or another letter case or extension.

use std::path::{Path, PathBuf};

use super::Recipe;
use super::diagnostic::{Diagnostic, did_you_mean};

/// What is at an import's path.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileKind {
    /// A regular file (or a link to one).
    File,
    Missing,
    /// Something else, in words: `"a directory"`, `"a FIFO"`...
    Other(&'static str),
}

/// One diagnostic per import whose file does not exist: surfaces, then wells, each in name
/// order.
pub fn check_files(r: &Recipe, exists: &dyn Fn(&Path) -> bool) -> Vec<Diagnostic> {
    let kind = |p: &Path| {
        if exists(p) {
            FileKind::File
        } else {
            FileKind::Missing
        }
    };
    check_files_with_listing(r, &kind, &|_| Vec::new())
}

/// As [`check_files`], with `kind(path)` saying what is at each path (an import that is no
/// regular file is an error saying what it is) and `list_dir(dir)` giving the file names in
/// `dir` (empty if unknown) to suggest the closest existing name.
pub fn check_files_with_listing(
    r: &Recipe,
    kind: &dyn Fn(&Path) -> FileKind,
    list_dir: &dyn Fn(&Path) -> Vec<String>,
) -> Vec<Diagnostic> {
    let exists = &|p: &Path| kind(p) == FileKind::File;
    let surfaces = r
        .surfaces
        .values()
        .map(|s| ("surface", &s.name, &s.file, &s.path, s.file_span));
    let wells = r
        .wells
        .values()
        .map(|w| ("well", &w.name, &w.file, &w.path, w.file_span));
    let mut out = Vec::new();
    for (what, name, file, path, span) in surfaces.chain(wells) {
        let written = file.display().to_string();
        match kind(path) {
            FileKind::File => continue,
            FileKind::Missing => {}
            FileKind::Other(what_it_is) => {
                let message =
                    format!("file `{written}` of {what} `{name}` is {what_it_is}, not a file");
                let help = "point `file` at the gOcad file itself".to_string();
                out.push(r.diagnostic_at(span, message, Some(help)));
                continue;
            }
        }
        let message = if path == file {
            format!("file `{written}` of {what} `{name}` not found")
        } else {
            format!(
                "file `{written}` of {what} `{name}` not found (looked for `{}`)",
                path.display()
            )
        };
        let help = suggestion(r, file, exists, list_dir)
            .map(|p| format!("did you mean `{}`?", p.display()))
            .or_else(|| Some("paths are relative to the recipe file's directory".into()));
        out.push(r.diagnostic_at(span, message, help));
    }
    out
}

/// The likely intended path, as the user would write it (relative to the recipe).
fn suggestion(
    r: &Recipe,
    file: &Path,
    exists: &dyn Fn(&Path) -> bool,
    list_dir: &dyn Fn(&Path) -> Vec<String>,
) -> Option<PathBuf> {
    let name = file.file_name()?.to_str()?;
    let parent = file.parent().unwrap_or(Path::new(""));
    let listing = list_dir(&r.base_dir.join(parent));
    if let Some(best) = did_you_mean(name, listing.iter().map(String::as_str)) {
        return Some(parent.join(best));
    }
    let mut candidates: Vec<PathBuf> = Vec::new();
    // The same name in a directory another import uses.
    let mut dirs: Vec<&Path> = r
        .surfaces
        .values()
        .filter_map(|o| o.file.parent())
        .filter(|d| *d != parent)
        .collect();
    dirs.sort();
    dirs.dedup();
    candidates.extend(dirs.iter().map(|d| d.join(name)));
    // Another letter case, or another gOcad extension.
    let stem = Path::new(name)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or(name);
    for n in [name.to_lowercase(), name.to_uppercase()] {
        candidates.push(parent.join(n));
    }
    for ext in ["ts", "TS", "ml", "gp", "wl", "pl"] {
        candidates.push(parent.join(format!("{stem}.{ext}")));
    }
    candidates
        .into_iter()
        .find(|c| c != file && exists(&r.base_dir.join(c)))
}
