//! A build where nothing changed, as a user runs it: the `recipe build --quiet` command on a
//! copy of a shipped recipe whose cache and outputs hold a full build, so the process start, the
//! engine, the report and the record are all in the time. The target: under 5% of the full
//! build. Groups: `noop/didactic` (the example: its full build and the no-op build) and
//! `noop/d` (refinement (d), the largest: the no-op build only; its full build takes seconds, so
//! it is timed by `benches/noop_rounds.sh`, see `benches/README.md`).
//!
//! Run with `cargo bench --bench noop`.

use criterion::{Criterion, criterion_group, criterion_main};
use std::path::Path;
use std::process::Command;

/// Copies the shipped recipe `rel` (relative to `recipes/`) and the didactic data into `dir`,
/// keeping their relative places.
fn copy_recipe(rel: &str, dir: &Path) {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("recipes");
    let data = dir.join("data/didactic");
    std::fs::create_dir_all(&data).expect("data dir");
    for e in std::fs::read_dir(src.join("data/didactic")).expect("recipes/data/didactic") {
        let e = e.expect("entry");
        std::fs::copy(e.path(), data.join(e.file_name())).expect("copy data");
    }
    let to = dir.join(rel);
    std::fs::create_dir_all(to.parent().expect("a parent")).expect("recipe dir");
    std::fs::copy(src.join(rel), to).expect("copy recipe");
}

/// `recipe build --quiet` of `dir/rel` with its cache in `dir/cache`.
fn build(dir: &Path, rel: &str) {
    let status = Command::new(env!("CARGO_BIN_EXE_recipe"))
        .args(["build", "--quiet", "--cache-dir", "cache", rel])
        .current_dir(dir)
        .env_remove("RECIPE_CACHE_DIR")
        .stderr(std::process::Stdio::null())
        .status()
        .expect("run recipe");
    assert!(status.success(), "the build of {rel} failed");
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("noop/didactic");
    g.sample_size(10);
    g.bench_function("full build, empty cache", |b| {
        b.iter_with_setup(
            || {
                let dir = tempfile::tempdir().expect("temp dir");
                copy_recipe("didactic.toml", dir.path());
                dir
            },
            |dir| build(dir.path(), "didactic.toml"),
        )
    });
    g.finish();
    for (group, rel) in [
        ("noop/didactic", "didactic.toml"),
        ("noop/d", "refinements/d.toml"),
    ] {
        let dir = tempfile::tempdir().expect("temp dir");
        copy_recipe(rel, dir.path());
        // The full build, then one build that writes the report of cached steps.
        build(dir.path(), rel);
        build(dir.path(), rel);
        let mut g = c.benchmark_group(group);
        g.sample_size(20);
        g.bench_function("nothing changed", |b| b.iter(|| build(dir.path(), rel)));
        g.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
