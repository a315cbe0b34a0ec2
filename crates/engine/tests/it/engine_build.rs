//! Incremental behaviour of the engine with toy operations: caching, reasons, early cutoff,
//! file inputs, dynamic expansion, failures, emitted files and the directory lock.

use crate::engine_support;

use engine::*;
use engine_support::*;
use std::sync::Mutex;

/// a = const(a_val); b = const(2); s = add(extra)(a, b); m = mod(3)(s); t = add(0)(m)
fn chain(a_val: i64, extra: i64, runs: &Runs) -> BuildGraph {
    let mut g = BuildGraph::new();
    let a = g.add_op("a", konst(a_val, runs), &[]).unwrap();
    let b = g.add_op("b", konst(2, runs), &[]).unwrap();
    let s = g.add_op("s", add(extra, runs), &[a, b]).unwrap();
    let m = g.add_op("m", modulo(3, runs), &[s]).unwrap();
    g.add_op("t", add(0, runs), &[m]).unwrap();
    g
}

#[test]
fn a_second_build_with_nothing_changed_runs_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 2);
    let runs = Runs::default();
    let r1 = run(chain(1, 0, &runs), &o);
    assert!(r1.ok);
    assert_eq!(runs.total(), 5);
    assert!(
        r1.nodes
            .iter()
            .all(|n| n.state == NodeState::Ran && n.reason == RebuildReason::NewNode)
    );
    assert_eq!(value(&r1, "t"), 0); // (1 + 2) % 3
    runs.reset();
    let r2 = run(chain(1, 0, &runs), &o);
    assert_eq!(runs.total(), 0);
    assert!(
        r2.nodes
            .iter()
            .all(|n| n.state == NodeState::Cached && n.reason == RebuildReason::UpToDate),
        "{:?}",
        states(&r2)
    );
    assert_eq!(value(&r2, "t"), 0);
    assert_eq!(r2.node("s").unwrap().counts.get("value"), Some(&3));
}

#[test]
fn changing_one_parameter_reruns_that_node_and_its_dependents_only_and_names_the_change() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 1);
    let runs = Runs::default();
    run(chain(1, 0, &runs), &o);
    runs.reset();
    let r = run(chain(1, 1, &runs), &o); // s: 3 -> 4, m: 0 -> 1, t: 0 -> 1
    assert_eq!(state(&r, "a"), NodeState::Cached);
    assert_eq!(state(&r, "b"), NodeState::Cached);
    assert_eq!(state(&r, "s"), NodeState::Ran);
    assert_eq!(state(&r, "m"), NodeState::Ran);
    assert_eq!(state(&r, "t"), NodeState::Ran);
    assert_eq!(runs.total(), 3);
    let reason = &r.node("s").unwrap().reason;
    assert_eq!(
        *reason,
        RebuildReason::ParamsChanged(vec![ParamChange {
            path: "extra".into(),
            old: Some("0".into()),
            new: Some("1".into())
        }])
    );
    assert_eq!(reason.to_string(), "extra: 0 → 1");
    assert_eq!(
        r.node("m").unwrap().reason,
        RebuildReason::UpstreamChanged {
            inputs: vec!["s".into()]
        }
    );
    assert_eq!(
        r.node("m").unwrap().reason.to_string(),
        "upstream output changed: s"
    );
}

#[test]
fn a_rerun_that_yields_the_same_output_cuts_off_its_dependents() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 2);
    let runs = Runs::default();
    run(chain(1, 0, &runs), &o); // s = 3, m = 0
    runs.reset();
    let r = run(chain(4, 0, &runs), &o); // a: 4, s = 6, m = 0 again
    assert_eq!(state(&r, "a"), NodeState::Ran);
    assert_eq!(state(&r, "s"), NodeState::Ran);
    assert_eq!(state(&r, "m"), NodeState::Ran);
    assert_eq!(state(&r, "t"), NodeState::CutOff);
    assert_eq!(state(&r, "b"), NodeState::Cached);
    assert_eq!(runs.total(), 3, "t must not run");
    assert_eq!(r.node("a").unwrap().reason.to_string(), "value: 1 → 4");
}

#[test]
fn an_operation_version_bump_reruns_with_the_version_as_reason() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 1);
    let runs = Runs::default();
    let g = |v| {
        let mut g = BuildGraph::new();
        let a = g.add_op("a", konst(5, &runs), &[]).unwrap();
        g.add_op("x", add_v(1, v, &runs), &[a]).unwrap();
        g
    };
    run(g(1), &o);
    let r = run(g(2), &o);
    assert_eq!(
        r.node("x").unwrap().reason,
        RebuildReason::VersionChanged { old: 1, new: 2 }
    );
    assert_eq!(state(&r, "a"), NodeState::Cached);
}

