//! The on-disk side of the engine: corrupt and missing cache entries, gc and clean, the lock
//! file's text form and diff, and parameter canonicalization as seen through node keys.

use crate::engine_support;

use engine::*;
use engine_support::*;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

fn chain(a_val: i64, runs: &Runs) -> BuildGraph {
    let mut g = BuildGraph::new();
    let a = g.add_op("a", konst(a_val, runs), &[]).unwrap();
    let b = g.add_op("b", konst(2, runs), &[]).unwrap();
    let s = g.add_op("s", add(0, runs), &[a, b]).unwrap();
    let m = g.add_op("m", modulo(3, runs), &[s]).unwrap();
    g.add_op("t", add(10, runs), &[m]).unwrap();
    g
}

fn entries(cache: &Path) -> Vec<PathBuf> {
    let mut v = Vec::new();
    for sub in ["objects", "actions"] {
        for e in std::fs::read_dir(cache.join(sub)).unwrap() {
            v.push(e.unwrap().path());
        }
    }
    v.sort();
    v
}

fn build_collecting(g: BuildGraph, o: &BuildOptions) -> (BuildReport, Vec<(String, String)>) {
    let corrupt = Mutex::new(Vec::new());
    let r = build(g, o, &|e| {
        if let Event::CacheCorrupt { name, detail } = e {
            corrupt.lock().unwrap().push((name.clone(), detail.clone()));
        }
    })
    .unwrap();
    (r, corrupt.into_inner().unwrap())
}

#[test]
fn truncating_or_corrupting_any_cache_entry_is_detected_repaired_and_then_fully_cached() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 2);
    let runs = Runs::default();
    let first = run(chain(1, &runs), &o);
    let expected: Vec<i64> = first.nodes.iter().map(|n| value(&first, &n.name)).collect();
    let all = entries(&o.cache_dir);
    assert_eq!(all.len(), 5 + 5, "objects 1, 2, 3, 0, 10 and five actions");
    for (mode, damage) in [("truncate", 0u8), ("flip", 1), ("append", 2)] {
        for path in &all {
            let mut bytes = std::fs::read(path).unwrap();
            match damage {
                0 => bytes.truncate(bytes.len() / 2),
                1 => bytes[0] ^= 0x55,
                _ => bytes.push(0),
            }
            std::fs::write(path, &bytes).unwrap();
            let (r, corrupt) = build_collecting(chain(1, &runs), &o);
            assert!(r.ok, "{mode} {}", path.display());
            assert!(
                !corrupt.is_empty(),
                "{mode} of {} went unnoticed",
                path.display()
            );
            let values: Vec<i64> = r.nodes.iter().map(|n| value(&r, &n.name)).collect();
            assert_eq!(values, expected, "{mode} {}", path.display());
            for (name, _) in &corrupt {
                assert!(matches!(
                    r.node(name).unwrap().reason,
                    RebuildReason::CacheCorrupt(_)
                ));
                assert_eq!(state(&r, name), NodeState::Ran);
            }
            let (again, corrupt) = build_collecting(chain(1, &runs), &o);
            assert!(corrupt.is_empty());
            assert!(
                again.nodes.iter().all(|n| n.state == NodeState::Cached),
                "{mode} {}: {:?}",
                path.display(),
                states(&again)
            );
        }
    }
}

/// Puts `kind` in place of the cache entry at `path`: a directory holding a file, a FIFO, or a
/// symbolic link to `/dev/zero`. False when this system cannot make it.
fn replace_entry(path: &Path, kind: &str) -> bool {
    std::fs::remove_file(path).unwrap();
    match kind {
        "directory" => {
            std::fs::create_dir_all(path.join("inside")).unwrap();
            std::fs::write(path.join("inside/file"), b"x").is_ok()
        }
        "fifo" => std::process::Command::new("mkfifo")
            .arg(path)
            .status()
            .is_ok_and(|s| s.success()),
        _ => {
            #[cfg(unix)]
            return Path::new("/dev/zero").exists()
                && std::os::unix::fs::symlink("/dev/zero", path).is_ok();
            #[cfg(not(unix))]
            false
        }
    }
}

