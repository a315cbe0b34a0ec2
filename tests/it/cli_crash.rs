//! Crash points: a build stopped at each of its writes in turn (`RECIPE_CRASH_AT_WRITE`, see
//! `engine::crash`), as a power cut would stop it, of every kind the build makes: cache
//! entries, records, outputs, the report, the lock file, and with `--locked` each staged output
//! moved into place. After each, the next build succeeds, leaves no temporary behind, and writes
//! the outputs and lock file a build that was never stopped writes. A build paused before its
//! last write (`RECIPE_PAUSE_AT`) shows that a second build waits for it.

use crate::common_cli::*;
use std::collections::BTreeSet;
use std::path::Path;
use std::process::{Command, Stdio};

/// Runs `recipe build --quiet -j 1 <extra> didactic.toml` in a copy of `template` stopped at
/// write `n`: the path it was writing, or `None` when the build has fewer writes and finished.
fn stopped_at(template: &Path, n: usize, extra: &[&str]) -> (Scratch, Option<String>) {
    let s = Scratch {
        dir: tempfile::tempdir().expect("temp dir"),
    };
    copy_dir(template, s.dir.path());
    let out = Command::new(env!("CARGO_BIN_EXE_recipe"))
        .args(["build", "--quiet", "-j", "1"])
        .args(extra)
        .arg("didactic.toml")
        .current_dir(s.dir.path())
        .env_remove("RECIPE_CACHE_DIR")
        .env(engine::crash::CRASH_AT_WRITE, n.to_string())
        .stdout(Stdio::null())
        .output()
        .expect("run recipe");
    let err = String::from_utf8_lossy(&out.stderr);
    if out.status.success() {
        return (s, None);
    }
    assert_eq!(
        out.status.code(),
        Some(engine::crash::CRASH_STATUS),
        "{err}"
    );
    let path = err
        .lines()
        .find_map(|l| l.strip_prefix(&format!("crash point: write {n}: ")))
        .unwrap_or_else(|| panic!("the crash point names its path: {err}"));
    (s, Some(path.to_string()))
}

/// The files the next build must write as an unstopped one does: the model's outputs (not the
/// report, which holds timings) and the lock file, by name.
fn written(s: &Scratch) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(s.path("out/didactic"))
        .expect("the output directory")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("didactic."))
        .map(|n| {
            let bytes = std::fs::read(s.path(&format!("out/didactic/{n}"))).unwrap();
            (n, bytes)
        })
        .collect();
    files.sort();
    files.push((
        "lock".into(),
        std::fs::read(s.path("didactic.toml.lock")).unwrap(),
    ));
    files
}

/// What a stopped write was: its kind, from where it writes.
fn kind(path: &str) -> &'static str {
    match path {
        p if p.contains("/.recipe/objects/") => "cache object",
        p if p.contains("/.recipe/actions/") => "cache action",
        p if p.contains("/.recipe/records/") => "record",
        p if p.ends_with("didactic.toml.lock") => "lock file",
        p if p.ends_with("report.json") || p.ends_with("report.html") => "report",
        p if p.contains(&format!("/out/{}", engine::store::TEMP_PREFIX)) => "staged output",
        p if p.contains("/out/") => "output",
        _ => "other",
    }
}

/// Stops the build `extra` from `template` at every write in turn; after each, `recover` builds
/// again, which must succeed cleanly and write `expected`. Returns the kinds of write stopped.
fn every_write(template: &Path, extra: &[&str], recover: &[&str]) -> BTreeSet<&'static str> {
    let expected = {
        let s = Scratch {
            dir: tempfile::tempdir().expect("temp dir"),
        };
        copy_dir(template, s.dir.path());
        let (ok, _, err) = s.build(recover);
        assert!(ok, "{err}");
        written(&s)
    };
    let mut kinds = BTreeSet::new();
    for n in 1.. {
        let (s, at) = stopped_at(template, n, extra);
        let Some(path) = at else {
            assert!(n > 10, "the build wrote only {} files", n - 1);
            break;
        };
        kinds.insert(kind(&path));
        let (ok, _, err) = s.build(recover);
        assert!(ok, "after a stop at write {n} ({path}): {err}");
        assert_eq!(debris(&s), Vec::<String>::new(), "after a stop at {path}");
        assert!(
            written(&s) == expected,
            "after a stop at {path}: outputs differ"
        );
    }
    kinds
}