#[test]
fn touching_a_file_without_changing_it_reruns_nothing_and_changing_it_names_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 2);
    let input = dir.path().join("top.txt");
    std::fs::write(&input, "7\n").unwrap();
    let runs = Runs::default();
    let g = |runs: &Runs| {
        let mut g = BuildGraph::new();
        let f = g.add_file("file:top", input.clone()).unwrap();
        let x = g.add_op("x", add(1, runs), &[f]).unwrap();
        let y = g.add_op("y", modulo(2, runs), &[x]).unwrap();
        g.add_op("z", add(0, runs), &[y]).unwrap();
        g
    };
    let r1 = run(g(&runs), &o);
    assert_eq!(value(&r1, "x"), 8);
    runs.reset();
    // Touch: rewrite the same bytes (new mtime).
    std::thread::sleep(std::time::Duration::from_millis(20));
    std::fs::write(&input, "7\n").unwrap();
    let r2 = run(g(&runs), &o);
    assert_eq!(runs.total(), 0);
    assert!(
        r2.nodes.iter().all(|n| n.state == NodeState::Cached),
        "{:?}",
        states(&r2)
    );
    // Change: 9 -> x = 10, y = 0 (was 0): y re-runs, z is cut off.
    std::fs::write(&input, "9\n").unwrap();
    let r3 = run(g(&runs), &o);
    let f = r3.node("file:top").unwrap();
    assert_eq!(f.state, NodeState::Ran);
    assert_eq!(
        f.reason,
        RebuildReason::InputFileChanged {
            path: input.display().to_string()
        }
    );
    assert_eq!(state(&r3, "x"), NodeState::Ran);
    assert_eq!(
        r3.node("x").unwrap().reason,
        RebuildReason::UpstreamChanged {
            inputs: vec!["file:top".into()]
        }
    );
    assert_eq!(state(&r3, "y"), NodeState::Ran);
    assert_eq!(state(&r3, "z"), NodeState::CutOff);
    assert_eq!(runs.total(), 2);
}

#[test]
fn a_missing_input_file_fails_its_node_with_the_path_and_skips_dependents() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 1);
    let runs = Runs::default();
    let mut g = BuildGraph::new();
    let missing = dir.path().join("nope.ts");
    let f = g.add_file("file:nope", missing.clone()).unwrap();
    g.add_op("x", add(1, &runs), &[f]).unwrap();
    let r = run(g, &o);
    assert!(!r.ok);
    let n = r.node("file:nope").unwrap();
    assert_eq!(n.state, NodeState::Failed);
    assert!(
        n.error
            .as_deref()
            .unwrap()
            .contains(&missing.display().to_string())
    );
    assert_eq!(state(&r, "x"), NodeState::Skipped);
}

fn split_graph(n: i64, runs: &Runs, cascade: bool) -> BuildGraph {
    let mut g = BuildGraph::new();
    let c = g.add_op("count", konst(n, runs), &[]).unwrap();
    g.set_expander(
        c,
        std::sync::Arc::new(Split {
            runs: runs.clone(),
            cascade,
        }),
    );
    g
}

#[test]
fn an_expander_adds_nodes_that_are_cached_next_time_and_follow_its_input() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 2);
    let runs = Runs::default();
    let events = Mutex::new(Vec::new());
    let r1 = build(split_graph(3, &runs, false), &o, &|e| {
        if let Event::Expanded { by, added } = e {
            events.lock().unwrap().push((by.clone(), *added));
        }
    })
    .unwrap();
    assert!(r1.ok);
    assert_eq!(events.into_inner().unwrap(), vec![("count".to_string(), 4)]);
    let names: Vec<&str> = r1.nodes.iter().map(|n| n.name.as_str()).collect();
    assert_eq!(names, vec!["count", "part:0", "part:1", "part:2", "join"]);
    assert_eq!(value(&r1, "join"), 3 + 4 + 5);
    assert_eq!(runs.total(), 5);
    runs.reset();
    let r2 = run(split_graph(3, &runs, false), &o);
    assert_eq!(runs.total(), 0);
    assert!(r2.nodes.iter().all(|n| n.state == NodeState::Cached));
    let lock2 = LockFile::from_report(&r2);
    assert!(lock2.nodes.contains_key("part:2"));
    // Fewer parts: part:2 disappears from report and lock.
    let r3 = run(split_graph(2, &runs, false), &o);
    assert!(r3.node("part:2").is_none());
    let lock3 = LockFile::from_report(&r3);
    assert!(!lock3.nodes.contains_key("part:2"));
    assert_eq!(value(&r3, "join"), 2 + 3);
    assert!(
        lock2
            .diff(&lock3)
            .iter()
            .any(|l| l.starts_with("node `part:2` removed"))
    );
}

