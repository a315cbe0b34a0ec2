//! `recipe build --watch`: rebuild on every save of the recipe or of an imported file.
//!
//! Decisions: parent directories are watched (non-recursively), so editors that save by writing a
//! temporary file and renaming it over the original are seen; only events that name the recipe or
//! an imported file count, so the build's own cache, lock file and outputs never trigger a
//! rebuild; a burst of events is debounced until 150 ms pass quietly, then files are re-hashed by
//! the build itself (content keys: a touch without a change re-runs nothing); an invalid recipe
//! prints its errors and waits for the next save; a change that arrives during a build is queued
//! in the channel and starts the next build as soon as this one ends.

use super::{BuildArgs, Failure, build, load};
use notify::{RecursiveMode, Watcher};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

const QUIET_PERIOD: Duration = Duration::from_millis(150);

pub fn run(args: &BuildArgs) -> Result<(), Failure> {
    let recipe = std::path::absolute(&args.recipe)?;
    let args = BuildArgs {
        recipe: recipe.clone(),
        ..args.clone()
    };
    let (tx, rx) = mpsc::channel::<notify::Result<notify::Event>>();
    let mut watcher = notify::recommended_watcher(move |res| {
        let _ = tx.send(res);
    })?;
    let mut watched_dirs: BTreeSet<PathBuf> = BTreeSet::new();
    let mut builds = 0usize;
    loop {
        let files = watch_set(&recipe);
        let dirs: BTreeSet<PathBuf> = files
            .iter()
            .filter_map(|f| f.parent().map(Path::to_path_buf))
            .collect();
        for d in dirs.difference(&watched_dirs) {
            if let Err(e) = watcher.watch(d, RecursiveMode::NonRecursive) {
                eprintln!("     Warning cannot watch {}: {e}", d.display());
            }
        }
        for d in watched_dirs.difference(&dirs) {
            let _ = watcher.unwatch(d);
        }
        watched_dirs = dirs;

        if let Err(Failure(msg)) = build::run(&args) {
            eprintln!("{msg}");
        }
        builds += 1;
        if args.max_builds.is_some_and(|m| builds >= m) {
            return Ok(());
        }
        eprintln!(
            "    Watching {} files for changes (Ctrl-C to stop)",
            files.len()
        );
        wait_for_change(&rx, &files)?;
    }
}

/// The recipe and, when it loads, every file it imports (absolute paths).
fn watch_set(recipe: &Path) -> BTreeSet<PathBuf> {
    let mut files = BTreeSet::from([recipe.to_path_buf()]);
    if let Ok(r) = load::load(recipe) {
        for s in r.surfaces.values() {
            if let Ok(p) = std::path::absolute(r.base_dir.join(&s.file)) {
                files.insert(p);
            }
        }
    }
    files
}

/// Blocks until an event names one of `files`, then until the burst is over.
fn wait_for_change(
    rx: &mpsc::Receiver<notify::Result<notify::Event>>,
    files: &BTreeSet<PathBuf>,
) -> Result<(), Failure> {
    let relevant = |ev: &notify::Result<notify::Event>| match ev {
        Ok(e) => e.paths.iter().any(|p| files.contains(p)),
        Err(_) => false,
    };
    loop {
        let ev = rx
            .recv()
            .map_err(|_| Failure("error: the file watcher stopped".into()))?;
        if relevant(&ev) {
            break;
        }
    }
    while rx.recv_timeout(QUIET_PERIOD).is_ok() {}
    Ok(())
}
