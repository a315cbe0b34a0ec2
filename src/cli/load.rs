//! Reading and validating a recipe file (the filesystem side of `recipe::parse`).

use super::Failure;
use crate::recipe::{self, Recipe};
use std::path::Path;

/// Reads, parses and validates the recipe, including that every imported file exists.
pub fn load(path: &Path) -> Result<Recipe, Failure> {
    let bytes = std::fs::read(path)
        .map_err(|e| Failure(format!("error: cannot read recipe {}: {e}", path.display())))?;
    let text =
        String::from_utf8(bytes).map_err(|e| not_utf8(path, e.as_bytes(), e.utf8_error()))?;
    let r = recipe::parse(path, &text).map_err(|d| render(&d))?;
    let list_dir = |d: &Path| -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(d)
            .map(|it| {
                it.filter_map(|e| e.ok())
                    .map(|e| e.file_name().to_string_lossy().into_owned())
                    .collect()
            })
            .unwrap_or_default();
        v.sort();
        v
    };
    let missing = recipe::check_files_with_listing(&r, &file_kind, &list_dir);
    if !missing.is_empty() {
        return Err(render(&missing));
    }
    Ok(r)
}

/// A recipe that is not UTF-8 (as TOML must be), at the first byte that is not, by line and
/// column (in characters, as every recipe error counts them).
fn not_utf8(path: &Path, bytes: &[u8], e: std::str::Utf8Error) -> Failure {
    let good = &bytes[..e.valid_up_to()];
    let line_start = good.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
    let line = good.iter().filter(|&&b| b == b'\n').count() + 1;
    let col = String::from_utf8_lossy(&good[line_start..]).chars().count() + 1;
    let bad = &bytes[e.valid_up_to()..];
    let shown: Vec<String> = bad
        .iter()
        .take(e.error_len().unwrap_or(bad.len()).max(1))
        .map(|b| format!("0x{b:02x}"))
        .collect();
    Failure(format!(
        "error: {}:{line}:{col}: the recipe is not UTF-8 text (byte {} here); help: TOML files \
         are UTF-8: save the recipe as UTF-8 (a Latin-1 or Windows-1252 editor setting writes \
         accented letters this way)",
        path.display(),
        shown.join(" ")
    ))
}

/// What is at `path`, links followed (a link to a file is the file).
pub(super) fn file_kind(path: &Path) -> recipe::FileKind {
    use recipe::FileKind;
    let Ok(meta) = std::fs::metadata(path) else {
        return FileKind::Missing;
    };
    let t = meta.file_type();
    if t.is_file() {
        return FileKind::File;
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return FileKind::Other("a FIFO (a named pipe)");
        }
        if t.is_block_device() || t.is_char_device() {
            return FileKind::Other("a device");
        }
    }
    if t.is_dir() {
        FileKind::Other("a directory")
    } else {
        FileKind::Other("not a regular file")
    }
}

fn render(diags: &[recipe::Diagnostic]) -> Failure {
    Failure(recipe::render(diags))
}

/// `recipe check`.
pub fn check(path: &Path) -> Result<(), Failure> {
    let r = load(path)?;
    outln!(
        "{}: ok ({} surfaces, {} intersection pairs, {} curve rules)",
        path.display(),
        r.surfaces.len(),
        r.intersect.len(),
        r.mesh.curves.len()
    );
    Ok(())
}