#[test]
fn expansion_can_cascade_through_nodes_it_added() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 3);
    let runs = Runs::default();
    let r = run(split_graph(2, &runs, true), &o);
    assert!(r.ok);
    assert_eq!(value(&r, "sub:0"), 2 + 100);
    let r2 = run(split_graph(2, &runs, true), &o);
    assert_eq!(state(&r2, "sub:0"), NodeState::Cached);
}

#[test]
fn a_failing_expander_fails_its_node_and_adds_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 1);
    let runs = Runs::default();
    let r = run(split_graph(-1, &runs, false), &o);
    assert!(!r.ok);
    let c = r.node("count").unwrap();
    assert_eq!(c.state, NodeState::Failed);
    assert!(c.error.as_deref().unwrap().contains("negative"));
    assert_eq!(r.nodes.len(), 1);
}

#[test]
fn a_failing_node_does_not_stop_an_independent_branch_and_its_dependents_are_skipped() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 2);
    let runs = Runs::default();
    let mut g = BuildGraph::new();
    let bad = g.add_op("bad", fail(&runs), &[]).unwrap();
    let d1 = g.add_op("after-bad", add(1, &runs), &[bad]).unwrap();
    g.add_op("after-after", add(1, &runs), &[d1]).unwrap();
    let good = g.add_op("good", konst(4, &runs), &[]).unwrap();
    g.add_op("after-good", add(1, &runs), &[good]).unwrap();
    let r = run(g, &o);
    assert!(!r.ok);
    assert_eq!(state(&r, "bad"), NodeState::Failed);
    assert_eq!(
        r.node("bad").unwrap().error.as_deref(),
        Some("toy failure: always fails")
    );
    assert_eq!(state(&r, "after-bad"), NodeState::Skipped);
    assert_eq!(
        r.node("after-bad").unwrap().reason,
        RebuildReason::InputFailed {
            inputs: vec!["bad".into()]
        }
    );
    assert_eq!(state(&r, "after-after"), NodeState::Skipped);
    assert_eq!(state(&r, "after-good"), NodeState::Ran);
    assert_eq!(value(&r, "after-good"), 5);
    let json = r.to_json();
    assert_eq!(json["ok"], false);
    assert!(!LockFile::from_report(&r).nodes.contains_key("bad"));
}

struct Panicky;
impl Operation for Panicky {
    fn kind(&self) -> &'static str {
        "panicky"
    }
    fn version(&self) -> u32 {
        1
    }
    fn params(&self) -> Params {
        Params::new()
    }
    fn run(&self, _: &dyn RunContext, _: &[Artifact]) -> Result<Output, OpError> {
        panic!("boom at (1, 2, 3)")
    }
}

#[test]
fn a_panicking_operation_is_reported_as_a_failed_node() {
    let dir = tempfile::tempdir().unwrap();
    let runs = Runs::default();
    let mut g = BuildGraph::new();
    g.add_op("p", std::sync::Arc::new(Panicky), &[]).unwrap();
    g.add_op("k", konst(1, &runs), &[]).unwrap();
    let r = run(g, &opts(dir.path(), 2));
    assert_eq!(state(&r, "p"), NodeState::Failed);
    assert!(
        r.node("p")
            .unwrap()
            .error
            .as_deref()
            .unwrap()
            .contains("boom at (1, 2, 3)")
    );
    assert_eq!(state(&r, "k"), NodeState::Ran);
}

#[test]
fn without_keep_going_a_failure_stops_further_dispatch() {
    let dir = tempfile::tempdir().unwrap();
    let mut o = opts(dir.path(), 1);
    o.keep_going = false;
    let runs = Runs::default();
    let mut g = BuildGraph::new();
    g.add_op("a-bad", fail(&runs), &[]).unwrap();
    g.add_op("z-good", konst(1, &runs), &[]).unwrap();
    let r = run(g, &o);
    assert!(!r.ok);
    assert_eq!(state(&r, "z-good"), NodeState::Skipped);
    assert_eq!(
        r.node("z-good").unwrap().reason,
        RebuildReason::BuildStopped
    );
}