#[test]
fn a_build_stopped_at_any_of_its_writes_is_finished_by_the_next_with_the_same_outputs() {
    // The example built, then edited: the build re-runs a few nodes and writes each kind of file.
    let s = Scratch::didactic_built();
    s.edit("\"F2\" = { size = 100.0 }", "\"F2\" = { size = 90.0 }");
    let kinds = every_write(s.dir.path(), &[], &[]);
    let all = [
        "cache object",
        "cache action",
        "record",
        "output",
        "report",
        "lock file",
    ];
    assert_eq!(kinds, BTreeSet::from(all), "the kinds of write stopped");
}

#[test]
fn a_locked_build_stopped_at_any_of_its_writes_or_moves_into_place_is_finished_by_the_next() {
    // Outputs lost since the last build: --locked writes them into a staging directory, then
    // moves each into the output directory.
    let s = Scratch::didactic_built();
    for f in ["didactic.msh", "didactic.vtu"] {
        std::fs::remove_file(s.path(&format!("out/didactic/{f}"))).unwrap();
    }
    let kinds = every_write(s.dir.path(), &["--locked"], &["--locked"]);
    assert!(
        kinds.contains("output") && kinds.contains("record"),
        "{kinds:?}"
    );
}

#[test]
fn a_build_paused_before_its_lock_file_keeps_a_second_build_waiting_until_it_is_done() {
    // A build of a new version is held just before it writes the lock file, its last write;
    // meanwhile the old version is built again. The cache stays locked until the lock file and
    // report are written, so the second build cannot finish first and leave the first one's
    // lock file beside its own outputs.
    let old = "\"F2\" = { size = 100.0 }";
    let new = "\"F2\" = { size = 70.0 }";
    let s = Scratch::didactic_built();
    let flag = s.path("paused");
    let spawn = |pause: bool| {
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_recipe"));
        cmd.args(["build", "--quiet", "didactic.toml"])
            .current_dir(s.path(""))
            .env_remove("RECIPE_CACHE_DIR")
            .stderr(Stdio::piped());
        if pause {
            cmd.env(engine::crash::PAUSE_AT, "didactic.toml.lock")
                .env(engine::crash::PAUSE_FLAG, &flag);
        }
        cmd.spawn().expect("run recipe")
    };
    s.edit(old, new);
    let mut first = spawn(true);
    let started = std::time::Instant::now();
    while !flag.exists() {
        assert!(
            first.try_wait().unwrap().is_none(),
            "the first build ended unpaused"
        );
        assert!(
            started.elapsed().as_secs() < 120,
            "the first build never paused"
        );
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    s.edit(new, old);
    let mut second = spawn(false);
    // A cached build takes a fraction of a second: three seconds on, it is still waiting.
    std::thread::sleep(std::time::Duration::from_secs(3));
    assert!(
        second.try_wait().unwrap().is_none(),
        "the second build finished while the first held the cache"
    );
    std::fs::remove_file(&flag).unwrap();
    for child in [first, second] {
        let out = child.wait_with_output().expect("the build ends");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    // The second build's version is the recipe's: its outputs, lock file and report agree.
    let (ok, _, err) = s.build(&["--locked"]);
    assert!(ok, "the lock file is the outputs' version's: {err}");
    let report = std::fs::read(s.path("out/didactic/report.json")).expect("the report");
    let report: serde_json::Value = serde_json::from_slice(&report).expect("JSON");
    let alone = Scratch::didactic_built();
    let expected = std::fs::read(alone.path("out/didactic/report.json")).expect("the report");
    let expected: serde_json::Value = serde_json::from_slice(&expected).expect("JSON");
    assert_eq!(
        report["counts"], expected["counts"],
        "the report is the old version's"
    );
}
