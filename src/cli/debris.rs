//! What a killed build leaves behind, found and removed by the next build of the recipe, or by
//! `gc` for every recipe recorded in the cache, while it holds the cache's lock: temporaries of atomic writes (`.tmp-<file name>.XXXXXX`) in the
//! output directory, beside the recipe (its lock file's) and in the recipe's record, and staging
//! directories of `--locked` builds beside the output directory whose process is gone.
//!
//! Decisions and why:
//! - Only names this program makes are touched: a temporary is `.tmp-`, a file name, a dot and
//!   six letters or digits ([`is_temporary`]); a staging directory holds the [`OWNER`] file its
//!   build wrote. A user's `.tmp-notes` stays.
//! - A staging directory is removed only when the process that made it is gone (its pid is not
//!   in `/proc`); where `/proc` does not exist, only when it is over a day old.

use std::path::Path;
use std::time::{Duration, SystemTime};

/// The file a staging directory holds, with the pid of the build that made it.
pub const OWNER: &str = ".georecipe-staging";

/// Is `name` the name of a temporary of `engine::write_atomic`?
pub fn is_temporary(name: &str) -> bool {
    let Some(rest) = name.strip_prefix(engine::store::TEMP_PREFIX) else {
        return false;
    };
    match rest.rsplit_once('.') {
        Some((target, suffix)) => {
            !target.is_empty()
                && suffix.len() == 6
                && suffix.chars().all(|c| c.is_ascii_alphanumeric())
        }
        None => false,
    }
}

/// Removes what killed builds of one recipe left: temporaries beside its lock file, in its
/// output directory and in its record (unless the cache is only read: `None`), and its dead
/// staging directories; returns how many. Run under the cache's lock (by the recipe's next
/// build, and by `gc`).
pub fn sweep_recipe(lock_file: &Path, output_dir: &Path, record_dir: Option<&Path>) -> usize {
    engine::store::sweep_temporaries_of(lock_file).unwrap_or(0)
        + sweep_temporaries(output_dir)
        + sweep_staging(output_dir)
        + record_dir.map_or(0, sweep_temporaries)
}

/// Removes the temporaries in `dir` (not below it); returns how many.
pub fn sweep_temporaries(dir: &Path) -> usize {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return 0;
    };
    entries
        .flatten()
        .filter(|e| e.file_type().is_ok_and(|t| t.is_file()))
        .filter(|e| is_temporary(&e.file_name().to_string_lossy()))
        .filter(|e| std::fs::remove_file(e.path()).is_ok())
        .count()
}

/// Removes the staging directories beside `output_dir` whose build is gone; returns how many.
pub fn sweep_staging(output_dir: &Path) -> usize {
    let (Some(parent), Some(name)) = (output_dir.parent(), output_dir.file_name()) else {
        return 0;
    };
    let parent = if parent.as_os_str().is_empty() {
        Path::new(".")
    } else {
        parent
    };
    let prefix = format!("{}{}-", engine::store::TEMP_PREFIX, name.to_string_lossy());
    let Ok(entries) = std::fs::read_dir(parent) else {
        return 0;
    };
    entries
        .flatten()
        .filter(|e| e.file_type().is_ok_and(|t| t.is_dir()))
        .filter(|e| e.file_name().to_string_lossy().starts_with(&prefix))
        .filter(|e| abandoned(&e.path()))
        .filter(|e| std::fs::remove_dir_all(e.path()).is_ok())
        .count()
}

/// Does the staging directory `dir` belong to a build that is gone?
fn abandoned(dir: &Path) -> bool {
    let owner = dir.join(OWNER);
    let Ok(super::user_file::UserFile::Text(text)) = super::user_file::read_text(&owner) else {
        return false;
    };
    let Ok(pid) = text.trim().parse::<u32>() else {
        return false;
    };
    let proc = Path::new("/proc");
    if proc.is_dir() {
        return !proc.join(pid.to_string()).exists();
    }
    let day = Duration::from_secs(24 * 3600);
    std::fs::metadata(&owner)
        .and_then(|m| m.modified())
        .is_ok_and(|t| SystemTime::now().duration_since(t).unwrap_or_default() > day)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_names_of_atomic_write_temporaries_count_as_temporaries() {
        assert!(is_temporary(".tmp-report.json.a1B2c3"));
        assert!(is_temporary(".tmp-didactic.toml.lock.XyZ012"));
        for name in [
            ".tmp-notes",
            ".tmp-report.json.abc",
            ".tmp-.abcdef",
            "tmp-report.json.abcdef",
            ".tmp-report.json.abc-ef",
        ] {
            assert!(!is_temporary(name), "{name}");
        }
    }

    #[test]
    fn temporaries_and_dead_builds_staging_go_and_everything_else_stays() {
        let root = tempfile::tempdir().unwrap();
        let out = root.path().join("out");
        std::fs::create_dir_all(&out).unwrap();
        for f in [".tmp-model.msh.q1w2e3", ".tmp-notes", "model.msh"] {
            std::fs::write(out.join(f), b"x").unwrap();
        }
        assert_eq!(sweep_temporaries(&out), 1);
        assert!(out.join(".tmp-notes").exists() && out.join("model.msh").exists());

        // A staging directory of a process that does not exist, one of this process, and a
        // directory with the same kind of name that is not a staging directory.
        let dead = root.path().join(".tmp-out-aaaaaa");
        let live = root.path().join(".tmp-out-bbbbbb");
        let other = root.path().join(".tmp-out-cccccc");
        for d in [&dead, &live, &other] {
            std::fs::create_dir_all(d).unwrap();
        }
        std::fs::write(dead.join(OWNER), u32::MAX.to_string()).unwrap();
        std::fs::write(live.join(OWNER), std::process::id().to_string()).unwrap();
        if Path::new("/proc").is_dir() {
            assert_eq!(sweep_staging(&out), 1);
            assert!(!dead.exists());
        }
        assert!(live.exists() && other.exists());
    }
}
