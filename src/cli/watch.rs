//! `recipe build --watch`: rebuild on every save of the recipe or of an imported file.
//!
//! Decisions: parent directories are watched (non-recursively), so editors that save by writing a
//! temporary file and renaming it over the original are seen; only events that name the recipe or
//! an imported file count, and never mere accesses (the build's own reads of those files would
//! otherwise wake it forever); a burst of events is debounced until 150 ms pass quietly; then the
//! watched files are hashed and a build starts only when some content differs from what the last
//! build was given, so a touch, a save without a change or a read never rebuilds and an idle
//! watcher rests. An invalid recipe prints its errors once and waits for a change; a change that
//! arrives during a build is queued in the channel and starts the next build when this one ends.

use super::{BuildArgs, Failure, build, load};
use notify::{EventKind, RecursiveMode, Watcher};
use std::collections::{BTreeMap, BTreeSet};
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
                errln!("     Warning cannot watch {}: {e}", d.display());
            }
        }
        for d in watched_dirs.difference(&dirs) {
            let _ = watcher.unwatch(d);
        }
        watched_dirs = dirs;

        let built = contents(&files);
        if let Err(Failure(msg)) = build::run(&args) {
            errln!("{msg}");
        }
        builds += 1;
        if args.max_builds.is_some_and(|m| builds >= m) {
            return Ok(());
        }
        if !args.quiet {
            errln!(
                "    Watching {} files for changes (Ctrl-C to stop)",
                files.len()
            );
        }
        wait_for_change(&rx, &files, &built)?;
    }
}

/// Each watched file's content hash (`None` when it cannot be read: a change all the same when
/// it comes back).
fn contents(files: &BTreeSet<PathBuf>) -> BTreeMap<PathBuf, Option<blake3::Hash>> {
    files
        .iter()
        .map(|f| (f.clone(), std::fs::read(f).ok().map(|b| blake3::hash(&b))))
        .collect()
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

/// Blocks until a burst of events that may change one of `files` is over and some file's content
/// differs from `built`.
fn wait_for_change(
    rx: &mpsc::Receiver<notify::Result<notify::Event>>,
    files: &BTreeSet<PathBuf>,
    built: &BTreeMap<PathBuf, Option<blake3::Hash>>,
) -> Result<(), Failure> {
    let relevant = |ev: &notify::Result<notify::Event>| match ev {
        Ok(e) => {
            !matches!(e.kind, EventKind::Access(_)) && e.paths.iter().any(|p| files.contains(p))
        }
        Err(_) => false,
    };
    loop {
        let ev = rx
            .recv()
            .map_err(|_| Failure("error: the file watcher stopped".into()))?;
        if !relevant(&ev) {
            continue;
        }
        while rx.recv_timeout(QUIET_PERIOD).is_ok() {}
        if contents(files) != *built {
            return Ok(());
        }
    }
}
