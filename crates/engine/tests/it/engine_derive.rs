//! Derivations: what a caller computes from a build's outputs, cached like a node's output,
//! outside the graph, and kept by `gc` as the record's last build.

use crate::engine_support;

use engine::*;
use engine_support::*;

/// `a` (lazy, 40) and `s = a + 1`.
fn graph(runs: &Runs) -> BuildGraph {
    let mut g = BuildGraph::new();
    let a = g.add_op("a", lazy(konst(40, runs)), &[]).unwrap();
    g.add_op("s", add(1, runs), &[a]).unwrap();
    g
}

/// `a + 100`, derived from a build's report (and saved into its record).
fn derive(o: &BuildOptions, r: &BuildReport, runs: &Runs) -> (i64, Artifact) {
    let d = Derivations::open(o).unwrap();
    let a = r.artifact("a").unwrap().clone();
    let out = d
        .derive("plus", add(100, runs).as_ref(), std::slice::from_ref(&a))
        .unwrap();
    d.save().unwrap();
    (decode_int(&out).unwrap(), a)
}

#[test]
fn a_derivation_runs_once_per_input_reads_no_lazy_input_when_cached_and_survives_gc() {
    let dir = tempfile::tempdir().unwrap();
    let o = opts(dir.path(), 2);
    let runs = Runs::default();
    let r = run(graph(&runs), &o);
    runs.reset();
    assert_eq!(derive(&o, &r, &runs).0, 140);
    assert_eq!(runs.total(), 1);
    // Cached: neither run nor its lazy input read.
    let r = run(graph(&runs), &o);
    runs.reset();
    let (v, a) = derive(&o, &r, &runs);
    assert_eq!((v, runs.total(), a.is_loaded()), (140, 0, false));
    // Not a node: the report and the lock file do not have it.
    assert!(r.node("plus").is_none());
    assert_eq!(LockFile::from_report(&r).nodes.len(), 2);
    // Kept by gc as part of the record's last build.
    let stats = gc(&o.cache_dir, &[]).unwrap();
    assert_eq!(stats.removed, 0, "{stats:?}");
    let (v, _) = derive(&o, &r, &runs);
    assert_eq!((v, runs.total()), (140, 0));
}
