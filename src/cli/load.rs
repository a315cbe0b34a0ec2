//! Reading and validating a recipe file (the filesystem side of `recipe::parse`).

use super::Failure;
use crate::recipe::{self, Recipe};
use std::path::Path;

/// Reads, parses and validates the recipe, including that every imported file exists.
pub fn load(path: &Path) -> Result<Recipe, Failure> {
    let text = std::fs::read_to_string(path).map_err(|e| Failure(format!("error: cannot read recipe {}: {e}", path.display())))?;
    let r = recipe::parse(path, &text).map_err(|d| render(&d))?;
    let missing = recipe::check_files(&r, &|p: &Path| p.is_file());
    if !missing.is_empty() {
        return Err(render(&missing));
    }
    Ok(r)
}

fn render(diags: &[recipe::Diagnostic]) -> Failure {
    let mut s = String::new();
    for d in diags {
        s.push_str(&d.to_string());
        s.push('\n');
    }
    s.push_str(&format!("error: the recipe has {} error{}", diags.len(), if diags.len() == 1 { "" } else { "s" }));
    Failure(s)
}

/// `recipe check`.
pub fn check(path: &Path) -> Result<(), Failure> {
    let r = load(path)?;
    println!(
        "{}: ok ({} surfaces, {} intersection pairs, {} curve rules)",
        path.display(),
        r.surfaces.len(),
        r.intersect.len(),
        r.curve_rules().len()
    );
    Ok(())
}