#[test]
fn a_node_that_failed_in_the_build_before_fails_again_without_running() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 2);
    let runs = Runs::default();
    let graph = |runs: &Runs| {
        let mut g = BuildGraph::new();
        g.add_op("bad", fail(runs), &[]).unwrap();
        g.add_op("good", konst(4, runs), &[]).unwrap();
        g
    };
    let lock = lock_cache(&o, &|_| {}).unwrap();
    let first = build_holding(graph(&runs), &o, &lock, &|_| {}).unwrap();
    assert_eq!(runs.total(), 2);
    let bad = first.node("bad").unwrap();
    let retry = Retry {
        failed_before: std::collections::BTreeMap::from([(bad.key, "as before".to_string())]),
        ..Retry::default()
    };
    runs.reset();
    let again = build_again(graph(&runs), &o, &lock, &retry, &|_| {}).unwrap();
    // `good` is cached; `bad`, of the same key, fails with the error given, unrun.
    assert_eq!(runs.total(), 0);
    assert_eq!(state(&again, "bad"), NodeState::Failed);
    assert_eq!(
        again.node("bad").unwrap().error.as_deref(),
        Some("as before")
    );
    assert_eq!(state(&again, "good"), NodeState::Cached);
    // Without the memo, it runs again (failures are not cached).
    runs.reset();
    let plain = build_holding(graph(&runs), &o, &lock, &|_| {}).unwrap();
    assert_eq!(runs.total(), 1);
    assert_eq!(state(&plain, "bad"), NodeState::Failed);
}

#[test]
fn emitted_files_are_written_rewritten_when_deleted_and_locked() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 2);
    let runs = Runs::default();
    let g = |v: i64, runs: &Runs| {
        let mut g = BuildGraph::new();
        let a = g.add_op("a", konst(v, runs), &[]).unwrap();
        g.add_op(
            "export",
            std::sync::Arc::new(Export {
                stem: "m".into(),
                runs: runs.clone(),
            }),
            &[a],
        )
        .unwrap();
        g
    };
    let r1 = run(g(41, &runs), &o);
    let out = dir.path().join("work/out/m.txt");
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "41\n");
    let h = Hash::of(b"41\n");
    assert_eq!(r1.output_files.get("out/m.txt"), Some(&h));
    // The report keeps the other artifacts, not the emitting node's: its bytes are on disk.
    assert!(r1.artifact("a").is_some());
    assert!(r1.artifact("export").is_none());
    let lock = LockFile::from_report(&r1);
    assert_eq!(lock.outputs.get("out/m.txt"), Some(&h));
    assert!(lock.to_text().contains("\"out/m.txt\""));
    // No temporary file left beside it.
    let names: Vec<_> = std::fs::read_dir(out.parent().unwrap())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names, vec![std::ffi::OsString::from("m.txt")]);
    // Deleted: the cached node rewrites it without running.
    std::fs::remove_file(&out).unwrap();
    runs.reset();
    let r2 = run(g(41, &runs), &o);
    assert_eq!(runs.total(), 0);
    assert_eq!(state(&r2, "export"), NodeState::Cached);
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "41\n");
    // Altered on disk: rewritten too.
    std::fs::write(&out, "garbage").unwrap();
    run(g(41, &runs), &o);
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "41\n");
    // New content: new hash in the lock, named by the diff.
    let r3 = run(g(42, &runs), &o);
    let lock3 = LockFile::from_report(&r3);
    let d = lock.diff(&lock3);
    assert!(
        d.iter().any(|l| l.starts_with("output file `out/m.txt`:")),
        "{d:?}"
    );
    assert!(
        d.iter().any(|l| l.starts_with("node `export`: output")),
        "{d:?}"
    );
}

#[test]
fn a_second_concurrent_build_waits_for_the_lock_then_succeeds() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 1);
    let held = engine::dirlock::DirLock::try_acquire(&o.cache_dir)
        .unwrap()
        .expect("lock free");
    let runs = Runs::default();
    let waited = Mutex::new(None);
    let releaser = std::thread::spawn(move || {
        std::thread::sleep(std::time::Duration::from_millis(300));
        drop(held);
    });
    let r = build(chain(1, 0, &runs), &o, &|e| {
        if let Event::WaitingForLock { path } = e {
            *waited.lock().unwrap() = Some(path.clone());
        }
    })
    .unwrap();
    releaser.join().unwrap();
    assert!(r.ok);
    assert_eq!(waited.into_inner().unwrap(), Some(o.cache_dir.join("lock")));
}

