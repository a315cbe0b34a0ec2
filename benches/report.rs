//! Rendering report.html and report.json of a ~1M-tet structured mesh (the pictures, histograms
//! and the seed's tables included).

use test_support::grid;

use criterion::{Criterion, criterion_group, criterion_main};
use georecipe::report::{ReportInput, render_both};
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
    g.bench_function("render_both_1m_tets", |b| {
        b.iter(|| render_both(black_box(&input)))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