/// Builds `g` in another thread and fails the test, rather than hang it, after a minute.
fn build_within_a_minute(g: BuildGraph, o: &BuildOptions) -> (BuildReport, Vec<(String, String)>) {
    let (tx, rx) = std::sync::mpsc::channel();
    let o = o.clone();
    std::thread::spawn(move || {
        let _ = tx.send(build_collecting(g, &o));
    });
    rx.recv_timeout(std::time::Duration::from_secs(60))
        .expect("the build finishes instead of blocking on the entry")
}

#[test]
fn a_directory_fifo_or_device_link_in_place_of_a_cache_entry_is_replaced_without_blocking() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 2);
    let runs = Runs::default();
    let first = run(chain(1, &runs), &o);
    let expected: Vec<i64> = first.nodes.iter().map(|n| value(&first, &n.name)).collect();
    for kind in ["directory", "fifo", "device link"] {
        for path in entries(&o.cache_dir) {
            if !replace_entry(&path, kind) {
                eprintln!("skipped: cannot make a {kind} here");
                return;
            }
            let (r, corrupt) = build_within_a_minute(chain(1, &runs), &o);
            assert!(r.ok, "{kind} at {}", path.display());
            let values: Vec<i64> = r.nodes.iter().map(|n| value(&r, &n.name)).collect();
            assert_eq!(values, expected, "{kind} at {}", path.display());
            assert!(
                corrupt.iter().any(|(_, d)| d.contains("not a file")),
                "{kind} at {}: {corrupt:?}",
                path.display()
            );
            assert!(
                std::fs::symlink_metadata(&path).is_ok_and(|m| m.file_type().is_file()),
                "{kind} at {} is a file again",
                path.display()
            );
            let (again, corrupt) = build_collecting(chain(1, &runs), &o);
            assert!(corrupt.is_empty(), "{kind}: {corrupt:?}");
            assert!(
                again.nodes.iter().all(|n| n.state == NodeState::Cached),
                "{kind} at {}: {:?}",
                path.display(),
                states(&again)
            );
        }
    }
}

#[test]
fn a_deleted_cache_entry_is_rebuilt_with_reason_cache_missing() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 1);
    let runs = Runs::default();
    let r = run(chain(1, &runs), &o);
    let s_out = r.node("s").unwrap().output.unwrap();
    std::fs::remove_file(o.cache_dir.join("objects").join(s_out.to_hex())).unwrap();
    let r2 = run(chain(1, &runs), &o);
    assert_eq!(state(&r2, "s"), NodeState::Ran);
    assert_eq!(r2.node("s").unwrap().reason, RebuildReason::CacheMissing);
    assert_eq!(state(&r2, "m"), NodeState::CutOff);
}

#[test]
fn gc_keeps_referenced_entries_and_removes_the_rest() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 1);
    let runs = Runs::default();
    run(chain(1, &runs), &o);
    let r = run(chain(4, &runs), &o); // a = 4, s = 6, m = 0, t = 10: objects 1 and 3 stale
    let keep = LockFile::from_report(&r);
    std::fs::write(o.cache_dir.join("objects").join(".tmp-stray"), b"x").unwrap();
    let stats = gc(&o.cache_dir, &[keep]).unwrap();
    assert_eq!(
        stats.removed,
        2 + 3 + 1,
        "objects 1 and 3, actions of a(1), s(1+2), m(3), the stray temp"
    );
    assert_eq!(stats.kept, 5 + 5);
    runs.reset();
    let again = run(chain(4, &runs), &o);
    assert_eq!(runs.total(), 0);
    assert!(again.nodes.iter().all(|n| n.state == NodeState::Cached));
    let old = run(chain(1, &runs), &o);
    assert_eq!(state(&old, "a"), NodeState::Ran);
    // gc from the last build when no lock file is at hand.
    let last = engine::gc::last_build(&o.cache_dir, &o.record).unwrap();
    assert_eq!(
        last,
        LockFile {
            outputs: Default::default(),
            ..LockFile::from_report(&old)
        }
    );
}

