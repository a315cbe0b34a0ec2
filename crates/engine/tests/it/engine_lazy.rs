//! Lazy outputs and emitted files a build leaves alone: what a build where nothing changed does
//! not read, and how a damaged entry it did not read is repaired once something needs it.

use crate::engine_support;

use engine::*;
use engine_support::*;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// `a` (lazy) → `s = a + extra` → `export` (lazy, emits `out/m.txt`).
fn graph(extra: i64, runs: &Runs) -> BuildGraph {
    let mut g = BuildGraph::new();
    let a = g.add_op("a", lazy(konst(40, runs)), &[]).unwrap();
    let s = g.add_op("s", add(extra, runs), &[a]).unwrap();
    let export = Arc::new(Export {
        stem: "m".into(),
        runs: runs.clone(),
    });
    g.add_op("export", lazy(export), &[s]).unwrap();
    g
}

/// The build's report and the nodes it said had a corrupt cache entry.
fn build_telling(g: BuildGraph, o: &BuildOptions) -> (BuildReport, Vec<String>) {
    let corrupt = Mutex::new(Vec::new());
    let r = build(g, o, &|e| {
        if let Event::CacheCorrupt { name, .. } = e {
            corrupt.lock().unwrap().push(name.clone());
        }
    })
    .unwrap();
    (r, corrupt.into_inner().unwrap())
}

fn object(o: &BuildOptions, r: &BuildReport, node: &str) -> PathBuf {
    let h = r.node(node).unwrap().output.unwrap();
    o.cache_dir.join("objects").join(h.to_hex())
}

/// Flips every byte of a file, keeping its length.
fn damage(path: &Path) {
    let bytes: Vec<u8> = std::fs::read(path).unwrap().iter().map(|b| !b).collect();
    std::fs::write(path, bytes).unwrap();
}

#[test]
fn a_build_where_nothing_changed_reads_no_lazy_output_and_leaves_the_files_alone() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 2);
    let runs = Runs::default();
    let first = run(graph(1, &runs), &o);
    let file = dir.path().join("work/out/m.txt");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "41\n");
    // Damaged entries a reading build would notice.
    damage(&object(&o, &first, "a"));
    damage(&object(&o, &first, "export"));
    runs.reset();
    let (r, corrupt) = build_telling(graph(1, &runs), &o);
    assert!(r.ok);
    assert_eq!(runs.total(), 0);
    assert_eq!(corrupt, Vec::<String>::new());
    assert!(r.nodes.iter().all(|n| n.state == NodeState::Cached));
    assert!(!r.artifact("a").unwrap().is_loaded());
    assert_eq!(r.output_files, first.output_files);
    assert!(r.node("export").unwrap().notes.is_empty());
}

#[test]
fn a_damaged_lazy_output_is_made_again_when_a_dependent_that_runs_reads_it() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 2);
    let runs = Runs::default();
    let first = run(graph(1, &runs), &o);
    damage(&object(&o, &first, "a"));
    let (r, corrupt) = build_telling(graph(2, &runs), &o);
    assert!(r.ok);
    assert_eq!(corrupt, ["a"]);
    assert_eq!(value(&r, "s"), 42);
    assert_eq!(state(&r, "a"), NodeState::Cached);
    let file = dir.path().join("work/out/m.txt");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "42\n");
    // Put back into the store: read by the next build that needs it, without a repair.
    let (r, corrupt) = build_telling(graph(3, &runs), &o);
    assert_eq!((value(&r, "s"), corrupt), (43, vec![]));
}

#[test]
fn an_emitted_file_changed_on_disk_is_written_again_from_the_output_even_if_damaged() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 1);
    let runs = Runs::default();
    let first = run(graph(1, &runs), &o);
    let file = dir.path().join("work/out/m.txt");
    damage(&object(&o, &first, "export"));
    std::fs::write(&file, "41\r\n").unwrap();
    runs.reset();
    let (r, corrupt) = build_telling(graph(1, &runs), &o);
    assert!(r.ok);
    assert_eq!(corrupt, ["export"]);
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "41\n");
    assert_eq!(r.node("export").unwrap().notes, ["rewrote out/m.txt"]);
    // Made again by the export alone: its cached input was read, not recomputed.
    assert_eq!(runs.total(), 1);
}
