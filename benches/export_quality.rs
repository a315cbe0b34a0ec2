//! Throughput of the exporters, the quality tables and the msh reader on a ~127k-tet layered box.

use test_support::export_support;

use criterion::{Criterion, criterion_group, criterion_main};
use export::quality::{table1, table2};
use export::{Format, export};
use geom::mesh::read::read_volume_msh;
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let mesh = export_support::layered_box(28, 27); // 28·28·27·6 = 127,008 tets
    let mut g = c.benchmark_group("export_127k_tets");
    g.sample_size(10);
    for f in [
        Format::Msh,
        Format::MshBinary,
        Format::Vtu,
        Format::Medit,
        Format::Inp,
    ] {
        g.bench_function(f.name(), |b| {
            b.iter(|| export(black_box(&mesh), "b", f).unwrap())
        });
    }
    g.bench_function("quality_tables", |b| {
        b.iter(|| (table1(black_box(&mesh)), table2(black_box(&mesh))))
    });
    let ascii = export(&mesh, "b", Format::Msh).unwrap().remove(0).1;
    let binary = export(&mesh, "b", Format::MshBinary).unwrap().remove(0).1;
    g.bench_function("read_volume_msh_ascii", |b| {
        b.iter(|| read_volume_msh(black_box(&ascii), "b").unwrap())
    });
    g.bench_function("read_volume_msh_binary", |b| {
        b.iter(|| read_volume_msh(black_box(&binary), "b").unwrap())
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
