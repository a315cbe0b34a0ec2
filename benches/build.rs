//! Whole builds of the shipped example: a full build from an empty cache versus a second build
//! with nothing changed (the target: the second costs under 5% of the first), and a rebuild after
//! one curve rule changed.

use criterion::{Criterion, criterion_group, criterion_main};
use engine::{self, BuildOptions};
use georecipe::{plan, recipe};
use std::path::Path;

fn build_once(recipe_path: &Path, text: &str, cache: &Path, out: &Path) -> engine::BuildReport {
    let r = recipe::parse(recipe_path, text).expect("the shipped recipe parses");
    let g = plan::lower(&r).expect("lowers");
    let opts = BuildOptions {
        cache_dir: cache.to_path_buf(),
        output_dir: out.to_path_buf(),
        staging_dir: None,
        jobs: 1,
        keep_going: true,
        record: engine::DEFAULT_RECORD.to_string(),
        read_only: false,
    };
    let report = engine::build(g, &opts, &|_| {}).expect("builds");
    assert!(report.ok);
    report
}

fn builds(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("recipes/didactic.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut g = c.benchmark_group("didactic");
    g.sample_size(10);
    g.bench_function("full build, empty cache, -j 1", |b| {
        b.iter_with_setup(
            || tempfile::tempdir().expect("temp dir"),
            |dir| {
                build_once(
                    &path,
                    &text,
                    &dir.path().join("cache"),
                    &dir.path().join("out"),
                );
            },
        )
    });
    let dir = tempfile::tempdir().unwrap();
    build_once(
        &path,
        &text,
        &dir.path().join("cache"),
        &dir.path().join("out"),
    );
    g.bench_function("second build, nothing changed", |b| {
        b.iter(|| {
            build_once(
                &path,
                &text,
                &dir.path().join("cache"),
                &dir.path().join("out"),
            )
        })
    });
    let edited = text.replace("\"F2\" = { size = 100.0 }", "\"F2\" = { size = 60.0 }");
    let mut flip = false;
    g.bench_function("rebuild after one curve rule changed", |b| {
        b.iter(|| {
            flip = !flip;
            build_once(
                &path,
                if flip { &edited } else { &text },
                &dir.path().join("cache"),
                &dir.path().join("out"),
            )
        })
    });
    g.finish();
}

criterion_group!(benches, builds);
criterion_main!(benches);
