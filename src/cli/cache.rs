//! Where the cache and the lock file live, and the commands that only read or tidy them
//! (`explain`, `graph`, `clean`, `gc`).

use super::{CacheArgs, Failure};
use engine::{self, LockFile};
use std::path::{Path, PathBuf};

/// `--cache-dir`, else `RECIPE_CACHE_DIR` (clap reads it), else `.recipe/` beside the recipe.
pub fn cache_dir(recipe: &Path, args: &CacheArgs) -> PathBuf {
    args.cache_dir
        .clone()
        .unwrap_or_else(|| recipe_dir(recipe).join(".recipe"))
}

pub fn recipe_dir(recipe: &Path) -> PathBuf {
    match recipe.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// The lock file beside the recipe: `didactic.toml` → `didactic.toml.lock`.
pub fn lock_path(recipe: &Path) -> PathBuf {
    let mut name = recipe
        .file_name()
        .map(|n| n.to_os_string())
        .unwrap_or_default();
    name.push(".lock");
    recipe_dir(recipe).join(name)
}

/// The last build's report (JSON), kept in the cache for `explain`.
pub fn last_report_path(cache: &Path) -> PathBuf {
    cache.join("last-report.json")
}

/// The last build's graph (DOT), kept in the cache for `graph`.
pub fn last_graph_path(cache: &Path) -> PathBuf {
    cache.join("last-graph.dot")
}

fn read_last(
    recipe: &Path,
    args: &CacheArgs,
    path: fn(&Path) -> PathBuf,
) -> Result<String, Failure> {
    let p = path(&cache_dir(recipe, args));
    std::fs::read_to_string(&p).map_err(|e| match e.kind() {
        std::io::ErrorKind::NotFound => Failure(format!(
            "error: no build recorded in {} yet: run `recipe build {}` first",
            p.display(),
            recipe.display()
        )),
        _ => Failure(format!(
            "error: cannot read the last build's record {}: {e}",
            p.display()
        )),
    })
}

/// `recipe explain`: why each node of the last build ran (or did not).
pub fn explain(recipe: &Path, args: &CacheArgs) -> Result<(), Failure> {
    let text = read_last(recipe, args, last_report_path)?;
    let r: serde_json::Value = serde_json::from_str(&text)
        .map_err(|e| Failure(format!("error: the last build's report is unreadable: {e}")))?;
    let nodes = r["nodes"].as_array().cloned().unwrap_or_default();
    let width = nodes
        .iter()
        .filter_map(|n| n["name"].as_str())
        .map(str::len)
        .max()
        .unwrap_or(0);
    for n in &nodes {
        let (name, state, reason) = (
            n["name"].as_str().unwrap_or(""),
            n["state"].as_str().unwrap_or(""),
            n["reason"].as_str().unwrap_or(""),
        );
        outln!("{name:<width$}  {state:<8} {reason}");
    }
    Ok(())
}

/// `recipe graph`: the last build's DAG in DOT, expanded part included, with node states.
pub fn graph(recipe: &Path, args: &CacheArgs) -> Result<(), Failure> {
    out!("{}", read_last(recipe, args, last_graph_path)?);
    Ok(())
}

pub fn clean(recipe: &Path, args: &CacheArgs) -> Result<(), Failure> {
    let dir = cache_dir(recipe, args);
    if engine::clean(&dir)? {
        outln!("removed {}", dir.display());
    } else {
        outln!("nothing to remove: {} does not exist", dir.display());
    }
    Ok(())
}

pub fn gc(recipe: &Path, args: &CacheArgs) -> Result<(), Failure> {
    let dir = cache_dir(recipe, args);
    if !dir.exists() {
        outln!("nothing to collect: {} does not exist", dir.display());
        return Ok(());
    }
    let mut keep = LockFile::default();
    if let Ok(text) = std::fs::read_to_string(lock_path(recipe)) {
        keep = LockFile::parse(&text)
            .map_err(|e| Failure(format!("error: {}: {e}", lock_path(recipe).display())))?;
    }
    if let Some(last) = engine::gc::last_build(&dir) {
        keep.nodes.extend(last.nodes);
        keep.outputs.extend(last.outputs);
    }
    let stats = engine::gc(&dir, &keep)?;
    outln!(
        "kept {} cache entries, removed {} ({} bytes freed)",
        stats.kept,
        stats.removed,
        stats.bytes_freed
    );
    Ok(())
}
