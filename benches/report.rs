//! The report of a ~1M-tet structured mesh: computing its figures (the seed's tables, the
//! histograms and the two pictures: what a build caches by the mesh's hash) and rendering
//! report.html and report.json from them (what a build whose mesh did not change does).

use test_support::grid;

use criterion::{Criterion, criterion_group, criterion_main};
use georecipe::report::{MeshFacts, ReportInput, render_both};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let m = grid::grid(80, 80, 26);
    let input = ReportInput::from_mesh("grid", "grid.toml", &m);
    let (html, json) = render_both(&input);
    eprintln!(
        "{} tets: report.html {} bytes, report.json {} bytes",
        m.tets.len(),
        html.len(),
        json.len()
    );
    let mut g = c.benchmark_group("report");
    g.sample_size(10);
    g.bench_function("mesh_facts_1m_tets", |b| {
        b.iter(|| MeshFacts::of(black_box(&m), "grid"))
    });
    g.bench_function("render_both_from_facts_1m_tets", |b| {
        b.iter(|| render_both(black_box(&input)))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
