//! Checking generated recipes of 10 000 and 100 000 entries (regions at distinct points, curve
//! rules, names each written twice): the checker must grow near-linearly with the recipe, so the
//! per-entry time at the two sizes should agree within a small factor.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use georecipe::recipe::parse;
use std::hint::black_box;
use std::path::Path;
use test_support::big_recipe;

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("recipe_check");
    g.sample_size(10);
    type Gen = fn(usize) -> String;
    let cases: [(&str, Gen); 3] = [
        ("regions", big_recipe::regions),
        ("curve_rules", big_recipe::curve_rules),
        ("repeated_names", big_recipe::repeated_region_names),
    ];
    for (name, generate) in cases {
        for n in [10_000, 100_000] {
            let text = generate(n);
            g.throughput(Throughput::Elements(n as u64));
            g.bench_with_input(BenchmarkId::new(name, n), &text, |b, t| {
                b.iter(|| parse(Path::new("big.toml"), black_box(t)).map(|r| r.regions.len()))
            });
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