#[test]
fn gc_keeps_the_last_build_of_every_record_sharing_the_cache_until_one_is_forgotten() {
    let dir = tempfile::tempdir().unwrap();
    let a = opts(dir.path(), 1);
    let b = BuildOptions {
        record: "b".into(),
        ..opts(dir.path(), 1)
    };
    let runs = Runs::default();
    run(chain(1, &runs), &a);
    run(chain(4, &runs), &b);
    // What builds kept at the root before records: ignored, and removed by gc.
    std::fs::write(a.cache_dir.join("manifest.bin"), b"an old manifest").unwrap();
    gc(&a.cache_dir, &[]).unwrap();
    assert!(!a.cache_dir.join("manifest.bin").exists());
    runs.reset();
    let again_a = run(chain(1, &runs), &a);
    let again_b = run(chain(4, &runs), &b);
    assert_eq!(runs.total(), 0, "gc kept both records' last builds");
    assert!(again_a.nodes.iter().all(|n| n.state == NodeState::Cached));
    assert!(again_b.nodes.iter().all(|n| n.state == NodeState::Cached));
    // Each record explains against its own last build, not the other's.
    let r = run(chain(5, &runs), &a);
    assert_eq!(r.node("a").unwrap().reason.to_string(), "value: 1 → 5");
    assert!(forget(&a.cache_dir, "b").unwrap());
    assert!(!forget(&a.cache_dir, "b").unwrap(), "already forgotten");
    assert!(forget(&a.cache_dir, "../b").is_err());
    assert!(gc(&a.cache_dir, &[]).unwrap().removed > 0);
    runs.reset();
    let r = run(chain(4, &runs), &b);
    assert_eq!(
        state(&r, "a"),
        NodeState::Ran,
        "b's entries went with its record"
    );
    assert_eq!(r.node("a").unwrap().reason, RebuildReason::NewNode);
}

#[test]
fn a_build_refuses_a_record_name_that_is_not_one_path_component() {
    let dir = tempfile::tempdir().unwrap();
    let o = BuildOptions {
        record: "../elsewhere".into(),
        ..opts(dir.path(), 1)
    };
    let e = build(chain(1, &Runs::default()), &o, &quiet).unwrap_err();
    assert!(e.to_string().contains("../elsewhere"), "{e}");
    assert!(!o.cache_dir.exists(), "nothing was created");
}

#[test]
fn clean_removes_the_cache_and_the_next_build_runs_everything() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 1);
    let runs = Runs::default();
    run(chain(1, &runs), &o);
    clean(&o.cache_dir).unwrap();
    assert!(!o.cache_dir.exists());
    clean(&o.cache_dir).unwrap();
    runs.reset();
    let r = run(chain(1, &runs), &o);
    assert_eq!(runs.total(), 5);
    assert!(r.nodes.iter().all(|n| n.reason == RebuildReason::NewNode));
}

#[test]
fn gc_and_clean_refuse_a_cache_in_use() {
    let dir = tempfile::tempdir().unwrap();
    let cache = dir.path().join("cache");
    engine::marker::claim(&cache).unwrap();
    let _held = engine::dirlock::DirLock::try_acquire(&cache)
        .unwrap()
        .unwrap();
    assert!(matches!(clean(&cache), Err(EngineError::Locked { .. })));
    assert!(matches!(gc(&cache, &[]), Err(EngineError::Locked { .. })));
    assert!(cache.exists());
}

#[test]
fn lock_file_text_is_sorted_round_trips_and_its_diff_names_the_changed_node() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 1);
    let runs = Runs::default();
    let l1 = LockFile::from_report(&run(chain(1, &runs), &o));
    let text = l1.to_text();
    assert_eq!(LockFile::parse(&text).unwrap(), l1);
    let positions: Vec<usize> = [
        "[nodes.a]",
        "[nodes.b]",
        "[nodes.m]",
        "[nodes.s]",
        "[nodes.t]",
    ]
    .iter()
    .map(|h| text.find(h).unwrap())
    .collect();
    assert!(positions.windows(2).all(|w| w[0] < w[1]), "{text}");
    let l2 = LockFile::from_report(&run(chain(2, &runs), &o)); // a 1 -> 2, s 3 -> 4, m 0 -> 1, t 10 -> 11
    let d = l1.diff(&l2);
    let a1 = l1.nodes["a"].output.short();
    let a2 = l2.nodes["a"].output.short();
    assert_eq!(d[0], format!("node `a`: output {a1}… → {a2}…"));
    assert_eq!(d.len(), 4, "{d:?}");
    assert!(l1.diff(&l1).is_empty());
}

