//! Where the cache and the lock file live, and the commands that only read or tidy them
//! (`explain`, `graph`, `clean`, `gc`).
//!
//! Any number of recipes may share one cache directory (one `.recipe/` for a folder of recipes,
//! one `--cache-dir` or CI cache for a repository): node entries are shared by key, and each
//! recipe's own state lives in its engine record, `<cache>/records/<name>/`: the engine's
//! manifest (the baseline of rebuild reasons), what its emitting nodes wrote and what the report
//! derived, the last build's report and graph (for `explain` and `graph`), the state of the
//! report in the output directory (`report_state`) and `recipe`, the recipe's path, by which
//! `gc` finds its lock file. The record is named after the recipe's path relative to the cache
//! directory, both canonical ([`RecipeRecord`]): two recipes of the same file name in different
//! folders get two records, and a repository checked out elsewhere with its cache (a CI cache
//! restored into another workspace) keeps its records. A recipe that moves away from its cache
//! starts a new record; the old one is forgotten by the next `gc`, which finds no recipe at its
//! path.
//!
//! Caches written before records kept one `last-report.json`, `last-graph.dot` and manifest at
//! their root, whichever recipe built last: they are not migrated (they may be another recipe's),
//! but ignored, so each recipe's first build explains its nodes as new, and `gc` deletes them.

use super::user_file::{UserFile, read_text};
use super::{CacheArgs, Failure};
use engine::checked::CheckedError;
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

/// A recipe's record in a cache: the engine's record name and the recipe's path as the record
/// keeps it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RecipeRecord {
    /// The engine's record name: the recipe's file name (made a plain name), `-`, and 16 hex
    /// digits of blake3 over `path`.
    pub name: String,
    /// The recipe's canonical path relative to the canonical cache directory, `/`-separated
    /// (absolute where no relative path leads there, as across Windows drives).
    pub path: String,
}

/// Lexically resolved `path`: absolute, its deepest existing ancestor canonical (symbolic links
/// resolved), `.` dropped and `..` applied to what follows, so a cache directory names the same
/// place before and after its first build creates it.
fn canonical(path: &Path) -> PathBuf {
    let abs = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let mut rest = Vec::new();
    let mut base = abs.as_path();
    let start = loop {
        if let Ok(c) = std::fs::canonicalize(base) {
            break c;
        }
        match (base.parent(), base.file_name()) {
            (Some(parent), Some(name)) => {
                rest.push(name.to_os_string());
                base = parent;
            }
            _ => break base.to_path_buf(),
        }
    };
    let mut out = start;
    for c in rest.iter().rev() {
        match c.to_str() {
            Some(".") => {}
            Some("..") => {
                out.pop();
            }
            _ => out.push(c),
        }
    }
    out
}

/// `to` relative to `from` (both absolute, canonical), `/`-separated; `to` whole where they share
/// no root.
fn relative(from: &Path, to: &Path) -> String {
    use std::path::Component;
    let a: Vec<Component> = from.components().collect();
    let b: Vec<Component> = to.components().collect();
    let common = a.iter().zip(&b).take_while(|(x, y)| x == y).count();
    let shares_root = common > 0 && matches!(a[0], Component::RootDir | Component::Prefix(_));
    if !shares_root {
        return to.to_string_lossy().replace('\\', "/");
    }
    let mut parts: Vec<String> = vec!["..".to_string(); a.len() - common];
    parts.extend(
        b[common..]
            .iter()
            .map(|c| c.as_os_str().to_string_lossy().into_owned()),
    );
    parts.join("/")
}

impl RecipeRecord {
    /// The record of `recipe` in the cache directory `cache`.
    pub fn of(recipe: &Path, cache: &Path) -> RecipeRecord {
        let path = relative(&canonical(cache), &canonical(recipe));
        let file: String = recipe
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default()
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-') {
                    c
                } else {
                    '_'
                }
            })
            .take(64)
            .collect();
        let file = file.trim_start_matches('.');
        let hash = blake3::hash(path.as_bytes()).to_hex();
        let name = if file.is_empty() {
            hash[..16].to_string()
        } else {
            format!("{file}-{}", &hash[..16])
        };
        RecipeRecord { name, path }
    }

    /// The record's directory in `cache`.
    pub fn dir(&self, cache: &Path) -> PathBuf {
        engine::manifest::record_dir(cache, &self.name)
    }

    /// Where the recipe is, given the cache directory the record is in.
    pub fn recipe_in(&self, cache: &Path) -> PathBuf {
        let p = Path::new(&self.path);
        if p.is_absolute() {
            return p.to_path_buf();
        }
        let mut out = canonical(cache);
        for part in self.path.split('/') {
            match part {
                "" | "." => {}
                ".." => {
                    out.pop();
                }
                _ => out.push(part),
            }
        }
        out
    }

    /// Writes the recipe's path into the record (the engine made its directory), unless it is
    /// already there.
    pub fn save(&self, cache: &Path) -> Result<(), Failure> {
        super::build::write_record(&self.dir(cache).join(RECIPE_FILE), self.path.as_bytes())
    }
}

/// The file in a record that holds the recipe's path ([`RecipeRecord::path`]).
const RECIPE_FILE: &str = "recipe";

/// The last build's report (JSON), kept in the recipe's record for `explain`.
pub fn last_report_path(record_dir: &Path) -> PathBuf {
    record_dir.join("last-report.json")
}

/// The last build's graph (DOT), kept in the recipe's record for `graph`.
pub fn last_graph_path(record_dir: &Path) -> PathBuf {
    record_dir.join("last-graph.dot")
}

