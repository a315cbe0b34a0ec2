//! Reading and validating a recipe file (the filesystem side of `recipe::parse`).

use super::Failure;
use crate::recipe::{self, Recipe};
use std::path::Path;

/// Reads, parses and validates the recipe, including that every imported file exists.
pub fn load(path: &Path) -> Result<Recipe, Failure> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| Failure(format!("error: cannot read recipe {}: {e}", path.display())))?;
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
    let missing = recipe::check_files_with_listing(&r, &|p: &Path| p.is_file(), &list_dir);
    if !missing.is_empty() {
        return Err(render(&missing));
    }
    Ok(r)
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