#[test]
fn events_report_start_progress_and_finish_of_running_nodes() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 2);
    let runs = Runs::default();
    let events = Mutex::new(Vec::new());
    build(chain(1, 0, &runs), &o, &|e| {
        events.lock().unwrap().push(e.clone())
    })
    .unwrap();
    let ev = events.into_inner().unwrap();
    let started = ev
        .iter()
        .filter(|e| matches!(e, Event::Started { .. }))
        .count();
    let finished = ev
        .iter()
        .filter(|e| matches!(e, Event::Finished(_)))
        .count();
    let progress = ev
        .iter()
        .filter(|e| matches!(e, Event::Progress { name, done: 1, total: 1 } if name == "s"))
        .count();
    assert_eq!((started, finished, progress), (5, 5, 1));
    let events = Mutex::new(Vec::new());
    build(chain(1, 0, &runs), &o, &|e| {
        events.lock().unwrap().push(e.clone())
    })
    .unwrap();
    assert!(
        !events
            .into_inner()
            .unwrap()
            .iter()
            .any(|e| matches!(e, Event::Started { .. }))
    );
}

#[test]
fn the_dot_rendering_shows_expanded_nodes_with_their_state() {
    let dir = tempfile::tempdir().unwrap();
    let runs = Runs::default();
    let r = run(split_graph(2, &runs, false), &opts(dir.path(), 1));
    let dot = r.to_dot();
    assert!(dot.starts_with("digraph build {"));
    assert!(
        dot.contains("\"part:1\" [label=\"part:1\\nadd · ran\""),
        "{dot}"
    );
    assert!(dot.contains("\"count\" -> \"part:1\";"));
    assert!(dot.contains("\"part:1\" -> \"join\";"));
    let json = r.to_json();
    assert_eq!(json["nodes"][0]["name"], "count");
    assert_eq!(json["nodes"][0]["state"], "ran");
    assert_eq!(json["nodes"][0]["reason"], "new node");
    assert_eq!(json["nodes"][0]["counts"]["value"], 2);
}

#[test]
fn duplicate_names_and_foreign_inputs_are_refused_when_building_the_graph() {
    let runs = Runs::default();
    let mut g = BuildGraph::new();
    g.add_op("a", konst(1, &runs), &[]).unwrap();
    assert_eq!(
        g.add_op("a", konst(2, &runs), &[]).unwrap_err(),
        GraphError::DuplicateName("a".into())
    );
    assert!(matches!(
        g.add_file("a", "x".into()),
        Err(GraphError::DuplicateName(_))
    ));
    let mut other = BuildGraph::new();
    other.add_op("x", konst(1, &runs), &[]).unwrap();
    let foreign = other.add_op("y", konst(1, &runs), &[]).unwrap();
    assert!(matches!(
        g.add_op("b", konst(1, &runs), &[foreign]),
        Err(GraphError::UnknownInput { .. })
    ));
}

#[test]
fn nodes_sharing_a_key_are_computed_once_and_share_their_state() {
    for jobs in [1, 3] {
        let dir = tempfile::tempdir().unwrap();
        let runs = Runs::default();
        let g = || {
            let mut g = BuildGraph::new();
            for name in ["twin-a", "twin-b", "twin-c"] {
                g.add_op(name, add(13, &runs), &[]).unwrap();
            }
            g
        };
        let r = run(g(), &opts(dir.path(), jobs));
        assert_eq!(runs.total(), 1, "jobs = {jobs}");
        assert!(
            r.nodes.iter().all(|n| n.state == NodeState::Ran),
            "jobs = {jobs}: {:?}",
            states(&r)
        );
        let r2 = run(g(), &opts(dir.path(), jobs));
        assert!(r2.nodes.iter().all(|n| n.state == NodeState::Cached));
        assert_eq!(runs.total(), 1);
    }
}

/// A graph `const(5) → add`, where `add` runs `f` under `version`.
fn changed_add(version: u32, f: fn(&Params, &[i64]) -> Result<i64, String>) -> BuildGraph {
    let runs = Runs::default();
    let mut g = BuildGraph::new();
    let c = g.add_op("c", konst(5, &runs), &[]).unwrap();
    let op = Toy {
        kind: "add",
        version,
        params: Params::new(),
        f,
        runs,
    };
    g.add_op("sum", std::sync::Arc::new(op), &[c]).unwrap();
    g
}