fn read_last(
    recipe: &Path,
    args: &CacheArgs,
    path: fn(&Path) -> PathBuf,
) -> Result<String, Failure> {
    let cache = cache_dir(recipe, args);
    let p = path(&RecipeRecord::of(recipe, &cache).dir(&cache));
    let bytes = engine::checked::read(&p).map_err(|e| match e {
        CheckedError::Missing => Failure(format!(
            "error: no build recorded in {} yet: run `recipe build {}` first",
            p.display(),
            recipe.display()
        )),
        CheckedError::Damaged(what) => Failure(format!(
            "error: the last build's record {} is damaged: {what}: run `recipe build {}` to \
             record it again",
            p.display(),
            recipe.display()
        )),
        CheckedError::Io(e) => Failure(format!(
            "error: cannot read the last build's record {}: {e}",
            p.display()
        )),
    })?;
    String::from_utf8(bytes).map_err(|_| {
        Failure(format!(
            "error: the last build's record {} is not text: run `recipe build {}` to record it again",
            p.display(),
            recipe.display()
        ))
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
    match engine::clean(&dir)? {
        engine::Cleaned::Removed => outln!("removed {}", dir.display()),
        engine::Cleaned::Absent => {
            outln!("nothing to remove: {} does not exist", dir.display())
        }
        engine::Cleaned::Kept(left) => outln!(
            "removed the cache's entries from {}; left what it holds that is not the cache's: {}",
            dir.display(),
            engine::marker::listed(&left)
        ),
    }
    Ok(())
}

/// The lock file of `recipe`, if it has one.
fn read_lock(recipe: &Path) -> Result<Option<LockFile>, Failure> {
    let path = lock_path(recipe);
    let cannot = |why: String| {
        Failure(format!(
            "error: cannot read the lock file {}: {why}",
            path.display()
        ))
    };
    match read_text(&path) {
        Ok(UserFile::Text(text)) => LockFile::parse(&text)
            .map(Some)
            .map_err(|e| Failure(format!("error: {}: {e}", path.display()))),
        Ok(UserFile::Missing) => Ok(None),
        Ok(UserFile::Not(what)) => Err(cannot(format!("it is {what}, not a file"))),
        Err(e) => Err(cannot(e.to_string())),
    }
}

/// Where a recorded recipe's builds write outside the cache (its lock file, its output directory,
/// its record), for the sweep of their debris; `None` for a recipe that no longer parses (its
/// output directory is unknown).
fn debris_places(recipe: &Path, cache: &Path) -> Option<(PathBuf, PathBuf, PathBuf)> {
    let UserFile::Text(text) = read_text(recipe).ok()? else {
        return None;
    };
    let r = crate::recipe::parse(recipe, &text).ok()?;
    let output = recipe_dir(recipe).join(&r.output.dir);
    let record = RecipeRecord::of(recipe, cache).dir(cache);
    Some((lock_path(recipe), output, record))
}

/// `recipe gc`: keeps what the lock file or the last build of any recipe that built into the
/// cache references (the one named included, even if it never built there), and removes the
/// rest, and what killed builds of those recipes left outside the cache (`debris`). A record whose recipe is gone from its path is forgotten first, and a record that does
/// not say where its recipe is (its build was interrupted) is kept.
pub fn gc(recipe: &Path, args: &CacheArgs) -> Result<(), Failure> {
    let dir = cache_dir(recipe, args);
    if !dir.exists() {
        outln!("nothing to collect: {} does not exist", dir.display());
        return Ok(());
    }
    engine::marker::require(&dir)?;
    let mut recipes = vec![canonical(recipe)];
    let mut forgotten = Vec::new();
    let names = engine::manifest::records(&dir)
        .map_err(|e| Failure(format!("error: cannot read {}: {e}", dir.display())))?;
    for name in names {
        let record_dir = engine::manifest::record_dir(&dir, &name);
        // A record that does not say where its recipe is, or says it damaged, is kept.
        let Some(path) = engine::checked::read(&record_dir.join(RECIPE_FILE))
            .ok()
            .and_then(|b| String::from_utf8(b).ok())
        else {
            continue;
        };
        let record = RecipeRecord { name, path };
        let at = record.recipe_in(&dir);
        if at.is_file() {
            recipes.push(at);
        } else if engine::forget(&dir, &record.name)? {
            forgotten.push(at);
        }
    }
    recipes.sort();
    recipes.dedup();
    let mut keep = Vec::new();
    for r in &recipes {
        keep.extend(read_lock(r)?);
    }
    let places: Vec<(PathBuf, PathBuf, PathBuf)> = recipes
        .iter()
        .filter_map(|r| debris_places(r, &dir))
        .collect();
    let swept = std::cell::Cell::new(0);
    let stats = engine::gc_and(&dir, &keep, &|| {
        for (lock, output, record) in &places {
            swept.set(swept.get() + super::debris::sweep_recipe(lock, output, Some(record)));
        }
    })?;
    if swept.get() > 0 {
        outln!(
            "removed {} temporar{} that killed builds left beside outputs and recipes",
            swept.get(),
            if swept.get() == 1 { "y" } else { "ies" }
        );
    }
    // What the command line kept at the root before records.
    for old in ["last-report.json", "last-graph.dot"] {
        let _ = std::fs::remove_file(dir.join(old));
    }
    for f in &forgotten {
        outln!(
            "forgot the last build of {}: no recipe there now",
            f.display()
        );
    }
    outln!(
        "kept {} cache entries, removed {} ({} bytes freed); kept for {} recipe{}",
        stats.kept,
        stats.removed,
        stats.bytes_freed,
        recipes.len(),
        if recipes.len() == 1 { "" } else { "s" }
    );
    Ok(())
}
