//! Where the cache and the lock file live, and the commands that only read or tidy them
//! (`explain`, `graph`, `clean`, `gc`).

use super::{CacheArgs, Failure};
use crate::engine::{self, BuildReport, LockFile};
use std::path::{Path, PathBuf};

/// `--cache-dir`, else `RECIPE_CACHE_DIR` (clap reads it), else `.recipe/` beside the recipe.
pub fn cache_dir(recipe: &Path, args: &CacheArgs) -> PathBuf {
    args.cache_dir.clone().unwrap_or_else(|| recipe_dir(recipe).join(".recipe"))
}

pub fn recipe_dir(recipe: &Path) -> PathBuf {
    match recipe.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// The lock file beside the recipe: `didactic.toml` → `didactic.toml.lock`.
pub fn lock_path(recipe: &Path) -> PathBuf {
    let mut name = recipe.file_name().map(|n| n.to_os_string()).unwrap_or_default();
    name.push(".lock");
    recipe_dir(recipe).join(name)
}

/// The last build's report, kept in the cache for `explain` and `graph`.
pub fn last_report_path(cache: &Path) -> PathBuf {
    cache.join("last-report.json")
}

fn read_last_report(recipe: &Path, args: &CacheArgs) -> Result<BuildReport, Failure> {
    let p = last_report_path(&cache_dir(recipe, args));
    let text = std::fs::read_to_string(&p)
        .map_err(|_| Failure(format!("error: no build recorded in {} yet: run `recipe build {}` first", p.display(), recipe.display())))?;
    BuildReport::from_json_text(&text).map_err(|e| Failure(format!("error: {}: {e}", p.display())))
}

/// `recipe explain`: why each node of the last build ran (or did not).
pub fn explain(recipe: &Path, args: &CacheArgs) -> Result<(), Failure> {
    let r = read_last_report(recipe, args)?;
    for n in &r.nodes {
        println!("{:<40} {:<8} {}", n.name, super::render::state_word(n.state), n.reason);
    }
    Ok(())
}

/// `recipe graph`: the last build's DAG in DOT, expanded part included.
pub fn graph(recipe: &Path, args: &CacheArgs) -> Result<(), Failure> {
    print!("{}", read_last_report(recipe, args)?.to_dot());
    Ok(())
}

pub fn clean(recipe: &Path, args: &CacheArgs) -> Result<(), Failure> {
    let dir = cache_dir(recipe, args);
    engine::clean(&dir)?;
    println!("removed {}", dir.display());
    Ok(())
}

pub fn gc(recipe: &Path, args: &CacheArgs) -> Result<(), Failure> {
    let dir = cache_dir(recipe, args);
    let mut keep = LockFile::default();
    if let Ok(text) = std::fs::read_to_string(lock_path(recipe)) {
        keep = LockFile::parse(&text).map_err(|e| Failure(format!("error: {}: {e}", lock_path(recipe).display())))?;
    }
    if let Ok(r) = read_last_report(recipe, args) {
        keep.merge(&LockFile::from_report(&r));
    }
    let stats = engine::gc(&dir, &keep)?;
    println!("{stats}");
    Ok(())
}