#[test]
fn an_output_that_changes_under_the_same_key_is_named_as_a_missing_version_bump() {
    let build = |g: BuildGraph| {
        let dir = tempfile::tempdir().unwrap();
        LockFile::from_report(&run(g, &opts(dir.path(), 1)))
    };
    let old = build(changed_add(1, |_, v| Ok(v[0] + 1)));
    // The same version with other code: the same key, another output.
    let forgot = build(changed_add(1, |_, v| Ok(v[0] + 2)));
    let stale = old.unversioned_changes(&forgot);
    assert_eq!(stale.len(), 1, "{stale:?}");
    assert!(stale[0].starts_with("node `sum`") && stale[0].contains("version bump"));
    assert!(old.diff(&forgot).iter().any(|l| l.contains("version bump")));
    // With the version bumped, the key changes too: an ordinary difference.
    let bumped = build(changed_add(2, |_, v| Ok(v[0] + 2)));
    assert!(old.unversioned_changes(&bumped).is_empty());
    assert!(
        old.diff(&bumped)
            .iter()
            .any(|l| l.starts_with("node `sum`: output"))
    );
}

/// `a → s` and `b → u`, independent.
fn two_chains(runs: &Runs) -> BuildGraph {
    let mut g = BuildGraph::new();
    let a = g.add_op("a", konst(1, runs), &[]).unwrap();
    let b = g.add_op("b", konst(2, runs), &[]).unwrap();
    g.add_op("s", add(10, runs), &[a]).unwrap();
    g.add_op("u", add(20, runs), &[b]).unwrap();
    g
}

fn focused(names: &[&str]) -> Retry {
    Retry {
        focus: names.iter().map(|n| n.to_string()).collect(),
        ..Retry::default()
    }
}

#[test]
fn a_focused_build_runs_only_what_the_named_nodes_need_for_any_number_of_jobs() {
    for jobs in [1, 4] {
        let dir = tempfile::tempdir().unwrap();
        let o = opts(dir.path(), jobs);
        let runs = Runs::default();
        let lock = lock_cache(&o, &|_| {}).unwrap();
        let r = build_again(two_chains(&runs), &o, &lock, &focused(&["s"]), &quiet).unwrap();
        assert_eq!(runs.total(), 2, "only a and s ran");
        assert_eq!(value(&r, "s"), 11);
        for name in ["b", "u"] {
            assert_eq!(state(&r, name), NodeState::Skipped);
            assert_eq!(r.node(name).unwrap().reason, RebuildReason::Unfocused);
        }
        assert!(!r.ok, "a build that left nodes out is not whole");
        // The whole build after it runs only what the focused one left out.
        runs.reset();
        let whole = build_holding(two_chains(&runs), &o, &lock, &quiet).unwrap();
        assert!(whole.ok);
        assert_eq!(runs.total(), 2, "b and u ran; a and s were cached");
        assert_eq!(state(&whole, "s"), NodeState::Cached);
    }
}

#[test]
fn a_focused_build_runs_the_expansion_that_adds_a_named_node() {
    for jobs in [1, 4] {
        let dir = tempfile::tempdir().unwrap();
        let o = opts(dir.path(), jobs);
        let runs = Runs::default();
        let mut g = split_graph(3, &runs, false);
        g.add_op("other", konst(7, &runs), &[]).unwrap();
        let lock = lock_cache(&o, &|_| {}).unwrap();
        let r = build_again(g, &o, &lock, &focused(&["part:1"]), &quiet).unwrap();
        // `count` expands (the named node exists only after it), then `part:1` runs.
        assert_eq!(runs.total(), 2);
        assert_eq!(value(&r, "part:1"), 3 + 1);
        for name in ["part:0", "part:2", "join", "other"] {
            assert_eq!(
                r.node(name).unwrap().reason,
                RebuildReason::Unfocused,
                "{name}"
            );
        }
    }
}

#[test]
fn a_focused_build_whose_named_node_fails_again_stops_there() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 2);
    let runs = Runs::default();
    let mut g = two_chains(&runs);
    let s = g.node("s").unwrap();
    g.add_op("bad", fail(&runs), &[s]).unwrap();
    let lock = lock_cache(&o, &|_| {}).unwrap();
    let r = build_again(g, &o, &lock, &focused(&["bad"]), &quiet).unwrap();
    assert_eq!(state(&r, "bad"), NodeState::Failed);
    assert_eq!(runs.total(), 3, "a, s and bad ran; b and u did not");
    assert_eq!(r.node("u").unwrap().reason, RebuildReason::Unfocused);
}