#[test]
fn a_damaged_lock_file_is_refused_with_a_message() {
    assert!(
        LockFile::parse("format = 1\n[nodes.a]\nkey = \"zz\"\noutput = \"00\"\n")
            .unwrap_err()
            .contains("recipe.lock")
    );
    assert!(
        LockFile::parse("format = 99\n")
            .unwrap_err()
            .contains("format 99")
    );
    assert!(LockFile::parse("this is not toml").is_err());
    assert_eq!(
        LockFile::parse("format = 1\n").unwrap(),
        LockFile::default()
    );
}

struct WithParams(Params);
impl Operation for WithParams {
    fn kind(&self) -> &'static str {
        "with-params"
    }
    fn version(&self) -> u32 {
        1
    }
    fn params(&self) -> Params {
        self.0.clone()
    }
    fn run(&self, _: &dyn RunContext, _: &[Artifact]) -> Result<Output, OpError> {
        Ok(Output::new(Artifact::encode(&0i64)?))
    }
}

fn key_of(p: Params) -> Hash {
    let dir = tempfile::tempdir().unwrap();
    let mut g = BuildGraph::new();
    g.add_op("n", std::sync::Arc::new(WithParams(p)), &[])
        .unwrap();
    run(g, &opts(dir.path(), 1)).node("n").unwrap().key
}

#[test]
fn nan_is_rejected_and_negative_zero_and_map_order_do_not_change_the_key() {
    assert!(matches!(
        Params::new().with("x", f64::NAN),
        Err(ParamError::NaN { .. })
    ));
    let mut m1 = std::collections::BTreeMap::new();
    m1.insert("b".to_string(), Param::Float(-0.0));
    m1.insert("a".to_string(), Param::Int(1));
    let mut m2 = std::collections::BTreeMap::new();
    m2.insert("a".to_string(), Param::Int(1));
    m2.insert("b".to_string(), Param::Float(0.0));
    let k1 = key_of(
        Params::new()
            .with("z", -0.0)
            .unwrap()
            .with("m", m1)
            .unwrap(),
    );
    let k2 = key_of(Params::new().with("m", m2).unwrap().with("z", 0.0).unwrap());
    assert_eq!(k1, k2);
    assert_ne!(k1, key_of(Params::new().with("z", 1e-300).unwrap()));
}

#[test]
fn a_damaged_manifest_only_costs_explanations_never_results() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 2);
    let runs = Runs::default();
    run(chain(1, &runs), &o);
    std::fs::write(o.record_dir().join("manifest.bin"), b"not a manifest").unwrap();
    runs.reset();
    let r = run(chain(1, &runs), &o);
    assert_eq!(runs.total(), 0);
    assert!(r.nodes.iter().all(|n| n.state == NodeState::Cached));
    // The manifest is rewritten, so explanations are back on the next change.
    let r2 = run(chain(5, &runs), &o);
    assert_eq!(r2.node("a").unwrap().reason.to_string(), "value: 1 → 5");
}

#[test]
fn a_build_removes_the_temporaries_a_killed_write_left_in_the_cache() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 1);
    let runs = Runs::default();
    run(chain(1, &runs), &o);
    let before = entries(&o.cache_dir);
    for sub in ["objects", "actions"] {
        std::fs::write(o.cache_dir.join(sub).join(".tmp-killed"), b"half a write").unwrap();
    }
    // A build killed while it marked the folder as a cache.
    let marker = o.cache_dir.join(".tmp-CACHEDIR.TAG.Ab12Cd");
    std::fs::write(&marker, b"half a marker").unwrap();
    runs.reset();
    run(chain(1, &runs), &o);
    assert_eq!(entries(&o.cache_dir), before, "debris gone, entries kept");
    assert!(!marker.exists(), "the marker's temporary is gone");
    assert_eq!(runs.total(), 0, "nothing re-ran");
}
